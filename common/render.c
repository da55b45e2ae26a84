/* render.c: the parallel pixel loop with progress report and per-pixel cost (chapter 1). */
#include "render.h"

#include "clock.h"
#include "heatmap.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

uint64_t render_thread_cost(void) {
    const struct stats *s = &stats_thread;
    return s->node_visits + s->instance_node_visits + s->box_tests + s->sphere_tests + s->triangle_tests + s->plane_tests;
}

void render_use_threads(int n) {
#ifdef _OPENMP
    if (n > 0)
        omp_set_num_threads(n);
#else
    (void)n;
#endif
}

/* ---- progress --------------------------------------------------------------------------------------
 * A thread of its own reports the progress while the pixel loop runs, so that a report comes on time
 * however long one row, block or pixel takes: on a terminal a bar redrawn every
 * RENDER_PROGRESS_BAR_SECONDS, elsewhere (a pipe, a log file) a line every RENDER_PROGRESS_SECONDS. The
 * time left is the time so far times the pieces left over the pieces done. */

#define RENDER_PROGRESS_SECONDS 5.0       /* a line at least this often when standard error is no terminal */
#define RENDER_PROGRESS_BAR_SECONDS 0.25  /* the bar's redraw on a terminal */
#define RENDER_PROGRESS_ENV "WHITTED_PROGRESS_SECONDS" /* overrides RENDER_PROGRESS_SECONDS (for tests) */
#define RENDER_PROGRESS_MAX_SECONDS 1e9                /* about 32 years: a longer interval is the default's */

struct progress {
    const char *unit;       /* "row" or "block" */
    int pieces;
    atomic_int done;        /* pieces finished, counted by the render threads */
    double started, interval;
    bool terminal, printed; /* printed: a line or the bar was written */
    bool finished;          /* set by render_image when the loop is over, under `lock` */
    pthread_mutex_t lock;
    pthread_cond_t wake;
};

/* Writes one report: the bar (no newline) on a terminal, a line elsewhere. */
static void print_progress(struct progress *p) {
    int done = atomic_load(&p->done);
    double elapsed = clock_seconds() - p->started;
    int percent = (int)(100.0 * done / p->pieces);
    const char *plural = p->pieces == 1 ? "" : "s";
    if (p->terminal) { /* the bar: a line written over itself, its end padded over a longer one's */
        char left[64] = "time left not known yet";
        if (done > 0)
            snprintf(left, sizeof left, "about %.1f s left", elapsed * (p->pieces - done) / done);
        fprintf(stderr, "\rrendering: %3d%%  %6.1f s elapsed, %-26s", percent, elapsed, left);
    } else if (done == 0) {
        fprintf(stderr, "rendering: 0%% of %d %s%s after %.1f s; the time left is known once one is done\n",
                p->pieces, p->unit, plural, elapsed);
    } else {
        fprintf(stderr, "rendering: %d%% of %d %s%s after %.1f s, about %.1f s left\n", percent, p->pieces, p->unit,
                plural, elapsed, elapsed * (p->pieces - done) / done);
    }
    fflush(stderr);
    p->printed = true;
}

/* The interval between lines: RENDER_PROGRESS_SECONDS, or the environment's positive number of seconds,
 * at most RENDER_PROGRESS_MAX_SECONDS (so that the time it is added to stays a time_t). */
static double progress_interval(void) {
    const char *text = getenv(RENDER_PROGRESS_ENV);
    char *end = NULL;
    double seconds = text != NULL ? strtod(text, &end) : 0.0;
    if (text == NULL || end == text || *end != '\0' || !(seconds > 0.0) || !(seconds <= RENDER_PROGRESS_MAX_SECONDS))
        return RENDER_PROGRESS_SECONDS;
    return seconds;
}

/* The reporting thread: a report every interval until render_image says the loop is over. */
static void *report_progress(void *context) {
    struct progress *p = context;
    pthread_mutex_lock(&p->lock);
    while (!p->finished) {
        double at = clock_seconds() + p->interval; /* CLOCK_MONOTONIC, as the condition waits by (below) */
        struct timespec until = {(time_t)at, (long)((at - floor(at)) * 1e9)};
        while (!p->finished && pthread_cond_timedwait(&p->wake, &p->lock, &until) != ETIMEDOUT) {
        }
        if (!p->finished)
            print_progress(p);
    }
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

/* Starts the reporting thread for a loop of `pieces` pieces. Returns false (and nothing will be
 * reported) when no thread can be started, as in the browser's build, which has none. */
static bool progress_start(struct progress *p, pthread_t *thread, int pieces, const char *unit) {
    p->unit = unit;
    p->pieces = pieces;
    atomic_init(&p->done, 0);
    p->started = clock_seconds();
    p->terminal = isatty(STDERR_FILENO);
    p->interval = p->terminal ? RENDER_PROGRESS_BAR_SECONDS : progress_interval();
    p->printed = p->finished = false;
    pthread_condattr_t monotonic;
    pthread_condattr_init(&monotonic);
    pthread_condattr_setclock(&monotonic, CLOCK_MONOTONIC);
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->wake, &monotonic);
    pthread_condattr_destroy(&monotonic);
    if (pthread_create(thread, NULL, report_progress, p) == 0)
        return true;
    pthread_cond_destroy(&p->wake);
    pthread_mutex_destroy(&p->lock);
    return false;
}

