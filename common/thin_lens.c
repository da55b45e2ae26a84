/* thin_lens.c: camera rays through a lens for depth of field (chapter 13; in words:
 * docs/13-distributed.md). */
#include "thin_lens.h"

#include <math.h>
#include <stdlib.h>

#include "sample_hash.h"
#include "supersample.h"

/* POV-Ray's focal blur puts its image points on average 1/32 of a pixel left of and above the point
 * asked for: its jitter within a cell of its 16 x 16 grid over the pixel is already centred on 0 and
 * has 1/2 taken off again. We shift ours alike, so that the two pictures agree (measured: the mean
 * difference over 8 x 8 blocks falls from 0.021 to 0.005 levels). */
#define THIN_LENS_POVRAY_SHIFT (1.0 / 32)

void thin_lens_init(struct thin_lens *t, const struct camera *camera, const struct lens *l, uint32_t seed) {
    int rings = l->blur_samples == 7 ? 1 : l->blur_samples == 19 ? 2 : 3;
    t->camera = camera;
    t->aperture = l->aperture;
    t->focal_distance = vec3_length(vec3_sub(l->focal_point, camera->eye));
    t->cell = 1.0 / (sqrt(3.0) * (rings + 1));
    t->seed = seed;
    t->samples = 0;
    for (int b = -rings; b <= rings; b++)
        for (int a = -rings; a <= rings; a++)
            if (abs(a + b) <= rings && t->samples < THIN_LENS_MAX_SAMPLES) {
                t->grid[t->samples][0] = t->cell * (a + 0.5 * b);
                t->grid[t->samples][1] = t->cell * (sqrt(3.0) / 2.0 * b);
                t->samples++;
            }
}

/* The image point to 1 / THIN_LENS_POINT_STEPS of a pixel, as a whole number for sample_hash. */
static uint32_t point_key(double coordinate) {
    return (uint32_t)(int32_t)floor(coordinate * THIN_LENS_POINT_STEPS);
}

/* TASK 13.2: the thin lens: a ray from a point of the lens through the focal plane */
ray thin_lens_ray(const struct thin_lens *t, double x, double y, int k) {
    const struct camera *c = t->camera;
    uint32_t kx = point_key(x), ky = point_key(y), index = 4 * (uint32_t)k;
    double u = sample_hash_unit(kx, ky, index, t->seed), v = sample_hash_unit(kx, ky, index + 1, t->seed);
    double s = sample_hash_unit(kx, ky, index + 2, t->seed), r = sample_hash_unit(kx, ky, index + 3, t->seed);
    /* Where the pinhole's ray through the (moved) image point meets the focal plane: its direction has
     * length 1 along the view, so the plane is focal_distance of it away. */
    double sx = x + s - 0.5 - THIN_LENS_POVRAY_SHIFT, sy = y + r - 0.5 - THIN_LENS_POVRAY_SHIFT;
    double px = 2.0 * sx / c->width - 1.0, py = 1.0 - 2.0 * sy / c->height;
    vec3 direction = vec3_add_scaled(c->forward, c->right, px * c->half_width);
    direction = vec3_add_scaled(direction, c->up, py * c->half_height);
    vec3 focus = vec3_add_scaled(c->eye, direction, t->focal_distance);
    /* The lens point: grid point k moved at random within its cell, in units of the diameter. */
    double gx = t->grid[k][0] + (u - 0.5) * t->cell, gy = t->grid[k][1] + (v - 0.5) * t->cell;
    vec3 origin = vec3_add_scaled(vec3_add_scaled(c->eye, c->right, t->aperture * gx), c->up, t->aperture * gy);
    return (ray){origin, vec3_normalize(vec3_sub(focus, origin))};
}

/* What a lens view looks through: the job and its lens. */
struct lens_view {
    const struct render_job *job;
    struct thin_lens lens;
};

/* The colour of the camera sample at (x, y): the mean of its lens rays, each traced and counted. The
 * mean is POV-Ray's (TraceRayWithFocalBlur): each ray's colour in single precision, summed in single
 * precision, the sum divided by the count. Where a colour lies on a half level, as 0.3 does (76.5 of
 * 255), the way a mean is rounded decides the level of every pixel of that colour: a sum of doubles
 * times 1 / samples wrote the background of 0.3 one level below POV-Ray's. */
static vec3 lens_colour_at(const void *context, double x, double y) {
    const struct lens_view *view = context;
    float sum[3] = {0.0f, 0.0f, 0.0f};
    for (int k = 0; k < view->lens.samples; k++) {
        ray r = thin_lens_ray(&view->lens, x, y, k);
        stats_thread.primary_rays++;
        vec3 c = view->job->trace(view->job->world, &r);
        sum[0] += (float)c.x;
        sum[1] += (float)c.y;
        sum[2] += (float)c.z;
    }
    double n = view->lens.samples;
    return vec3_make((float)(sum[0] / n), (float)(sum[1] / n), (float)(sum[2] / n));
}

static void render_block(const struct render_job *job, struct image *img, int left, int top, int right, int bottom) {
    if (job->lens == NULL || !lens_is_open(job->lens)) {
        supersample_sampler.block(job, img, left, top, right, bottom);
        return;
    }
    struct lens_view lens_view = {job, {0}};
    thin_lens_init(&lens_view.lens, job->camera, job->lens, job->antialias->seed);
    struct sample_view view = {lens_colour_at, &lens_view};
    supersample_render_view(job, &view, img, left, top, right, bottom);
}

const struct render_sampler thin_lens_sampler = {render_block, &supersample_ray_scale, supersample_block_edges_matter};
