/* supersample.c: a pixel's colour from several rays, by the four methods of the antialias line
 * (chapter 12; the rules in words: docs/12-antialias.md). */
#include "supersample.h"

#include <math.h>
#include <string.h>

#include "camera.h"
#include "sample_hash.h"

static const uint32_t ray_ticks[] = {0, 1, 10, 100};
const struct heatmap_scale supersample_ray_scale = {100, ray_ticks, 4};

/* One sample: the colour through (x, y), counted in *rays. */
static vec3 look(const struct sample_view *view, double x, double y, int *rays) {
    (*rays)++;
    return view->colour_at(view->context, x, y);
}

/* TASK 12.1: the box filter over a regular n x n grid */
vec3 supersample_grid(const struct sample_view *view, int i, int j, int n) {
    /* The mean is taken about the first sample, so that n x n equal colours give that colour back to the
     * last bit. A plain sum does not: nine samples of 0.3 sum to 2.6999999999999997, and a ninth of it
     * is 0.29999999999999993, which is written as level 76, where one ray of 0.3 (76.5 levels) is 77. */
    vec3 first = vec3_make(0, 0, 0), offsets = vec3_make(0, 0, 0);
    for (int b = 0; b < n; b++)
        for (int a = 0; a < n; a++) {
            vec3 sample = view->colour_at(view->context, i + (a + 0.5) / n, j + (b + 0.5) / n);
            if (a == 0 && b == 0)
                first = sample;
            else
                offsets = vec3_add(offsets, vec3_sub(sample, first));
        }
    return vec3_add(first, vec3_scale(offsets, 1.0 / (n * n)));
}

/* Pixel (i, j)'s colour as the mean of n x n samples, one at a random point of each cell of the grid:
 * cell (a, b) takes the numbers 2k and 2k + 1 of the pixel (k = b n + a) under the seed. */
/* TASK 12.1 ALSO: jittered samples, a random point in each cell of the n x n grid */
static vec3 jittered(const struct sample_view *view, int i, int j, int n, uint32_t seed) {
    vec3 first = vec3_make(0, 0, 0), offsets = vec3_make(0, 0, 0); /* as in supersample_grid */
    for (int b = 0; b < n; b++)
        for (int a = 0; a < n; a++) {
            uint32_t k = (uint32_t)(b * n + a);
            double u = sample_hash_unit((uint32_t)i, (uint32_t)j, 2 * k, seed);
            double v = sample_hash_unit((uint32_t)i, (uint32_t)j, 2 * k + 1, seed);
            vec3 sample = view->colour_at(view->context, i + (a + u) / n, j + (b + v) / n);
            if (k == 0)
                first = sample;
            else
                offsets = vec3_add(offsets, vec3_sub(sample, first));
        }
    return vec3_add(first, vec3_scale(offsets, 1.0 / (n * n)));
}

/* POV-Ray's Antialias_Gamma encoding of one channel, a negative one counting as 0. */
static double encoded(double channel) { return pow(fmax(channel, 0.0), 1.0 / ANTIALIAS_GAMMA); }

/* TASK 12.2: POV-Ray's colour difference test */
bool supersample_differ(vec3 a, vec3 b, double threshold) {
    double distance = fabs(encoded(a.x) - encoded(b.x)) + fabs(encoded(a.y) - encoded(b.y)) +
                      fabs(encoded(a.z) - encoded(b.z));
    return distance >= threshold;
}

/* ---- adaptive: POV-Ray's sampling method 1 --------------------------------------------------------
 * Each pixel first gets one ray through its centre. Then, in reading order, the pixel's colour is
 * compared with the colour its left and upper neighbours have now. Where either differs, the pixel is
 * refined, and so is each differing neighbour not refined yet: n x n rays on the grid are added to its
 * centre ray and all n^2 + 1 averaged. A neighbour outside the block (its row above, its column to
 * the left) is traced again, through its centre, and counts as refined already: POV-Ray renders
 * blocks independently, so it cannot refine a pixel of another block. */

/* Refines pixel (i, j), whose colour so far is its centre's: one more ray per cell of the grid. */
static void refine(const struct sample_view *view, int i, int j, int n, vec3 *colour, int *rays, bool *refined) {
    vec3 grid = supersample_grid(view, i, j, n);
    *colour = vec3_scale(vec3_add(*colour, vec3_scale(grid, n * n)), 1.0 / (n * n + 1));
    *rays += n * n;
    *refined = true;
}

