/* ray_budget.c: the bound on the rays a scene asks for, from its keys (chapter 1). */
#include "ray_budget.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "antialias.h"
#include "area_light.h"
#include "instance_syntax.h"
#include "lens.h"
#include "path_settings.h"
#include "ray.h"
#include "triangle.h"

/* The most camera samples the antialias method takes for the whole picture, from how supersample.c
 * spends them in its blocks of ANTIALIAS_BLOCK pixels a side; *per_pixel gets the most for one pixel. */
static double camera_samples(const struct antialias *a, int width, int height, double *per_pixel) {
    double pixels = (double)width * height, n = a->samples;
    double across = ceil((double)width / ANTIALIAS_BLOCK), down = ceil((double)height / ANTIALIAS_BLOCK);
    double cells = ldexp(1.0, a->samples - 1), side = cells + 1;
    switch (a->method) {
    case ANTIALIAS_GRID:
    case ANTIALIAS_JITTER:
        *per_pixel = n * n;
        return pixels * n * n;
    case ANTIALIAS_ADAPTIVE: /* the centre and the grid; each block also looks once beyond its top and left */
        *per_pixel = n * n + 1;
        return pixels * (n * n + 1) + across * height + down * width;
    case ANTIALIAS_RECURSIVE: /* every point of the pixel's table, its four corners shared in the block */
        *per_pixel = side * side;
        return pixels * (side * side - 4) + pixels + down * width + across * height + across * down;
    case ANTIALIAS_NONE:
        break;
    }
    *per_pixel = 1;
    return pixels;
}

/* The shadow rays one hit sends: one to each point light, one to each point of an area light's grid.
 * *area gets the area lights' share. */
static double shadow_rays(const struct scene *s, double *area) {
    double all = 0;
    *area = 0;
    for (size_t k = 0; k < s->light_count; k++) {
        const struct area_light *a = &s->lights[k].area;
        double rays = area_light_is_area(a) ? (double)a->size1 * a->size2 : 1.0;
        all += rays;
        if (area_light_is_area(a))
            *area += rays;
    }
    return all;
}

/* The most rays of one camera ray's tree down to max_depth, counting the shadow rays apart: a tree
 * whose surfaces neither reflect nor let light through is the camera ray alone, one whose surfaces do
 * one or the other is a chain of max_depth rays, and only a surface that does both branches it in two
 * (a refracted ray that turns into a reflected one at total internal reflection stays one ray). */
static double rays_to_depth(const struct scene *s) {
    int branches = 0;
    for (size_t k = 0; k < s->material_count; k++) {
        const struct material *m = &s->materials[k];
        int here = (m->reflection > 0.0) + material_passes_light(m);
        if (here > branches)
            branches = here;
    }
    if (branches == 0)
        return 1.0;
    if (branches == 1)
        return s->max_depth;
    return ldexp(1.0, s->max_depth) - 1.0;
}

/* The shapes every ray of chapter `chapter` tests, no structure holding them: the spheres, boxes and
 * planes it draws, and before RAY_BUDGET_GATHER_CHAPTER its triangle lines; at least 1. (A mesh's
 * triangles are tested only by rays that meet its box before chapter 9, and are in the tree after.) */
static double shapes_every_ray_tests(const struct scene *s, int chapter) {
    double shapes = 0.0;
    for (size_t k = 0; scene_syntaxes[k] != NULL; k++) {
        const struct shape_list *list = scene_shapes(s, scene_syntaxes[k]);
        bool in_a_tree = scene_syntaxes[k] == &triangle_syntax && chapter >= RAY_BUDGET_GATHER_CHAPTER;
        if (list != NULL && list->kind != NULL && !in_a_tree)
            shapes += (double)list->count;
    }
    return shapes > 1.0 ? shapes : 1.0;
}

