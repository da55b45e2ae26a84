/* check_accel.c: the coursework checks of chapters 9 to 11: the kd-tree's split rules and traversal,
 * the BVH's builds and traversal, the fast BVH's two-lane box test and its order of children, on small
 * meshes whose right answers are known (the coursework kit). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "check.h"
#include "fast_bvh.h"
#include "fast_bvh_build.h"
#include "hit.h"
#include "kdtree.h"
#include "stats.h"
#include "triangle.h"

/* Hits are compared to their exact values within this: far above rounding, far below a mistake. */
#define ACCEL_TOLERANCE 1e-9

/* Triangles in the test meshes: 64 makes a tree six levels deep, small enough to describe. */
#define ROW_TRIANGLES 64

/* A mesh of `count` triangles, each 0.5 wide in the plane z = z0 + k * dz and centred at
 * (x0 + k * dx, y0 + k * dy): with d = 0 all are stacked, else they form a row with gaps. Aborts when
 * memory runs out (a check program, not a library). */
static void add_triangle(struct mesh *m, vec3 centre) {
    size_t v = m->vertex_count;
    m->vertices[v] = vec3_add(centre, vec3_make(-0.25, -0.25, 0));
    m->vertices[v + 1] = vec3_add(centre, vec3_make(0.25, -0.25, 0));
    m->vertices[v + 2] = vec3_add(centre, vec3_make(-0.25, 0.25, 0));
    m->faces[m->face_count++] = (struct mesh_face){{(uint32_t)v, (uint32_t)v + 1, (uint32_t)v + 2}};
    m->vertex_count += 3;
}

static struct mesh new_mesh(size_t faces) {
    struct mesh m = {calloc(3 * faces, sizeof(vec3)), 0, calloc(faces, sizeof(struct mesh_face)), 0};
    if (m.vertices == NULL || m.faces == NULL)
        abort();
    return m;
}

/* ROW_TRIANGLES triangles in a row along `axis`, 1 apart. */
static struct mesh row(int axis) {
    struct mesh m = new_mesh(ROW_TRIANGLES);
    for (int k = 0; k < ROW_TRIANGLES; k++)
        add_triangle(&m, vec3_make(axis == 0 ? k : 0, axis == 1 ? k : 0, axis == 2 ? k : 0));
    return m;
}

/* Two clusters of ROW_TRIANGLES / 2 triangles, around x = 0 and x = 100: a tree should cut the gap. */
static struct mesh two_clusters(void) {
    struct mesh m = new_mesh(ROW_TRIANGLES);
    for (int k = 0; k < ROW_TRIANGLES; k++)
        add_triangle(&m, vec3_make((k % 2) * 100.0 + (k / 2 % 4) * 0.3, (k / 8) * 0.3, 0));
    return m;
}

/* Three layers at z = 0, -1, -2, each a 4 x 4 grid of triangle pairs covering [0, 4]^2 (ROW_TRIANGLES
 * * 1.5 faces): a ray down -z from z = 5 first meets the layer z = 0, at t = 5. */
static struct mesh layers(void) {
    struct mesh m = new_mesh(96);
    for (int z = 0; z < 3; z++)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                size_t v = m.vertex_count;
                m.vertices[v] = vec3_make(i, j, -z);
                m.vertices[v + 1] = vec3_make(i + 1, j, -z);
                m.vertices[v + 2] = vec3_make(i + 1, j + 1, -z);
                m.vertices[v + 3] = vec3_make(i, j + 1, -z);
                m.faces[m.face_count++] = (struct mesh_face){{(uint32_t)v, (uint32_t)v + 1, (uint32_t)v + 2}};
                m.faces[m.face_count++] = (struct mesh_face){{(uint32_t)v, (uint32_t)v + 2, (uint32_t)v + 3}};
                m.vertex_count += 4;
            }
    return m;
}

/* ---- 9.1 the seed's rule ----------------------------------------------------------------------- */

