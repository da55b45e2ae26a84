/* accel_fast_bvh.c: routing the world's triangle queries through chapter 11's fast BVH at a chosen rung. */
#include "accel_fast_bvh.h"

#include <stdio.h>

#include "clock.h"
#include "fast_bvh.h"
#include "fast_bvh_build.h"
#include "float_triangle.h"

static bool fast_bvh_closest_any(const void *bvh, const ray *r, double t_min, double t_max, double *t,
                                 uint32_t *face) {
    return fast_bvh_closest(bvh, r, t_min, t_max, t, face);
}

static bool fast_bvh_occluded_any(const void *bvh, const ray *r, double t_min, double t_max) {
    return fast_bvh_occluded(bvh, r, t_min, t_max);
}

static void fast_bvh_for_each_hit_any(const void *bvh, const ray *r, double t_min, double t_max,
                                      world_hit_visitor visit, void *context) {
    fast_bvh_for_each_hit(bvh, r, t_min, t_max, visit, context);
}

static void fast_bvh_free_any(void *bvh) { fast_bvh_free(bvh); }

bool accel_world_use_fast_bvh(struct accel_world *w, int split, int rung, char *err, size_t err_size) {
    if (rung == FAST_BVH_RUNG_PLAIN) /* chapter 10's hierarchy, unchanged */
        return accel_world_use_bvh(w, split, err, err_size);
    double started = clock_seconds();
    int tree_rung = rung == FAST_BVH_RUNG_PACKET ? FAST_BVH_RUNG_LEAN : rung; /* rung 10 walks rung 9's tree */
    struct fast_bvh *bvh = fast_bvh_build(&w->triangles, (enum bvh_split)split, (enum fast_bvh_rung)tree_rung);
    double build_ms = 1e3 * (clock_seconds() - started);
    if (bvh == NULL) {
        snprintf(err, err_size, "out of memory building the BVH");
        return false;
    }
    struct bvh_info info;
    fast_bvh_get_info(bvh, &info);
    static const char *const names[2][FAST_BVH_RUNG_TOP + 1] = {
        {"", "", "fast BVH, rung 2 wide (median split)", "fast BVH, rung 3 simd (median split)",
         "fast BVH, rung 4 prefetch (median split)", "fast BVH, rung 5 build (median split)",
         "fast BVH, rung 6 float (median split)", "fast BVH, rung 7 compact (median split)",
         "fast BVH, rung 8 eight (median split)", "fast BVH, rung 9 lean (median split)"},
        {"", "", "fast BVH, rung 2 wide (binned SAH)", "fast BVH, rung 3 simd (binned SAH)",
         "fast BVH, rung 4 prefetch (binned SAH)", "fast BVH, rung 5 build (binned SAH)",
         "fast BVH, rung 6 float (binned SAH)", "fast BVH, rung 7 compact (binned SAH)",
         "fast BVH, rung 8 eight (binned SAH)", "fast BVH, rung 9 lean (binned SAH)"},
    };
    /* Rung 8 on a processor without AVX2 (or told to act so) built rung 6's tree: the report says so. */
    static const char *const fallback[2][2] = {
        {"fast BVH, rung 8 eight without AVX2: rung 6's tree and walk (median split)",
         "fast BVH, rung 8 eight without AVX2: rung 6's tree and walk (binned SAH)"},
        {"fast BVH, rung 9 lean without AVX2: rung 6's tree and walk (median split)",
         "fast BVH, rung 9 lean without AVX2: rung 6's tree and walk (binned SAH)"},
    };
    /* Rung 10, camera rays in packets (chapter 11 renders them), over rung 9's tree or its fallback. */
    static const char *const packet[2][2] = {
        {"fast BVH, rung 10 packet without AVX2: rung 6's tree (median split)",
         "fast BVH, rung 10 packet without AVX2: rung 6's tree (binned SAH)"},
        {"fast BVH, rung 10 packet (median split)", "fast BVH, rung 10 packet (binned SAH)"}};
    /* Rung 11, rung 9's tree with the float triangle test, or rung 9's fallback without AVX2. */
    static const char *const exact[2][2] = {
        {"fast BVH, rung 11 exact-float without AVX2: rung 6's tree and walk (median split)",
         "fast BVH, rung 11 exact-float without AVX2: rung 6's tree and walk (binned SAH)"},
        {"fast BVH, rung 11 exact-float (median split)", "fast BVH, rung 11 exact-float (binned SAH)"}};
    bool wide = rung == FAST_BVH_RUNG_EIGHT || rung == FAST_BVH_RUNG_LEAN;
    const char *name = rung == FAST_BVH_RUNG_EXACT    ? exact[bvh->nodes8 != NULL][split == BVH_SPLIT_SAH]
                       : rung == FAST_BVH_RUNG_PACKET ? packet[bvh->nodes8 != NULL][split == BVH_SPLIT_SAH]
                       : wide && bvh->nodes8 == NULL ? fallback[rung == FAST_BVH_RUNG_LEAN][split == BVH_SPLIT_SAH]
                                                     : names[split == BVH_SPLIT_SAH][rung];
    w->summary = (struct accel_summary){name, build_ms, info.nodes, info.leaves,
                                        info.max_depth, info.sah_cost};
    w->structure = bvh;
    w->free_structure = fast_bvh_free_any;
    w->accel.structure = bvh;
    w->accel.closest = fast_bvh_closest_any;
    w->accel.occluded = fast_bvh_occluded_any;
    w->accel.for_each_hit = fast_bvh_for_each_hit_any;
    w->world.accel = &w->accel;
    return true;
}

struct accel_world *accel_world_create_at_rung(struct scene *s, const struct accel_choice *c, int rung, char *err,
                                               size_t err_size) {
    struct accel_world *w = accel_world_create(s, c, err, err_size);
    if (w != NULL && c->kind == ACCEL_BVH &&
        !accel_world_use_fast_bvh(w, c->sah ? BVH_SPLIT_SAH : BVH_SPLIT_MEDIAN, rung, err, err_size)) {
        accel_world_destroy(w);
        return NULL;
    }
    return w;
}