double ray_budget_estimate(const struct scene *s, int chapter, struct ray_budget *b) {
    double pixels = (double)s->width * s->height;
    b->line = 0;
    if (instance_chapter_draws(chapter, PATH_CHAPTER)) {
        const struct path_settings *p = &s->paths;
        double shadows = p->strategy == PATH_SCATTER ? 0.0 : p->bounces + 1.0;
        b->per_pixel = p->samples;
        b->camera_rays = pixels * p->samples;
        b->shadow_per_hit = p->strategy == PATH_SCATTER ? 0.0 : 1.0;
        b->tree_rays = p->bounces + 2.0 + shadows;
        b->line = p->line;
    } else {
        b->camera_rays = camera_samples(&s->antialias, s->width, s->height, &b->per_pixel);
        if (lens_is_open(&s->lens))
            b->camera_rays *= s->lens.blur_samples;
        double area = 0;
        b->shadow_per_hit = chapter >= RAY_BUDGET_SHADOW_CHAPTER ? shadow_rays(s, &area) : 0.0;
        double point = b->shadow_per_hit - area;
        b->tree_rays = 1.0 + b->shadow_per_hit;
        if (chapter >= RAY_BUDGET_TREE_CHAPTER) {
            /* At most 2^max_depth - 1 rays, each with its shadow rays; and the budget holds the secondary
             * rays and the area lights' shadow rays to RAY_TREE_BUDGET, plus the one shading that spends
             * the last of it, each of the 1 + RAY_TREE_BUDGET rays adding its point lights' rays. */
            double by_depth = rays_to_depth(s) * b->tree_rays;
            double by_budget = 1.0 + RAY_TREE_BUDGET + area + point * (1.0 + RAY_TREE_BUDGET);
            b->tree_rays = fmin(by_depth, by_budget);
        }
        if (b->per_pixel * (lens_is_open(&s->lens) ? s->lens.blur_samples : 1) >= b->tree_rays)
            b->line = s->antialias.line;
    }
    b->total = b->camera_rays * b->tree_rays;
    b->shapes_per_ray = shapes_every_ray_tests(s, chapter);
    b->tests = b->total * b->shapes_per_ray;
    return b->total;
}

/* Appends printf-style text at out + *used, keeping within out_size. */
static void append(char *out, size_t out_size, size_t *used, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

static void append(char *out, size_t out_size, size_t *used, const char *format, ...) {
    if (*used >= out_size)
        return;
    va_list args;
    va_start(args, format);
    int n = vsnprintf(out + *used, out_size - *used, format, args);
    va_end(args);
    if (n > 0)
        *used += (size_t)n;
}

void ray_budget_describe(const struct ray_budget *b, const struct scene *s, int chapter, char *out,
                         size_t out_size) {
    size_t used = 0;
    if (out_size > 0)
        out[0] = '\0';
    append(out, out_size, &used, "%d x %d pixels", s->width, s->height);
    if (instance_chapter_draws(chapter, PATH_CHAPTER)) {
        append(out, out_size, &used, ", paths samples %d bounces %d strategy %s: up to %.0f rays a path",
               s->paths.samples, s->paths.bounces, path_strategy_name(s->paths.strategy), b->tree_rays);
        return;
    }
    const struct antialias *a = &s->antialias;
    if (a->method == ANTIALIAS_RECURSIVE)
        append(out, out_size, &used, ", antialias recursive depth %d: up to %.0f rays a pixel", a->samples,
               b->per_pixel);
    else if (a->method != ANTIALIAS_NONE)
        append(out, out_size, &used, ", antialias %s samples %d: %s%.0f rays a pixel", antialias_method_name(a->method),
               a->samples, a->method == ANTIALIAS_ADAPTIVE ? "up to " : "", b->per_pixel);
    if (lens_is_open(&s->lens))
        append(out, out_size, &used, ", blur_samples %d", s->lens.blur_samples);
    if (b->shadow_per_hit > 0) {
        int side1 = 0, side2 = 0;
        for (size_t k = 0; k < s->light_count; k++) { /* the largest area light */
            const struct area_light *l = &s->lights[k].area;
            if ((double)l->size1 * l->size2 > (double)side1 * side2) {
                side1 = l->size1;
                side2 = l->size2;
            }
        }
        append(out, out_size, &used, ", %zu light%s", s->light_count, s->light_count == 1 ? "" : "s");
        if (side1 > 0)
            append(out, out_size, &used, " (area light %d x %d)", side1, side2);
        append(out, out_size, &used, ": %.0f shadow ray%s a hit", b->shadow_per_hit, b->shadow_per_hit == 1 ? "" : "s");
    }
    if (chapter >= RAY_BUDGET_TREE_CHAPTER)
        append(out, out_size, &used, ", max_depth %d: up to %.0f rays a camera ray", s->max_depth, b->tree_rays);
}
