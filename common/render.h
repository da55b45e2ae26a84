/* render.h: the pixel loop, one primary ray through each pixel, shared by every chapter (chapter 1).
 *
 * Each chapter supplies only its trace function: what colour a ray sees. Rows are shared out among
 * threads (OpenMP); every pixel is computed the same way whatever thread does it, so the picture is
 * bit-identical for any thread count. */
#ifndef WHITTED_RENDER_H
#define WHITTED_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include "camera.h"
#include "image.h"
#include "stats.h"

/* What a chapter computes: the colour seen along primary ray r in `world` (the chapter's scene and
 * whatever it built from it). Must be safe to call from several threads at once. */
typedef vec3 (*render_trace_fn)(const void *world, const ray *r);

struct render_job {
    const struct camera *camera;
    render_trace_fn trace;
    const void *world;
    int threads;        /* 0 = as many as OpenMP offers */
    bool progress;      /* print a progress line with an estimate of the time left to stderr */
    struct image *heatmap; /* optional (NULL): the work each pixel cost, drawn by heatmap_colour */
};

/* Renders every pixel of `img` (and of job->heatmap), which must already have the camera's size, and
 * adds all threads' counters into *total. Each pixel is stored as soon as it is finished, in the 8 bits
 * the PNG keeps, so no frame of doubles is ever held. Cannot fail. */
void render_image(const struct render_job *job, struct image *img, struct stats *total);

/* Returns the traversal cost counted so far by the calling thread: node visits plus box, sphere,
 * triangle and plane tests. The difference before and after a ray is that ray's cost. */
uint64_t render_thread_cost(void);

#endif
