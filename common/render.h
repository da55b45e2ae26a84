/* render.h: the pixel loop, one primary ray through each pixel, shared by every chapter (chapter 1).
 *
 * Each chapter supplies only its trace function: what colour a ray sees. Rows are shared out among
 * threads (OpenMP); every pixel is computed the same way whatever thread does it, so the picture is
 * bit-identical for any thread count. Chapter 12 adds a sampler that shoots several rays per pixel;
 * it is handed blocks of pixels instead of rows, with the same guarantee. */
#ifndef WHITTED_RENDER_H
#define WHITTED_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include "antialias.h"
#include "camera.h"
#include "heatmap.h"
#include "image.h"
#include "lens.h"
#include "stats.h"

/* What a chapter computes: the colour seen along primary ray r in `world` (the chapter's scene and
 * whatever it built from it). Must be safe to call from several threads at once. */
typedef vec3 (*render_trace_fn)(const void *world, const ray *r);

struct render_job;

/* Renders pixels [left, right) x [top, bottom) of img (and of job->heatmap), counting its camera rays,
 * its pixels and its most camera rays for one pixel in stats_thread. */
typedef void (*render_block_fn)(const struct render_job *job, struct image *img, int left, int top, int right,
                                int bottom);

/* Another way of sampling the pixels than one ray through each centre (chapter 12's anti-aliasing):
 * the picture is rendered in blocks of ANTIALIAS_BLOCK x ANTIALIAS_BLOCK pixels from the top-left
 * corner (smaller at the right and bottom edges), each handed to `block` on some thread. */
struct render_sampler {
    render_block_fn block;
    const struct heatmap_scale *heatmap; /* the scale of what `block` draws into the heat-map */
};

struct render_job {
    const struct camera *camera;
    render_trace_fn trace;
    const void *world;
    int threads;        /* 0 = as many as OpenMP offers */
    bool progress;      /* report the progress and the time left on stderr while rendering: a bar on a
                         * terminal, else a line every 5 s (render.c's RENDER_PROGRESS_SECONDS, or the
                         * environment's WHITTED_PROGRESS_SECONDS) */
    struct image *heatmap; /* optional (NULL): the work each pixel cost, drawn by heatmap_colour */
    const struct render_sampler *sampler; /* optional (NULL): one ray through each pixel centre */
    const struct antialias *antialias;    /* the sampler's settings (the scene's antialias line) */
    const struct lens *lens;              /* the camera's lens, for chapter 13's sampler */
};

/* Renders every pixel of `img` (and of job->heatmap), which must already have the camera's size, and
 * adds all threads' counters into *total. Each pixel is stored as soon as it is finished, in the 8 bits
 * the PNG keeps, so no frame of doubles is ever held. Cannot fail. */
void render_image(const struct render_job *job, struct image *img, struct stats *total);

/* Returns the traversal cost counted so far by the calling thread: node visits (with chapter 16's
 * instances, of both levels) plus box, sphere, triangle and plane tests. The difference before and
 * after a ray is that ray's cost. */
uint64_t render_thread_cost(void);

/* Makes every parallel part of the program use n threads: the pixel loop (unless a job names its own)
 * and what else asks OpenMP how many it has (chapter 11's build). n <= 0 leaves OpenMP's default, one a
 * core. Without OpenMP (the browser's build) everything runs on one thread and this does nothing. */
void render_use_threads(int n);

#endif
