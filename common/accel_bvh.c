/* accel_bvh.c: routing the world's triangle queries through a bounding volume hierarchy (chapter 10). */
#include "accel.h"

#include <stdio.h>

#include "bvh.h"
#include "clock.h"

static bool bvh_closest_any(const void *bvh, const ray *r, double t_min, double t_max, double *t,
                            uint32_t *face) {
    return bvh_closest(bvh, r, t_min, t_max, t, face);
}

static bool bvh_occluded_any(const void *bvh, const ray *r, double t_min, double t_max) {
    return bvh_occluded(bvh, r, t_min, t_max);
}

static void bvh_for_each_hit_any(const void *bvh, const ray *r, double t_min, double t_max,
                                 world_hit_visitor visit, void *context) {
    bvh_for_each_hit(bvh, r, t_min, t_max, visit, context);
}

static void bvh_free_any(void *bvh) { bvh_free(bvh); }

bool accel_world_use_bvh(struct accel_world *w, int split, char *err, size_t err_size) {
    double started = clock_seconds();
    struct bvh *bvh = bvh_build(&w->triangles, (enum bvh_split)split);
    double build_ms = 1e3 * (clock_seconds() - started);
    if (bvh == NULL) {
        snprintf(err, err_size, "out of memory building the BVH");
        return false;
    }
    struct bvh_info info;
    bvh_get_info(bvh, &info);
    w->summary = (struct accel_summary){split == BVH_SPLIT_SAH ? "BVH (binned SAH)" : "BVH (median split)",
                                        build_ms, info.nodes, info.leaves, info.max_depth, info.sah_cost};
    w->structure = bvh;
    w->free_structure = bvh_free_any;
    w->accel.structure = bvh;
    w->accel.closest = bvh_closest_any;
    w->accel.occluded = bvh_occluded_any;
    w->accel.for_each_hit = bvh_for_each_hit_any;
    w->world.accel = &w->accel;
    return true;
}