static void adaptive_block(const struct antialias *a, const struct sample_view *view, int left, int top, int w,
                           int h, vec3 *colours, int *rays, int *outside) {
    int n = a->samples;
    vec3 above[ANTIALIAS_BLOCK];
    bool refined[ANTIALIAS_BLOCK * ANTIALIAS_BLOCK];
    for (int x = 0; x < w; x++)
        above[x] = look(view, left + x + 0.5, top - 0.5, outside);
    for (int y = 0; y < h; y++) {
        int j = top + y;
        vec3 beside = look(view, left - 0.5, j + 0.5, outside);
        for (int x = 0; x < w; x++) {
            int i = left + x, k = y * w + x;
            colours[k] = look(view, i + 0.5, j + 0.5, &rays[k]);
            refined[k] = false;
            bool left_differs = supersample_differ(x > 0 ? colours[k - 1] : beside, colours[k], a->threshold);
            bool top_differs = supersample_differ(y > 0 ? colours[k - w] : above[x], colours[k], a->threshold);
            if (left_differs && x > 0 && !refined[k - 1])
                refine(view, i - 1, j, n, &colours[k - 1], &rays[k - 1], &refined[k - 1]);
            if (top_differs && y > 0 && !refined[k - w])
                refine(view, i, j - 1, n, &colours[k - w], &rays[k - w], &refined[k - w]);
            if (left_differs || top_differs)
                refine(view, i, j, n, &colours[k], &rays[k], &refined[k]);
        }
    }
}

/* ---- recursive: POV-Ray's sampling method 2 -------------------------------------------------------
 * Rays go through the corners of every pixel of the block (each corner traced once). A pixel's square
 * whose four corners all agree (no pair differs) takes their mean. Otherwise, while the depth allows,
 * rays go through the middles of its four sides and its centre, and each of its four quarters is
 * treated the same way; the square's colour is the mean of its quarters'. Points are shared within
 * one pixel (a table of its points), not between pixels, as in POV-Ray. */

#define FINEST (1 << (ANTIALIAS_MAX_DEPTH - 1)) /* cells a side of a pixel at the greatest depth */

/* One pixel's table of points: point (p, q) is (i + p / cells, j + q / cells). */
struct pixel_points {
    const struct sample_view *view;
    double threshold;
    int i, j, cells;
    vec3 colour[(FINEST + 1) * (FINEST + 1)];
    bool sampled[(FINEST + 1) * (FINEST + 1)];
    int *rays;
};

/* The colour at point (p, q), traced when the pixel has not traced it yet. */
static vec3 point(struct pixel_points *t, int p, int q) {
    int k = q * (t->cells + 1) + p;
    if (!t->sampled[k]) {
        t->colour[k] = look(t->view, t->i + (double)p / t->cells, t->j + (double)q / t->cells, t->rays);
        t->sampled[k] = true;
    }
    return t->colour[k];
}

/* The colour of the square of side `size` (in table steps) with top-left point (p, q), quartered up to
 * `level` more times. */
static vec3 square(struct pixel_points *t, int p, int q, int size, int level) {
    vec3 top_left = point(t, p, q), bottom_left = point(t, p, q + size);
    vec3 top_right = point(t, p + size, q), bottom_right = point(t, p + size, q + size);
    double limit = t->threshold;
    bool differ = supersample_differ(top_left, bottom_left, limit) || supersample_differ(top_left, top_right, limit) ||
                  supersample_differ(top_left, bottom_right, limit) ||
                  supersample_differ(bottom_left, top_right, limit) ||
                  supersample_differ(bottom_left, bottom_right, limit) ||
                  supersample_differ(top_right, bottom_right, limit);
    if (level == 0 || !differ)
        return vec3_scale(vec3_add(vec3_add(vec3_add(top_left, bottom_left), top_right), bottom_right), 0.25);
    int half = size / 2;
    point(t, p, q + half); /* POV-Ray's order: the middles of the left, top, right and bottom sides, */
    point(t, p + half, q);
    point(t, p + size, q + half);
    point(t, p + half, q + size);
    point(t, p + half, q + half); /* then the centre */
    vec3 sum = vec3_add(square(t, p, q, half, level - 1), square(t, p, q + half, half, level - 1));
    sum = vec3_add(sum, square(t, p + half, q, half, level - 1));
    sum = vec3_add(sum, square(t, p + half, q + half, half, level - 1));
    return vec3_scale(sum, 0.25);
}