static bool seed_case(int axis, char *why, size_t why_size) {
    static const char *const names[] = {"x", "y", "z"};
    struct mesh m = row(axis);
    check_calling("seed_plane (through kdtree_build)", "%d triangles in a row along %s", ROW_TRIANGLES, names[axis]);
    struct kdtree *k = kdtree_build(&m, KD_SPLIT_SEED);
    struct kdtree_info info = {0};
    char invalid[512] = "";
    bool valid = k != NULL && kdtree_is_valid(k, &m, invalid, sizeof invalid);
    if (k != NULL)
        kdtree_get_info(k, &info);
    kdtree_free(k);
    mesh_free(&m);
    /* Median planes halve 64 triangles five times: 32 leaves of 2 at depth 5 if no triangle straddled;
     * a plane through a triangle's centre copies it into both halves, which may add a level. */
    if (valid && info.leaves >= ROW_TRIANGLES / 2 && info.max_depth <= 8)
        return true;
    if (!valid)
        snprintf(why, why_size, "kdtree_build(KD_SPLIT_SEED) on %d triangles in a row along %s made a broken tree: %s",
                 ROW_TRIANGLES, names[axis], k == NULL ? "it returned NULL" : invalid);
    else
        snprintf(why, why_size, "kdtree_build(KD_SPLIT_SEED) on %d separate triangles in a row along %s: median planes "
                 "on the %s axis should give at least %d leaves of at most 2 triangles, depth about 6; your tree has %zu "
                 "leaves, depth %zu%s", ROW_TRIANGLES, names[axis], names[axis], ROW_TRIANGLES / 2, info.leaves,
                 info.max_depth, info.leaves <= 1 ? ": seed_plane never chose a plane? (the axis whose median leaves "
                 "the most triangles whole)" : "");
    return false;
}

CHECK(check_seed_row_x) { return seed_case(0, why, why_size); }
CHECK(check_seed_row_z) { return seed_case(2, why, why_size); }

/* ---- 9.2 the SAH ------------------------------------------------------------------------------ */

/* A bound on the predicted cost per ray of an SAH tree over two_clusters: the reference's is 4.32, a
 * single leaf's 64; the margin leaves room for other tie rules. */
#define SAH_TWO_CLUSTERS_COST 6.0

CHECK(check_sah_gap) {
    struct mesh m = two_clusters();
    check_calling("sah_plane (through kdtree_build)", "two clusters of %d triangles at x = 0 and x = 100",
                  ROW_TRIANGLES / 2);
    struct kdtree *k = kdtree_build(&m, KD_SPLIT_SAH);
    struct kdtree_info info = {0};
    char invalid[512] = "";
    bool valid = k != NULL && kdtree_is_valid(k, &m, invalid, sizeof invalid);
    if (k != NULL)
        kdtree_get_info(k, &info);
    bool gap = valid && k->nodes[0].axis == 0 && k->nodes[0].split > 1.0f && k->nodes[0].split < 100.0f;
    kdtree_free(k);
    mesh_free(&m);
    if (gap && info.empty_leaves > 0 && info.sah_cost < SAH_TWO_CLUSTERS_COST)
        return true;
    snprintf(why, why_size, "kdtree_build(KD_SPLIT_SAH) on two clusters of %d triangles at x = 0 and x = 100: the "
             "heuristic cuts the root on x, between the clusters, and cuts the gap away (an empty leaf), for a "
             "predicted cost below %.0f; yours %s, has %zu nodes, %zu empty leaves, cost %.2f%s",
             ROW_TRIANGLES / 2, SAH_TWO_CLUSTERS_COST, !valid ? "is broken" : gap ? "cuts between the clusters" : "does "
             "not cut the root between the clusters", info.nodes, info.empty_leaves, info.sah_cost,
             info.leaves <= 1 ? ": sah_plane never chose a plane? (price every bound of every box)" : "");
    return false;
}

/* ---- 9.3 and 10.3: traversal -------------------------------------------------------------------- */

/* "a hit at t = 5.00" (t with `digits` decimals) or `none` ("a miss", "no hit"), for a check's message. */
static const char *hit_text(bool hit, double t, int digits, const char *none, char buffer[static 64]) {
    if (!hit)
        return none;
    snprintf(buffer, 64, "a hit at t = %.*f", digits, t);
    return buffer;
}

typedef bool (*closest_fn)(const void *tree, const ray *r, double t_min, double t_max, double *t, uint32_t *face);

static bool kd_closest(const void *tree, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    return kdtree_closest(tree, r, t_min, t_max, t, face);
}
static bool bvh_closest_fn(const void *tree, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    return bvh_closest(tree, r, t_min, t_max, t, face);
}
static bool fast_closest_fn(const void *tree, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    return fast_bvh_closest(tree, r, t_min, t_max, t, face);
}

/* The nearest of the hits fast_bvh_for_each_hit lists (lowest face on a tie): the walk that visits every
 * box the ray enters, in slot order, so it tests the box test (11.1) without the nearest-first order
 * (11.2). */
struct nearest_listed {
    bool found;
    double t;
    uint32_t face;
};

