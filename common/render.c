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

void render_use_threads(int n) {
#ifdef _OPENMP
    if (n > 0)
        omp_set_num_threads(n);
#else
    (void)n;
#endif
}

static void print_progress(int done, int pieces, double started) {
    double elapsed = clock_seconds() - started;
    double left = done > 0 ? elapsed * (pieces - done) / done : 0.0;
    fprintf(stderr, "\rrendering: %3d%%  %6.1f s elapsed, about %6.1f s left ", 100 * done / pieces,
            elapsed, left);
    fflush(stderr);
}

/* Renders row j of img, one ray through each pixel centre. */
static void render_row(const struct render_job *job, struct image *img, int j) {
    for (int i = 0; i < img->width; i++) {
        ray r = camera_ray(job->camera, i, j);
        uint64_t cost_before = render_thread_cost();
        stats_thread.primary_rays++;
        image_set(img, i, j, job->trace(job->world, &r));
        if (job->heatmap != NULL) {
            uint64_t cost = render_thread_cost() - cost_before;
            image_set(job->heatmap, i, j, heatmap_colour(cost > UINT32_MAX ? UINT32_MAX : (uint32_t)cost));
        }
    }
    stats_thread.pixels += (uint64_t)img->width;
    stats_thread.camera_rays_max = 1;
}

/* Renders block number `block` (counted along the rows of blocks) with the job's sampler. */
static void render_block(const struct render_job *job, struct image *img, int block) {
    int across = (img->width + ANTIALIAS_BLOCK - 1) / ANTIALIAS_BLOCK;
    int left = block % across * ANTIALIAS_BLOCK, top = block / across * ANTIALIAS_BLOCK;
    int right = left + ANTIALIAS_BLOCK < img->width ? left + ANTIALIAS_BLOCK : img->width;
    int bottom = top + ANTIALIAS_BLOCK < img->height ? top + ANTIALIAS_BLOCK : img->height;
    job->sampler->block(job, img, left, top, right, bottom);
}

void render_image(const struct render_job *job, struct image *img, struct stats *total) {
    /* The work is shared out in pieces: rows, or the sampler's blocks. */
    int pieces = img->height;
    if (job->sampler != NULL)
        pieces = ((img->width + ANTIALIAS_BLOCK - 1) / ANTIALIAS_BLOCK) *
                 ((img->height + ANTIALIAS_BLOCK - 1) / ANTIALIAS_BLOCK);
    int pieces_done = 0;
    double started = clock_seconds();
    bool progress = job->progress;
#ifdef _OPENMP
    int threads = job->threads > 0 ? job->threads : omp_get_max_threads();
#endif

#pragma omp parallel num_threads(threads)
    {
        stats_reset_thread();
#pragma omp for schedule(dynamic, 1)
        for (int piece = 0; piece < pieces; piece++) {
            if (job->sampler == NULL)
                render_row(job, img, piece);
            else
                render_block(job, img, piece);
            int done;
#pragma omp atomic capture
            done = ++pieces_done;
            bool first_thread = true;
#ifdef _OPENMP
            first_thread = omp_get_thread_num() == 0;
#endif
            if (progress && first_thread)
                print_progress(done, pieces, started);
        }
#pragma omp critical
        stats_add(total, &stats_thread);
    }
    if (progress) {
        print_progress(pieces, pieces, started);
        fputc('\n', stderr);
    }
}
