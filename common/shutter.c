/* shutter.c: a time for each camera sample, and the sampler that traces each sample at its time
 * (chapter 16; shutter.h). */
#include "shutter.h"

#include <math.h>

#include "sample_hash.h"
#include "supersample.h"
#include "thin_lens.h"
#include "world.h"

double shutter_time(double clock, double shutter, double x, double y, uint32_t seed) {
    if (shutter == 0.0)
        return clock;
    uint32_t kx = (uint32_t)(int32_t)floor(x * THIN_LENS_POINT_STEPS);
    uint32_t ky = (uint32_t)(int32_t)floor(y * THIN_LENS_POINT_STEPS);
    return clock + shutter * sample_hash_unit(kx, ky, SHUTTER_HASH_INDEX, seed);
}

/* What a view through the shutter looks with: the job, and its lens when it has one. */
struct shutter_view {
    const struct render_job *job;
    bool lens_open;
    struct thin_lens lens;
};

/* The colour of the camera sample at (x, y): its rays (one, or the lens's) traced in the world at the
 * sample's time, each counted. */
static vec3 colour_at(const void *context, double x, double y) {
    const struct shutter_view *view = context;
    const struct render_job *job = view->job;
    const struct world *frame = job->world;
    struct world at = *frame; /* the sample's own world: the frame's, at the sample's time */
    at.time = shutter_time(frame->time, frame->scene->shutter, x, y, job->antialias->seed);
    if (!view->lens_open) {
        ray r = camera_ray_through(job->camera, x, y);
        stats_thread.primary_rays++;
        return job->trace(&at, &r);
    }
    vec3 sum = vec3_make(0, 0, 0);
    for (int k = 0; k < view->lens.samples; k++) {
        ray r = thin_lens_ray(&view->lens, x, y, k);
        stats_thread.primary_rays++;
        sum = vec3_add(sum, job->trace(&at, &r));
    }
    return vec3_scale(sum, 1.0 / view->lens.samples);
}

static void render_block(const struct render_job *job, struct image *img, int left, int top, int right, int bottom) {
    struct shutter_view shutter_view = {job, job->lens != NULL && lens_is_open(job->lens), {0}};
    if (shutter_view.lens_open)
        thin_lens_init(&shutter_view.lens, job->camera, job->lens, job->antialias->seed);
    struct sample_view view = {colour_at, &shutter_view};
    supersample_render_view(job, &view, img, left, top, right, bottom);
}

const struct render_sampler shutter_sampler = {render_block, &supersample_ray_scale};
