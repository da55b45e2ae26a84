/* ray_budget.h: before a picture is rendered, an upper bound on the rays its scene asks for, worked out
 * from the scene's keys alone, and the limit above which a chapter will not start without --no-limit
 * (chapter 1; docs/scene-format.md, "Limits").
 *
 * Each key is capped alone, but their product is not: 640 x 480 pixels, recursive anti-aliasing at
 * depth 6, a lens of 37 rays, a 33 x 33 area light and max_depth 64 are each allowed, and together they
 * would take days. The bound multiplies what the chapter does with the keys:
 *
 *   rays = camera rays of the whole picture           (pixels x the antialias method's most rays a
 *                                                      pixel x the lens's blur_samples)
 *          x rays of one camera ray's tree            (the tree's rays x (1 + shadow rays a hit))
 *
 * A tree holds at most 2^max_depth - 1 rays when a material both reflects and lets light through (a
 * reflected and a refracted ray at every hit), max_depth rays when each material does one or the other,
 * and only the camera ray when none does either; never
 * more than the tree's budget allows (RAY_TREE_BUDGET secondary rays, area lights' shadow rays counted
 * against it: whitted.h). A hit sends one shadow ray to each point light and one to each point of an
 * area light's grid (the adaptive rule's worst case: every point). Chapter 15's paths replace all that:
 *   rays = pixels x samples x (bounces + 2 rays of a path + bounces + 1 shadow rays, none for scatter).
 * Passes straight through surfaces of equal index (ray.h's RAY_MAX_CROSSINGS) are not counted: they
 * spend the same budget. A ray's own cost is bounded too: it tests every sphere, box and plane the scene
 * draws (no structure holds them) and, before chapter 9 gathers them into its tree, every triangle line,
 * so the tests are rays x those shapes, with limits of their own. The numbers are doubles, so no product
 * overflows. */
#ifndef WHITTED_RAY_BUDGET_H
#define WHITTED_RAY_BUDGET_H

#include <stddef.h>

#include "scene.h"

/* A scene that asks for more rays than this is refused (exit 1) unless --no-limit is given: at ten
 * million rays a second, more than a day. */
#define RAY_BUDGET_LIMIT 1e12
/* A scene that asks for more than this gets a note on standard error (unless --quiet): at ten million
 * rays a second, more than a quarter of an hour. */
#define RAY_BUDGET_LARGE 1e10
/* The same for the tests of the shapes every ray tests (at 3e8 tests a second, as two cores test
 * spheres, more than a day and a quarter of an hour). */
#define RAY_BUDGET_TEST_LIMIT 3e13
#define RAY_BUDGET_TEST_LARGE 3e11
/* The chapter from which triangle lines are gathered into a tree with the meshes (chapter 9's). */
#define RAY_BUDGET_GATHER_CHAPTER 9
/* The chapters that add shadow rays (7) and the tree of reflected and refracted rays (8). */
#define RAY_BUDGET_SHADOW_CHAPTER 7
#define RAY_BUDGET_TREE_CHAPTER 8

/* The bound and its factors, for the message that names them. */
struct ray_budget {
    double camera_rays;     /* of the whole picture (chapter 15: paths) */
    double per_pixel;       /* the antialias method's most camera rays for one pixel (chapter 15: paths) */
    double shadow_per_hit;  /* shadow rays one hit sends */
    double tree_rays;       /* rays of one camera ray's tree, its shadow rays included (chapter 15: a
                               path's rays) */
    double total;           /* camera_rays x tree_rays */
    double shapes_per_ray;  /* the shapes every ray tests, no structure holding them (at least 1) */
    double tests;           /* total x shapes_per_ray */
    int line;               /* the scene line of the key that contributes most, 0 when not known */
};

/* Fills *b with the bound on the rays chapter `chapter` traces for scene s, which must already hold
 * only what the chapter draws (scene_drop_unsupported) and its final size. Returns b->total. Cannot
 * fail: every factor is at least 1 and finite for any scene the reader accepts. */
double ray_budget_estimate(const struct scene *s, int chapter, struct ray_budget *b);

/* Writes the factors of b in words into out, e.g. "640 x 480 pixels, antialias recursive depth 6: up to
 * 1089 rays a pixel, blur_samples 37, 1 light (area 33 x 33): 1089 shadow rays a hit, max_depth 64: up
 * to 67580 rays a tree". Cannot fail (cut short if out_size is too small). */
void ray_budget_describe(const struct ray_budget *b, const struct scene *s, int chapter, char *out,
                         size_t out_size);

#endif