static bool keep_nearest(void *context, double t, uint32_t face) {
    struct nearest_listed *n = context;
    if (!n->found || t < n->t || (t == n->t && face < n->face))
        *n = (struct nearest_listed){true, t, face};
    return true;
}

static bool fast_every_hit_fn(const void *tree, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    struct nearest_listed n = {false, 0.0, 0};
    fast_bvh_for_each_hit(tree, r, t_min, t_max, keep_nearest, &n);
    if (n.found) {
        *t = n.t;
        *face = n.face;
    }
    return n.found;
}

/* Rays into the three layers: down from above (nearest z = 0, t = 5), up from below (nearest z = -2,
 * t = 3), from above but starting between the layers, and beside the grid (a miss). */
static bool layered_rays(const char *what, const void *tree, closest_fn closest, char *why, size_t why_size) {
    const struct { ray r; double t; const char *say; } cases[] = {
        {{{1.3, 2.6, 5}, {0, 0, -1}}, 5.0, "from (1.3, 2.6, 5) down -z: the top layer z = 0 is nearest"},
        {{{3.7, 0.2, -5}, {0, 0, 1}}, 3.0, "from (3.7, 0.2, -5) up +z: the bottom layer z = -2 is nearest"},
        {{{2.5, 2.5, -0.5}, {0, 0, -1}}, 0.5, "from (2.5, 2.5, -0.5) down -z, between the layers: z = -1 is nearest"},
        {{{0.5, 0.5, 5}, {0, 0.6, -0.8}}, NAN, "from (0.5, 0.5, 5) along (0, 0.6, -0.8): z = 0 at y = 4.25 is beside "
                                                "the grid, z = -1 at y = 5 too; no hit"},
        {{{-3, 2.2, -1.5}, {1, 0, 0}}, NAN, "from (-3, 2.2, -1.5) along +x, between the layers: no hit"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double expected = cases[k].t;
        double t = NAN;
        uint32_t face = 0;
        check_calling(what, "three layers of triangles at z = 0, -1, -2 over [0, 4]^2 and a ray %s", cases[k].say);
        bool hit = closest(tree, &cases[k].r, 1e-9, INFINITY, &t, &face);
        if (isnan(expected) ? !hit : hit && fabs(t - expected) < ACCEL_TOLERANCE)
            continue;
        char said[64], got[64];
        snprintf(why, why_size, "%s, three layers of triangles at z = 0, -1, -2 over [0, 4]^2, a ray %s: expected %s; "
                 "got %s%s", what, cases[k].say, hit_text(!isnan(expected), expected, 2, "a miss", said),
                 hit_text(hit, t, 2, "no hit", got),
                 hit && !isnan(expected) && t > expected ? ": a farther layer; visit the near child first and stop "
                                                           "only when nothing nearer can be left" : "");
        return false;
    }
    return true;
}

/* layers() in a mesh with room for `extra` more triangles (three new corners each), added with add_face. */
static struct mesh layers_with_room(size_t extra) {
    struct mesh m = layers();
    struct mesh big = new_mesh(m.face_count + extra);
    memcpy(big.vertices, m.vertices, m.vertex_count * sizeof *m.vertices);
    memcpy(big.faces, m.faces, m.face_count * sizeof *m.faces);
    big.vertex_count = m.vertex_count;
    big.face_count = m.face_count;
    mesh_free(&m);
    return big;
}

/* Adds the triangle a, b, c to m, which has room for it. */
static void add_face(struct mesh *m, vec3 a, vec3 b, vec3 c) {
    size_t v = m->vertex_count;
    m->vertices[v] = a;
    m->vertices[v + 1] = b;
    m->vertices[v + 2] = c;
    m->faces[m->face_count++] = (struct mesh_face){{(uint32_t)v, (uint32_t)v + 1, (uint32_t)v + 2}};
    m->vertex_count += 3;
}

/* layers() with four walls across x (planes x = 0.5, 1.5, 2.5, 3.5, each two triangles) and one long
 * slanted triangle, in the plane x + z = 2.5, that crosses them all: a tree must list it in many cells,
 * and a ray can hit it in the first cell it enters at a point beyond that cell, with a nearer wall in
 * the next. */
static struct mesh crossed_layers(void) {
    struct mesh big = layers_with_room(9);
    for (int w = 0; w < 4; w++) {
        double x = w + 0.5;
        add_face(&big, vec3_make(x, 0, -3), vec3_make(x, 4, -3), vec3_make(x, 4, 1));
        add_face(&big, vec3_make(x, 0, -3), vec3_make(x, 4, 1), vec3_make(x, 0, 1));
    }
    add_face(&big, vec3_make(4.5, -1, -2), vec3_make(4.5, 6, -2), vec3_make(-1, 2.5, 3.5));
    return big;
}

/* The nearest hit of r among all of m's faces, tested one by one (the brute-force loop): the answer a
 * tree must give. */
static bool every_face_closest(const struct mesh *m, const ray *r, double *t) {
    struct hit h = hit_nothing(INFINITY);
    bool hit = triangle_mesh_closest(m, 0, r, 1e-9, &h);
    *t = h.t;
    return hit;
}

/* Rays over crossed_layers(): down -z, along +x and along -x on grids of 12 x 12 starting points, a
 * little tilted so that none runs along an edge. Each nearest hit must be the brute-force loop's. */
static bool crossing_rays(const char *what, const void *tree, closest_fn closest, char *why, size_t why_size) {
    struct mesh m = crossed_layers();
    const struct { vec3 origin, step_i, step_j, direction; const char *say; } families[] = {
        {{-0.41, -0.43, 5}, {0.43, 0, 0}, {0, 0.43, 0}, {0.013, 0.011, -1}, "down -z"},
        {{-2, -0.37, -2.93}, {0, 0.41, 0}, {0, 0, 0.37}, {1, 0.012, 0.009}, "along +x"},
        {{7, -0.37, -2.93}, {0, 0.41, 0}, {0, 0, 0.37}, {-1, 0.012, 0.009}, "along -x"},
    };
    bool ok = true;
    for (size_t f = 0; f < sizeof families / sizeof families[0] && ok; f++)
        for (int i = 0; i < 12 && ok; i++)
            for (int j = 0; j < 12 && ok; j++) {
                vec3 o = vec3_add(families[f].origin,
                                  vec3_add(vec3_scale(families[f].step_i, i), vec3_scale(families[f].step_j, j)));
                ray r = {o, vec3_normalize(families[f].direction)};
                double expected = NAN, t = NAN;
                uint32_t face = 0;
                bool want = every_face_closest(&m, &r, &expected);
                check_calling(what, "three layers of triangles crossed by four walls and one long slanted triangle, "
                              "and a ray from (%.2f, %.2f, %.2f) %s", o.x, o.y, o.z, families[f].say);
                bool hit = closest(tree, &r, 1e-9, INFINITY, &t, &face);
                if (hit == want && (!hit || fabs(t - expected) < ACCEL_TOLERANCE))
                    continue;
                char said[64], got[64];
                snprintf(why, why_size, "%s, three layers of triangles crossed by four walls and one long slanted "
                         "triangle, a ray from (%.2f, %.2f, %.2f) %s: testing every triangle gives %s; yours "
                         "gave %s%s", what, o.x, o.y, o.z, families[f].say, hit_text(want, expected, 4, "a miss", said),
                         hit_text(hit, t, 4, "no hit", got),
                         hit && want && t > expected ? ": a farther hit. The first hit found need not be the nearest (a "
                         "triangle or box can reach past the next); stop only when nothing nearer can be left" : "");
                ok = false;
            }
    mesh_free(&m);
    return ok;
}

CHECK(check_kd_crossing) {
    struct mesh m = crossed_layers();
    check_calling("kdtree_build", "three layers of triangles crossed by four walls and one long slanted triangle");
    struct kdtree *k = kdtree_build(&m, KD_SPLIT_SAH);
    bool ok = k != NULL && crossing_rays("kdtree_closest", k, kd_closest, why, why_size);
    if (k == NULL)
        snprintf(why, why_size, "kdtree_build returned NULL");
    kdtree_free(k);
    mesh_free(&m);
    return ok;
}

CHECK(check_kd_traversal) {
    struct mesh m = layers();
    check_calling("kdtree_build", "three layers of triangles at z = 0, -1, -2 over [0, 4]^2");
    struct kdtree *k = kdtree_build(&m, KD_SPLIT_SAH);
    bool ok = k != NULL && layered_rays("kdtree_closest", k, kd_closest, why, why_size);
    if (k == NULL)
        snprintf(why, why_size, "kdtree_build returned NULL");
    kdtree_free(k);
    mesh_free(&m);
    return ok;
}

CHECK(check_kd_occluded) {
    struct mesh m = layers();
    check_calling("kdtree_build", "three layers of triangles at z = 0, -1, -2 over [0, 4]^2");
    struct kdtree *k = kdtree_build(&m, KD_SPLIT_SAH);
    ray down = {{1.5, 1.5, 5}, {0, 0, -1}};
    check_calling("kdtree_occluded", "three layers of triangles at z = 0, -1, -2 over [0, 4]^2 and a ray from "
                  "(1.5, 1.5, 5) down -z");
    bool ok = k != NULL && kdtree_occluded(k, &down, 1e-9, 10.0) && !kdtree_occluded(k, &down, 1e-9, 4.0);
    kdtree_free(k);
    mesh_free(&m);
    if (!ok)
        snprintf(why, why_size, "kdtree_occluded: a ray from (1.5, 1.5, 5) down -z over three layers of triangles "
                 "(z = 0, -1, -2) is blocked within t < 10 and clear within t < 4 (the first layer is 5 away)");
    return ok;
}

/* ---- 10.1, 10.2 the BVH builds ------------------------------------------------------------------ */

static bool bvh_case(const char *what, struct mesh m, enum bvh_split split, size_t min_leaves, char *why,
                     size_t why_size) {
    check_calling(split == BVH_SPLIT_MEDIAN ? "split_median (through bvh_build)" : "split_sah (through bvh_build)",
                  "%s", what);
    struct bvh *b = bvh_build(&m, split);
    struct bvh_info info = {0};
    char invalid[512] = "";
    bool valid = b != NULL && bvh_is_valid(b, &m, invalid, sizeof invalid);
    if (b != NULL)
        bvh_get_info(b, &info);
    bvh_free(b);
    mesh_free(&m);
    if (valid && info.leaves >= min_leaves)
        return true;
    if (!valid)
        snprintf(why, why_size, "bvh_build on %s made a broken hierarchy: %s", what,
                 b == NULL ? "it returned NULL" : invalid);
    else
        snprintf(why, why_size, "bvh_build on %s: expected at least %zu leaves; yours has %zu (depth %zu)%s", what,
                 min_leaves, info.leaves, info.max_depth, info.leaves <= 1 ? ": the split never divides the triangles?" : "");
    return false;
}

CHECK(check_bvh_median) {
    /* Halving 64 triangles until at most two are left: 32 leaves. */
    return bvh_case("64 triangles in a row along x, median split", row(0), BVH_SPLIT_MEDIAN, ROW_TRIANGLES / 2, why,
                    why_size);
}

CHECK(check_bvh_sah) {
    return bvh_case("two clusters of 32 triangles 100 apart, SAH split (the gap must be cut)", two_clusters(),
                    BVH_SPLIT_SAH, 2, why, why_size);
}

/* The SAH's predicted cost per ray (in triangle tests) of a good tree over unequal_clusters(): cutting
 * the 100-unit gap first, the binned SAH reaches 1.27; halving by count, as the median rule does, puts
 * 24 triangles of the big cluster in one box with the small cluster and costs 3.24, and leaves of 8
 * cost more still. 2 lies well between. */
#define SAH_UNEQUAL_MAX_COST 2.0

/* 56 triangles in a 8 x 7 patch at x = 0 and 8 in a 4 x 2 patch at x = 100. */
static struct mesh unequal_clusters(void) {
    struct mesh m = new_mesh(ROW_TRIANGLES);
    for (int k = 0; k < ROW_TRIANGLES; k++)
        add_triangle(&m, k < 56 ? vec3_make((k % 8) * 0.3, (k / 8) * 0.3, 0)
                                : vec3_make(100 + (k % 4) * 0.3, (k / 4 % 2) * 0.3, 0));
    return m;
}

CHECK(check_bvh_sah_unequal) {
    struct mesh m = unequal_clusters();
    check_calling("split_sah (through bvh_build)", "56 triangles at x = 0 and 8 at x = 100");
    struct bvh *b = bvh_build(&m, BVH_SPLIT_SAH);
    mesh_free(&m);
    struct bvh_info info = {0};
    if (b != NULL)
        bvh_get_info(b, &info);
    bvh_free(b);
    if (b != NULL && info.sah_cost <= SAH_UNEQUAL_MAX_COST)
        return true;
    snprintf(why, why_size, "bvh_build(BVH_SPLIT_SAH) on 56 triangles at x = 0 and 8 at x = 100: a tree that cuts the "
             "gap first costs about 1.3 triangle tests per ray by the SAH (bvh_info.sah_cost), at most %.1f; yours "
             "costs %.2f%s", SAH_UNEQUAL_MAX_COST, info.sah_cost,
             b == NULL ? " (bvh_build returned NULL)" : ": is every plane priced, area(L) n(L) + area(R) n(R), and the "
             "cheapest taken? (halving by count costs 3.2)");
    return false;
}

CHECK(check_bvh_traversal) {
    struct mesh m = layers();
    check_calling("bvh_build", "three layers of triangles at z = 0, -1, -2 over [0, 4]^2");
    struct bvh *b = bvh_build(&m, BVH_SPLIT_SAH);
    bool ok = b != NULL && layered_rays("bvh_closest", b, bvh_closest_fn, why, why_size);
    if (b == NULL)
        snprintf(why, why_size, "bvh_build returned NULL");
    bvh_free(b);
    mesh_free(&m);
    return ok;
}

CHECK(check_bvh_crossing) {
    struct mesh m = crossed_layers();
    check_calling("bvh_build", "three layers of triangles crossed by four walls and one long slanted triangle");
    struct bvh *b = bvh_build(&m, BVH_SPLIT_SAH);
    bool ok = b != NULL && crossing_rays("bvh_closest", b, bvh_closest_fn, why, why_size);
    if (b == NULL)
        snprintf(why, why_size, "bvh_build returned NULL");
    bvh_free(b);
    mesh_free(&m);
    return ok;
}

/* Triangle tests per ray that a near-child-first walk stays within on a stack of ROW_TRIANGLES
 * triangles seen end on: it meets the top one in its first leaf (at most a few triangles), and every
 * other box then starts beyond that hit. A walk that takes children in any other order tests most of
 * the stack (tens of triangles). 8 leaves room for leaves of a few triangles and an extra leaf. */
#define NEAR_FIRST_MAX_TESTS 8.0

/* Rays straight down from z = 100 and up from z = -100 through the stack of row(2), at a few points
 * inside the triangles (x, y > -0.25, x + y < 0): whether each finds its nearest hit (t = 37 down, 100
 * up), and the triangle tests per ray in *per_ray. */
static bool stack_rays(const char *what, const void *tree, closest_fn closest, double *per_ray) {
    /* Points whose coordinates are floats too, so that chapter 11's rung 6 walks these rays in float
     * (straight down or up, the origin's x and y decide the slabs of those axes exactly in float). */
    const double at[][2] = {{-0.125, -0.125}, {0.0625, -0.1875}, {-0.1875, 0.125}, {-0.15625, -0.0625}};
    int rays = 0;
    uint64_t before = stats_thread.triangle_tests;
    bool right = true;
    for (int k = 0; k < 4; k++)
        for (int up = 0; up < 2; up++) {
            ray r = {{at[k][0], at[k][1], up ? -100.0 : 100.0}, {0, 0, up ? 1.0 : -1.0}};
            double t = NAN;
            uint32_t face = 0;
            char ray_text[160];
            check_calling(what, "%d triangles stacked at z = 0 .. %d and %s", ROW_TRIANGLES, ROW_TRIANGLES - 1,
                          check_ray_text(&r, ray_text));
            right = right && closest(tree, &r, 1e-9, INFINITY, &t, &face) && fabs(t - (up ? 100.0 : 37.0)) < ACCEL_TOLERANCE;
            rays++;
        }
    *per_ray = (double)(stats_thread.triangle_tests - before) / rays;
    return right;
}

/* Runs stack_rays on `tree`, a hierarchy over row(2) that `what` names ("bvh_closest"), and fails with
 * `wrong_hits` when a hit is wrong or with `slow` when the rays need more than NEAR_FIRST_MAX_TESTS
 * triangle tests each. */
static bool near_first_case(const char *what, const void *tree, closest_fn closest, const char *wrong_hits,
                            const char *slow, char *why, size_t why_size) {
    double per_ray;
    bool right = stack_rays(what, tree, closest, &per_ray);
    if (right && per_ray <= NEAR_FIRST_MAX_TESTS)
        return true;
    if (!right)
        snprintf(why, why_size, "%s on %d triangles stacked at z = 0 .. %d, rays straight down from z = 100 and up from "
                 "z = -100: the nearest hits are at t = 37 and t = 100%s", what, ROW_TRIANGLES, ROW_TRIANGLES - 1,
                 wrong_hits);
    else
        snprintf(why, why_size, "%s on %d triangles stacked at z = 0 .. %d, rays straight down from z = 100 and up from "
                 "z = -100: the right hits, but %.1f triangle tests per ray, where visiting the nearer child first needs "
                 "at most %.0f (the first leaf holds the nearest hit, and every other box starts beyond it). %s", what,
                 ROW_TRIANGLES, ROW_TRIANGLES - 1, per_ray, NEAR_FIRST_MAX_TESTS, slow);
    return false;
}

CHECK(check_bvh_near_first) {
    struct mesh m = row(2); /* the triangles stacked at z = 0, 1, ..., 63 over the same square */
    check_calling("bvh_build", "%d triangles stacked at z = 0 .. %d", ROW_TRIANGLES, ROW_TRIANGLES - 1);
    struct bvh *b = bvh_build(&m, BVH_SPLIT_SAH);
    mesh_free(&m);
    if (b == NULL) {
        snprintf(why, why_size, "bvh_build returned NULL");
        return false;
    }
    bool ok = near_first_case("bvh_closest", b, bvh_closest_fn, "", "Are the children taken far one first?", why,
                              why_size);
    bvh_free(b);
    return ok;
}

/* layers() and one needle-thin triangle (a sliver) above them at z = 1, 3 long and 1e-6 high: the sine of
 * the angle between its edges from the first corner is 6.7e-7, below the 1e-6 under which the BVH keeps a
 * triangle out of the tree (BVH_SLIVER_SINE in bvh.c) and has every ray test it. */
static struct mesh layers_and_a_sliver(void) {
    struct mesh big = layers_with_room(1);
    add_face(&big, vec3_make(0.5, 2, 1), vec3_make(3.5, 2, 1), vec3_make(2, 2 + 1e-6, 1));
    return big;
}

/* Builds the BVH (SAH) over mesh(), which `what` describes; NULL, saying so in why, when bvh_build fails. */
static struct bvh *bvh_over(struct mesh (*mesh)(void), const char *what, char *why, size_t why_size) {
    struct mesh m = mesh();
    check_calling("bvh_build", "%s", what);
    struct bvh *b = bvh_build(&m, BVH_SPLIT_SAH);
    mesh_free(&m);
    if (b == NULL)
        snprintf(why, why_size, "bvh_build returned NULL on %s", what);
    return b;
}

CHECK(check_bvh_slivers) {
    struct bvh *b = bvh_over(layers_and_a_sliver, "three layers of triangles and a needle-thin one above them", why,
                             why_size);
    if (b == NULL)
        return false;
    /* Rays down -z from z = 5 through the sliver, where it is 1e-6 high: its hit at t = 4 is nearer than
     * the top layer's at t = 5. */
    const double xs[] = {1.0, 2.0, 2.9};
    bool ok = true;
    for (size_t k = 0; k < sizeof xs / sizeof xs[0] && ok; k++) {
        double height = xs[k] < 2 ? (xs[k] - 0.5) / 1.5 * 1e-6 : (3.5 - xs[k]) / 1.5 * 1e-6;
        ray r = {{xs[k], 2 + height / 2, 5}, {0, 0, -1}};
        double t = NAN;
        uint32_t face = 0;
        char ray_text[160];
        check_calling("bvh_closest", "three layers of triangles and a needle-thin one above them at z = 1, and %s",
                      check_ray_text(&r, ray_text));
        bool hit = bvh_closest(b, &r, 1e-9, INFINITY, &t, &face);
        if (hit && fabs(t - 4.0) < ACCEL_TOLERANCE)
            continue;
        char got[64];
        snprintf(why, why_size, "bvh_closest on three layers of triangles (z = 0, -1, -2) under a needle-thin triangle "
                 "at z = 1, %s: it meets the needle-thin one first, at t = 4.00; yours gave %s%s", ray_text,
                 hit_text(hit, t, 2, "no hit", got),
                 hit && t > 4.0 ? ". Needle-thin triangles (slivers) are kept out of the tree, after the others in "
                 "b->triangles (from tree_count to triangle_count): every walk tests them first" : "");
        ok = false;
    }
    bvh_free(b);
    return ok;
}

CHECK(check_bvh_counted) {
    struct bvh *b = bvh_over(layers, "three layers of triangles at z = 0, -1, -2 over [0, 4]^2", why, why_size);
    if (b == NULL)
        return false;
    ray down = {{1.3, 2.6, 5}, {0, 0, -1}};
    double t;
    uint32_t face;
    struct stats before = stats_thread;
    check_calling("bvh_closest", "three layers of triangles at z = 0, -1, -2 over [0, 4]^2 and a ray from "
                  "(1.3, 2.6, 5) down -z");
    bvh_closest(b, &down, 1e-9, INFINITY, &t, &face);
    bvh_free(b);
    uint64_t nodes = stats_thread.node_visits - before.node_visits, boxes = stats_thread.box_tests - before.box_tests,
             triangles = stats_thread.triangle_tests - before.triangle_tests;
    if (nodes > 0 && boxes > 0 && triangles > 0)
        return true;
    snprintf(why, why_size, "bvh_closest on three layers of triangles and a ray from (1.3, 2.6, 5) down -z: bvh.h says "
             "a walk adds to the thread's counters (stats_thread) the nodes it visits, the boxes it tests and the "
             "triangles it tests (the program prints them as `node visits`, `box tests` and `triangle tests`); yours "
             "counted %llu, %llu and %llu, where a walk that finds the top layer needs at least one of each",
             (unsigned long long)nodes, (unsigned long long)boxes, (unsigned long long)triangles);
    return false;
}

/* ---- 11.1 the fast BVH's two-lane box test ------------------------------------------------------ */

/* What a failing 11.1 check adds to its message: how child_pair_hit is meant to work. */
#define PAIR_HINT " child_pair_hit(n, h, ...) tests children 2h and 2h + 1 of node n (lanes 0 and 1 of a double2): " \
                  "on each axis the near plane is bounds[a][s->near[a]] (the high bound when the ray runs towards " \
                  "minus), the entry is the largest near t and the exit the smallest far t, and bit k of the mask is " \
                  "set when lane k's entry is at or before its exit"

/* Builds the fast BVH over mesh() at rung `rung` (rung 3 and up test children with child_pair_hit) and
 * runs `rays` on it, each ray's nearest hit taken from all the hits the walk lists; on a failure, adds
 * PAIR_HINT to the message. */
static bool fast_case(struct mesh (*mesh)(void), enum fast_bvh_rung rung,
                      bool (*rays)(const char *, const void *, closest_fn, char *, size_t), char *why, size_t why_size) {
    struct mesh m = mesh();
    check_calling("fast_bvh_build", "a mesh of %zu triangles at rung %d", m.face_count, (int)rung);
    struct fast_bvh *b = fast_bvh_build(&m, BVH_SPLIT_SAH, rung);
    char what[128];
    snprintf(what, sizeof what, "the nearest of the hits fast_bvh_for_each_hit lists at rung %d (%s)", (int)rung,
             fast_bvh_rung_name((int)rung));
    bool ok = b != NULL && rays(what, b, fast_every_hit_fn, why, why_size);
    if (b == NULL)
        snprintf(why, why_size, "fast_bvh_build returned NULL");
    else if (!ok) {
        size_t used = strlen(why);
        snprintf(why + used, why_size - used, ".%s", PAIR_HINT);
    }
    fast_bvh_free(b);
    mesh_free(&m);
    return ok;
}

/* At rung 5, the top rung whose every ray tests boxes with child_pair_hit (rung 6 tests them in float,
 * child_quad_hit, and falls back on child_pair_hit only for rays its bound does not cover). */
CHECK(check_fast_layers) { return fast_case(layers, FAST_BVH_RUNG_BUILD, layered_rays, why, why_size); }

CHECK(check_fast_crossing) { return fast_case(crossed_layers, FAST_BVH_RUNG_BUILD, crossing_rays, why, why_size); }

/* ---- 11.2 the children hit, nearest first ------------------------------------------------------- */

CHECK(check_fast_near_first) {
    struct mesh m = row(2); /* the triangles stacked at z = 0, 1, ..., 63 over the same square */
    /* At rung 6, whose walk chapters 11 to 14 take (their default, rung 7, walks it over compact
     * leaves), so that this check needs only what the chapters' own pictures run: its float build
     * (which goes with task 10.2) and its float box test, child_quad_hit (which goes with task 11.1). */
    check_calling("fast_bvh_build", "%d triangles stacked at z = 0 .. %d, rung 6", ROW_TRIANGLES, ROW_TRIANGLES - 1);
    struct fast_bvh *b = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_FLOAT);
    mesh_free(&m);
    if (b == NULL) {
        snprintf(why, why_size, "fast_bvh_build returned NULL");
        return false;
    }
    bool ok = near_first_case("fast_bvh_closest at rung 6", b, fast_closest_fn, ", and yours are not. Does "
                              "nearest_first write the slot k of every child whose bit k is set in hit, and return how "
                              "many?", "Does nearest_first order the children by entry[k >> 1][k & 1], the smallest "
                              "first?", why, why_size);
    fast_bvh_free(b);
    return ok;
}