static void recursive_block(const struct antialias *a, const struct sample_view *view, int left, int top, int w,
                            int h, vec3 *colours, int *rays, int *outside) {
    vec3 corner[(ANTIALIAS_BLOCK + 1) * (ANTIALIAS_BLOCK + 1)];
    for (int q = 0; q <= h; q++)
        for (int p = 0; p <= w; p++) /* a corner is counted in the pixel whose top-left it is */
            corner[q * (w + 1) + p] = look(view, left + p, top + q, p < w && q < h ? &rays[q * w + p] : outside);
    struct pixel_points t;
    t.view = view;
    t.threshold = a->threshold;
    t.cells = 1 << (a->samples - 1);
    int side = t.cells + 1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            t.i = left + x;
            t.j = top + y;
            t.rays = &rays[y * w + x];
            memset(t.sampled, 0, (size_t)side * (size_t)side * sizeof t.sampled[0]);
            /* the pixel's corners, from the block's: top left, top right, bottom left, bottom right */
            const vec3 *c = &corner[y * (w + 1) + x];
            int at[4] = {0, t.cells, side * t.cells, side * side - 1};
            vec3 from[4] = {c[0], c[1], c[w + 1], c[w + 2]};
            for (int k = 0; k < 4; k++) {
                t.colour[at[k]] = from[k];
                t.sampled[at[k]] = true;
            }
            colours[y * w + x] = square(&t, 0, 0, t.cells, a->samples - 1);
        }
}

uint64_t supersample_block(const struct antialias *a, const struct sample_view *view, int left, int top, int right,
                           int bottom, vec3 *colours, int *rays) {
    int w = right - left, h = bottom - top, n = a->samples, outside = 0;
    if (w < 1 || h < 1 || w > ANTIALIAS_BLOCK || h > ANTIALIAS_BLOCK)
        return 0;
    memset(rays, 0, (size_t)w * (size_t)h * sizeof rays[0]);
    switch (a->method) {
    case ANTIALIAS_NONE:
        for (int k = 0; k < w * h; k++)
            colours[k] = look(view, left + k % w + 0.5, top + k / w + 0.5, &rays[k]);
        break;
    case ANTIALIAS_GRID:
        for (int k = 0; k < w * h; k++) {
            colours[k] = supersample_grid(view, left + k % w, top + k / w, n);
            rays[k] = n * n;
        }
        break;
    case ANTIALIAS_JITTER:
        for (int k = 0; k < w * h; k++) {
            colours[k] = jittered(view, left + k % w, top + k / w, n, a->seed);
            rays[k] = n * n;
        }
        break;
    case ANTIALIAS_ADAPTIVE:
        adaptive_block(a, view, left, top, w, h, colours, rays, &outside);
        break;
    case ANTIALIAS_RECURSIVE:
        recursive_block(a, view, left, top, w, h, colours, rays, &outside);
        break;
    }
    uint64_t total = (uint64_t)outside;
    for (int k = 0; k < w * h; k++)
        total += (uint64_t)rays[k];
    return total;
}

/* ---- the renderer's sampler ---------------------------------------------------------------------- */

/* The camera's ray through (x, y), traced and counted: the view of a render job. */
static vec3 camera_colour_at(const void *context, double x, double y) {
    const struct render_job *job = context;
    ray r = camera_ray_through(job->camera, x, y);
    stats_thread.primary_rays++;
    return job->trace(job->world, &r);
}

void supersample_render_view(const struct render_job *job, const struct sample_view *view, struct image *img, int left,
                             int top, int right, int bottom) {
    vec3 colours[ANTIALIAS_BLOCK * ANTIALIAS_BLOCK];
    int rays[ANTIALIAS_BLOCK * ANTIALIAS_BLOCK];
    supersample_block(job->antialias, view, left, top, right, bottom, colours, rays);
    int w = right - left;
    for (int j = top; j < bottom; j++)
        for (int i = left; i < right; i++) {
            int k = (j - top) * w + (i - left);
            stats_thread.non_finite_pixels += !vec3_is_finite(colours[k]);
            image_set(img, i, j, colours[k]);
            if (job->heatmap != NULL)
                image_set(job->heatmap, i, j, heatmap_colour_on(&supersample_ray_scale, (uint32_t)rays[k]));
            if ((uint64_t)rays[k] > stats_thread.camera_rays_max)
                stats_thread.camera_rays_max = (uint64_t)rays[k];
        }
    stats_thread.pixels += (uint64_t)w * (uint64_t)(bottom - top);
}

/* The job's pixels through the camera. */
static void render_block(const struct render_job *job, struct image *img, int left, int top, int right, int bottom) {
    struct sample_view view = {camera_colour_at, job};
    supersample_render_view(job, &view, img, left, top, right, bottom);
}

bool supersample_block_edges_matter(const struct render_job *job) {
    return job->antialias->method == ANTIALIAS_ADAPTIVE;
}

const struct render_sampler supersample_sampler = {render_block, &supersample_ray_scale,
                                                   supersample_block_edges_matter};
