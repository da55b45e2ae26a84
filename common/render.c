/* render.c: the parallel pixel loop with progress report and per-pixel cost (chapter 1). */
#include "render.h"

#include "clock.h"
#include "heatmap.h"

#include <stdio.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

uint64_t render_thread_cost(void) {
    const struct stats *s = &stats_thread;
    return s->node_visits + s->box_tests + s->sphere_tests + s->triangle_tests + s->plane_tests;
}

static void print_progress(int rows_done, int rows, double started) {
    double elapsed = clock_seconds() - started;
    double left = rows_done > 0 ? elapsed * (rows - rows_done) / rows_done : 0.0;
    fprintf(stderr, "\rrendering: %3d%%  %6.1f s elapsed, about %6.1f s left ", 100 * rows_done / rows,
            elapsed, left);
    fflush(stderr);
}

void render_image(const struct render_job *job, struct image *img, struct stats *total) {
    const struct camera *cam = job->camera;
    int rows_done = 0;
    double started = clock_seconds();
    bool progress = job->progress;
#ifdef _OPENMP
    int threads = job->threads > 0 ? job->threads : omp_get_max_threads();
#endif

#pragma omp parallel num_threads(threads)
    {
        stats_reset_thread();
#pragma omp for schedule(dynamic, 1)
        for (int j = 0; j < img->height; j++) {
            for (int i = 0; i < img->width; i++) {
                ray r = camera_ray(cam, i, j);
                uint64_t cost_before = render_thread_cost();
                stats_thread.primary_rays++;
                image_set(img, i, j, job->trace(job->world, &r));
                if (job->heatmap != NULL) {
                    uint64_t cost = render_thread_cost() - cost_before;
                    image_set(job->heatmap, i, j, heatmap_colour(cost > UINT32_MAX ? UINT32_MAX : (uint32_t)cost));
                }
            }
            int done;
#pragma omp atomic capture
            done = ++rows_done;
            bool first_thread = true;
#ifdef _OPENMP
            first_thread = omp_get_thread_num() == 0;
#endif
            if (progress && first_thread)
                print_progress(done, img->height, started);
        }
#pragma omp critical
        stats_add(total, &stats_thread);
    }
    if (progress) {
        print_progress(img->height, img->height, started);
        fputc('\n', stderr);
    }
}
