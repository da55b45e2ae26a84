/* stats.h: counters for rays by kind and intersection tests by primitive kind (chapter 1).
 *
 * Counting is part of the lesson: every chapter prints how many rays it traced and how many
 * intersection tests it ran, so the effect of each new idea is a number, not a feeling. The counters
 * are per thread (no locks, no shared cache lines on the hot path); the renderer adds each thread's
 * counters into a total with stats_add when the thread finishes. */
#ifndef WHITTED_STATS_H
#define WHITTED_STATS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

struct stats {
    uint64_t primary_rays;   /* camera rays: one per pixel, more with chapter 12's anti-aliasing */
    uint64_t pixels;         /* pixels rendered (0 when only rays were counted: then one ray a pixel) */
    uint64_t camera_rays_max; /* the most camera rays one pixel took (chapter 12); stats_add keeps the largest */
    uint64_t shadow_rays;    /* one per (hit, light facing the surface) pair, from chapter 7 */
    uint64_t reflected_rays; /* from chapter 8; only rays within the depth limit */
    uint64_t refracted_rays; /* from chapter 8 */
    uint64_t sphere_tests;
    uint64_t triangle_tests;
    /* triangle tests skipped because the ray missed a mesh's bounding box: the mesh's face count for
     * each miss. Counted only by world.c's per-mesh culling (chapters 5 to 8, and 9 and 10 with
     * --accel none). Not work done: triangle_tests + triangle_tests_culled is what the same rays would
     * cost without bounding boxes, as in chapter 4's brute-force loop. */
    uint64_t triangle_tests_culled;
    uint64_t plane_tests;
    uint64_t box_tests;      /* box primitives and bounding boxes (chapter 5 on) */
    uint64_t node_visits;    /* kd-tree or BVH nodes visited (chapters 9 and 10) */
    uint64_t instance_node_visits; /* top-level nodes visited, over instances (chapter 16); their objects' own
                                      trees' nodes count in node_visits */
    /* Chapter 8's limits (docs/08-recursion.md, "Ray trees that cannot run away"): */
    uint64_t adc_saves;          /* secondary rays not traced, their weight being under adc_bailout */
    uint64_t crossings_capped;   /* rays stopped after RAY_MAX_CROSSINGS pass-throughs */
    uint64_t budget_cut;         /* secondary rays not traced, the camera ray's RAY_TREE_BUDGET spent */
    uint64_t interior_overflows; /* objects entered but not remembered, the interior list being full */
    /* Pixels whose colour came out not a number or infinite: none, unless the renderer has a fault that
     * the scene brings out. The picture is then not written (cli.c), rather than written with those
     * pixels black. */
    uint64_t non_finite_pixels;
};

/* The calling thread's counters. Intersection code increments fields directly:
 * stats_thread.sphere_tests++. */
extern _Thread_local struct stats stats_thread;

/* Adds every counter of `from` into `into`. Cannot fail. */
void stats_add(struct stats *into, const struct stats *from);

/* Resets the calling thread's counters to zero. Cannot fail. */
void stats_reset_thread(void);

/* Prints the non-zero counters of `s` to `out`, one aligned "name: value" line each, with the
 * total number of rays, then each counter divided by the number of pixels (of camera rays when no
 * pixels were counted); when some pixel took more than one camera ray, also the camera rays per pixel,
 * their mean and their most. Cannot fail (write errors on `out` are the caller's to check). */
void stats_print(FILE *out, const struct stats *s);

/* Prints one warning line to `out` for each of chapter 8's limits that cut a ray tree short (crossings
 * capped, ray budget spent, interior list full), saying how often and which limit; prints nothing when
 * none did. adc_bailout savings are not warnings: they are POV-Ray's rule. Cannot fail. */
void stats_warn_limits(FILE *out, const struct stats *s);

#endif