/* Stops the reporting thread and writes the last report: the full bar on a terminal, or, where lines
 * were written, a last one. */
static void progress_stop(struct progress *p, pthread_t thread) {
    pthread_mutex_lock(&p->lock);
    p->finished = true;
    pthread_cond_signal(&p->wake);
    pthread_mutex_unlock(&p->lock);
    pthread_join(thread, NULL);
    pthread_cond_destroy(&p->wake);
    pthread_mutex_destroy(&p->lock);
    if (p->terminal) {
        print_progress(p);
        fputc('\n', stderr);
    } else if (p->printed) {
        fprintf(stderr, "rendering: done in %.1f s\n", clock_seconds() - p->started);
    }
}

/* Renders row j of the window, one ray through each pixel centre. */
static void render_row(const struct render_job *job, struct image *img, struct render_window w, int j) {
    for (int i = w.left; i < w.left + w.width; i++) {
        ray r = camera_ray(job->camera, i, j);
        uint64_t cost_before = render_thread_cost();
        stats_thread.primary_rays++;
        vec3 colour = job->trace(job->world, &r);
        stats_thread.non_finite_pixels += !vec3_is_finite(colour);
        image_set(img, i, j, colour);
        if (job->heatmap != NULL) {
            uint64_t cost = render_thread_cost() - cost_before;
            image_set(job->heatmap, i, j, heatmap_colour(cost > UINT32_MAX ? UINT32_MAX : (uint32_t)cost));
        }
    }
    stats_thread.pixels += (uint64_t)w.width;
    stats_thread.camera_rays_max = 1;
}

/* The blocks of the picture's grid (ANTIALIAS_BLOCK pixels a side from its top-left corner) that the
 * window meets: `across` by `down` of them, the first being column `column`, row `row` of the grid. */
struct block_span {
    int column, row, across, down;
};

static struct block_span blocks_met(struct render_window w) {
    int column = w.left / ANTIALIAS_BLOCK, row = w.top / ANTIALIAS_BLOCK;
    return (struct block_span){column, row, (w.left + w.width - 1) / ANTIALIAS_BLOCK - column + 1,
                               (w.top + w.height - 1) / ANTIALIAS_BLOCK - row + 1};
}

/* Renders the part within the window of block number `block` of those it meets (counted along their
 * rows) with the job's sampler. */
static void render_block(const struct render_job *job, struct image *img, struct render_window w, int block) {
    struct block_span span = blocks_met(w);
    int left = (span.column + block % span.across) * ANTIALIAS_BLOCK;
    int top = (span.row + block / span.across) * ANTIALIAS_BLOCK;
    int right = left + ANTIALIAS_BLOCK < w.left + w.width ? left + ANTIALIAS_BLOCK : w.left + w.width;
    int bottom = top + ANTIALIAS_BLOCK < w.top + w.height ? top + ANTIALIAS_BLOCK : w.top + w.height;
    job->sampler->block(job, img, left > w.left ? left : w.left, top > w.top ? top : w.top, right, bottom);
}

bool render_window_is_exact(const struct render_job *job, struct render_window window, int width, int height) {
    if (job->sampler == NULL || job->sampler->block_edges_matter == NULL || !job->sampler->block_edges_matter(job))
        return true;
    int right = window.left + window.width, bottom = window.top + window.height;
    return window.left % ANTIALIAS_BLOCK == 0 && window.top % ANTIALIAS_BLOCK == 0 &&
           (right % ANTIALIAS_BLOCK == 0 || right == width) && (bottom % ANTIALIAS_BLOCK == 0 || bottom == height);
}

void render_image(const struct render_job *job, struct image *img, struct stats *total) {
    struct render_window w = job->window;
    if (w.width == 0)
        w = (struct render_window){0, 0, img->width, img->height};
    /* The work is shared out in pieces: the window's rows, or the sampler's blocks it meets. */
    int pieces = w.height;
    if (job->sampler != NULL)
        pieces = blocks_met(w).across * blocks_met(w).down;
    struct progress progress;
    pthread_t reporter;
    bool reporting = job->progress && progress_start(&progress, &reporter, pieces, job->sampler ? "block" : "row");
#ifdef _OPENMP
    int threads = job->threads > 0 ? job->threads : omp_get_max_threads();
#endif

#pragma omp parallel num_threads(threads)
    {
        stats_reset_thread();
#pragma omp for schedule(dynamic, 1)
        for (int piece = 0; piece < pieces; piece++) {
            if (job->sampler == NULL)
                render_row(job, img, w, w.top + piece);
            else
                render_block(job, img, w, piece);
            if (reporting)
                atomic_fetch_add(&progress.done, 1);
        }
#pragma omp critical
        stats_add(total, &stats_thread);
    }
    if (reporting)
        progress_stop(&progress, reporter);
}
