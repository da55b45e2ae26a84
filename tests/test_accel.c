/* test_accel.c: the kd-tree, the BVH and the fast BVH at every rung (chapters 9, 10 and 11) against the
 * brute-force loop, ray by ray.
 *
 * Every ray is first traced by brute force: triangle_intersect on every face, which gives each face's
 * t. The answer for any window t_min < t < t_max follows from those: the nearest hit (the lowest face
 * among equal t), whether anything is hit, and the set of faces hit. All the structures (chapter 10's
 * BVH with the median and the SAH split, kd-tree with the dissertation's rule and the SAH, chapter 11's
 * fast BVH at every rung by the SAH, at rungs 7 to 9 by the median, and rungs 8 and 9 as without AVX2)
 * must then give exactly that answer: the same t to the last bit, the same face, the same set, each face
 * reported once.
 *
 * The rays are chosen to hurt: random ones, rays aimed at faces, vertices and shared edges, rays along
 * the axes (with signed zero components) through vertices, rays lying in planes through vertices or
 * on the padded planes the structures cut space with (TRIANGLE_BOX_PAD and KD_BOX_PAD are 2^-20 of the
 * mesh size), origins on vertices, on the mesh's box faces and inside the mesh, tiny and non-unit
 * directions, and windows that end or start exactly at a hit. The meshes: random triangle soups with
 * degenerate, coincident and axis-aligned triangles, a tessellated sphere, stacked axis-aligned grids,
 * and the bunny and the small teapot when scenes/models has them. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "fast_bvh.h"
#include "fast_bvh_build.h"
#include "fast_bvh_eight.h"
#include "float4.h"
#include "fast_bvh_lean.h"
#include "float_triangle.h"
#include "hit.h"
#include "kdtree.h"
#include "mesh.h"
#include "mesh_load.h"
#include "speck_triangle.h"
#include "stats.h"
#include "triangle.h"

/* Seconds each of the larger tests may take. make test-accel-long builds this file again with 0 (no
 * limit), since a test's own timeout outranks the runner's --timeout 0. */
#ifndef ACCEL_TEST_TIMEOUT
#define ACCEL_TEST_TIMEOUT 120
#endif

/* Brute-force triangle tests per mesh (rays * faces): about 0.2 s each at -O2. */
#define ACCEL_TEST_BUDGET 2.5e7
#define ACCEL_TEST_MAX_RAYS 12000
#define ACCEL_TEST_MIN_RAYS 600

/* The fraction of the mesh's size by which the structures pad their boxes (triangle.h, kdtree.c). */
#define ACCEL_PAD TRIANGLE_BOX_PAD

/* ---- reproducible random numbers (splitmix64) ---------------------------------------------------- */

struct rng {
    uint64_t state;
};

static uint64_t rng_next(struct rng *g) {
    uint64_t z = (g->state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double rng_unit(struct rng *g) { return (double)(rng_next(g) >> 11) * 0x1.0p-53; } /* [0, 1) */

static double rng_between(struct rng *g, double lo, double hi) { return lo + (hi - lo) * rng_unit(g); }

static uint32_t rng_below(struct rng *g, uint32_t n) { return (uint32_t)(rng_next(g) % n); }

static vec3 rng_direction(struct rng *g) {
    for (;;) {
        vec3 d = {rng_between(g, -1, 1), rng_between(g, -1, 1), rng_between(g, -1, 1)};
        double length = vec3_length(d);
        if (length > 0.1 && length <= 1.0)
            return vec3_scale(d, 1.0 / length);
    }
}

static void set_axis(vec3 *v, int axis, double value) {
    if (axis == 0)
        v->x = value;
    else if (axis == 1)
        v->y = value;
    else
        v->z = value;
}

/* ---- meshes made here ------------------------------------------------------------------------- */

struct builder {
    struct mesh m;
    size_t vertex_capacity, face_capacity;
};

static uint32_t add_vertex(struct builder *b, vec3 p) {
    if (b->m.vertex_count == b->vertex_capacity) {
        b->vertex_capacity = b->vertex_capacity ? 2 * b->vertex_capacity : 64;
        b->m.vertices = realloc(b->m.vertices, b->vertex_capacity * sizeof *b->m.vertices);
        cr_assert_not_null(b->m.vertices);
    }
    b->m.vertices[b->m.vertex_count] = p;
    return (uint32_t)b->m.vertex_count++;
}

static void add_face(struct builder *b, uint32_t v0, uint32_t v1, uint32_t v2) {
    if (b->m.face_count == b->face_capacity) {
        b->face_capacity = b->face_capacity ? 2 * b->face_capacity : 64;
        b->m.faces = realloc(b->m.faces, b->face_capacity * sizeof *b->m.faces);
        cr_assert_not_null(b->m.faces);
    }
    b->m.faces[b->m.face_count++] = (struct mesh_face){{v0, v1, v2}};
}

static void add_triangle(struct builder *b, vec3 p0, vec3 p1, vec3 p2) {
    uint32_t v0 = add_vertex(b, p0), v1 = add_vertex(b, p1), v2 = add_vertex(b, p2);
    add_face(b, v0, v1, v2);
}

/* A coordinate in [0, 1), sometimes snapped to sixteenths so that planes through vertices repeat. */
static double soup_coordinate(struct rng *g) {
    double x = rng_unit(g);
    return rng_below(g, 4) == 0 ? floor(x * 16.0) / 16.0 : x;
}

static vec3 soup_point(struct rng *g) { return vec3_make(soup_coordinate(g), soup_coordinate(g), soup_coordinate(g)); }

/* `count` random triangles in the unit cube: mostly small ones, some spanning the cube, some flat in
 * an axis plane, some sharing vertices and edges with earlier ones, and some degenerate (two corners
 * equal, all three equal, corners on an axis-aligned line or on a general line) or coincident with an
 * earlier triangle (same corners in the same order, which ties exactly, or in another order). */
static struct mesh make_soup(uint64_t seed, size_t count) {
    struct rng g = {seed};
    struct builder b = {0};
    while (b.m.face_count < count) {
        uint32_t kind = rng_below(&g, 100);
        size_t faces = b.m.face_count;
        if (kind < 8 && faces > 0) { /* coincident with an earlier face */
            const uint32_t *v = b.m.faces[rng_below(&g, (uint32_t)faces)].v;
            if (kind < 4)
                add_face(&b, v[0], v[1], v[2]);
            else
                add_face(&b, v[1], v[2], v[0]);
        } else if (kind < 14) { /* degenerate */
            vec3 a = soup_point(&g), c = soup_point(&g);
            switch (kind % 4) {
            case 0:
                add_triangle(&b, a, a, c);
                break;
            case 1:
                add_triangle(&b, a, a, a);
                break;
            case 2: {
                vec3 p = a, q = a;
                int axis = (int)rng_below(&g, 3);
                set_axis(&p, axis, vec3_axis(a, axis) + 0.25);
                set_axis(&q, axis, vec3_axis(a, axis) + 0.5);
                add_triangle(&b, a, p, q);
                break;
            }
            default:
                add_triangle(&b, a, vec3_scale(vec3_add(a, c), 0.5), c);
            }
        } else if (kind < 26 && faces > 0) { /* shares one or two corners with an earlier face */
            const uint32_t *v = b.m.faces[rng_below(&g, (uint32_t)faces)].v;
            vec3 near = b.m.vertices[v[0]];
            uint32_t extra = add_vertex(&b, vec3_add(near, vec3_scale(rng_direction(&g), 0.05)));
            if (kind % 2 == 0)
                add_face(&b, v[1], v[0], extra); /* the shared edge v0-v1, reversed as in a mesh */
            else
                add_face(&b, v[0], extra, add_vertex(&b, vec3_add(near, vec3_scale(rng_direction(&g), 0.05))));
        } else if (kind < 34) { /* flat in a plane x, y or z = constant */
            int axis = (int)rng_below(&g, 3);
            double level = soup_coordinate(&g);
            vec3 p[3];
            for (int k = 0; k < 3; k++) {
                p[k] = soup_point(&g);
                set_axis(&p[k], axis, level);
            }
            add_triangle(&b, p[0], p[1], p[2]);
        } else if (kind < 42) { /* large */
            add_triangle(&b, soup_point(&g), soup_point(&g), soup_point(&g));
        } else { /* small */
            vec3 centre = soup_point(&g);
            double size = rng_between(&g, 0.005, 0.1);
            add_triangle(&b, vec3_add_scaled(centre, rng_direction(&g), size),
                         vec3_add_scaled(centre, rng_direction(&g), size),
                         vec3_add_scaled(centre, rng_direction(&g), size));
        }
    }
    return b.m;
}

/* A UV sphere: `rings` bands of latitude, `segments` of longitude, poles included. */
static struct mesh make_sphere(int rings, int segments, vec3 centre, double radius) {
    struct builder b = {0};
    uint32_t north = add_vertex(&b, vec3_add(centre, vec3_make(0, radius, 0)));
    for (int i = 1; i < rings; i++) {
        double theta = M_PI * i / rings;
        for (int j = 0; j < segments; j++) {
            double phi = 2.0 * M_PI * j / segments;
            add_vertex(&b, vec3_add(centre, vec3_scale(vec3_make(sin(theta) * cos(phi), cos(theta),
                                                                sin(theta) * sin(phi)), radius)));
        }
    }
    uint32_t south = add_vertex(&b, vec3_add(centre, vec3_make(0, -radius, 0)));
    for (int j = 0; j < segments; j++) {
        int next = (j + 1) % segments;
        add_face(&b, north, 1 + next, 1 + j);
        uint32_t last = 1 + (uint32_t)((rings - 2) * segments);
        add_face(&b, south, last + j, last + next);
    }
    for (int i = 0; i + 2 < rings; i++)
        for (int j = 0; j < segments; j++) {
            uint32_t a = 1 + (uint32_t)(i * segments + j), c = 1 + (uint32_t)(i * segments + (j + 1) % segments);
            add_face(&b, a, c, a + (uint32_t)segments);
            add_face(&b, c, c + (uint32_t)segments, a + (uint32_t)segments);
        }
    return b.m;
}

/* Three stacked square grids at z = 0, 1, 2 with integer corners (every cell two triangles sharing a
 * diagonal), crossed by a wall at x = n / 2: all coordinates exact, many coplanar triangles, many
 * shared edges hit at exactly the same t. */
static struct mesh make_grids(int n) {
    struct builder b = {0};
    for (int layer = 0; layer < 3; layer++) {
        uint32_t first = (uint32_t)b.m.vertex_count;
        for (int i = 0; i <= n; i++)
            for (int j = 0; j <= n; j++)
                add_vertex(&b, vec3_make(i, j, layer));
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                uint32_t a = first + (uint32_t)(i * (n + 1) + j);
                add_face(&b, a, a + (uint32_t)(n + 1), a + 1);
                add_face(&b, a + 1, a + (uint32_t)(n + 1), a + (uint32_t)(n + 2));
            }
    }
    uint32_t first = (uint32_t)b.m.vertex_count;
    for (int j = 0; j <= n; j++)
        for (int k = 0; k <= 4; k++)
            add_vertex(&b, vec3_make(n / 2, j, k * 0.5));
    for (int j = 0; j < n; j++)
        for (int k = 0; k < 4; k++) {
            uint32_t a = first + (uint32_t)(j * 5 + k);
            add_face(&b, a, a + 5, a + 1);
            add_face(&b, a + 1, a + 5, a + 6);
        }
    return b.m;
}

/* ---- the four structures behind one interface ------------------------------------------------- */

typedef bool (*visit_fn)(void *ctx, double t, uint32_t face);

struct accel {
    const char *name;
    void *structure;
    bool (*closest)(const void *s, const ray *r, double t_min, double t_max, double *t, uint32_t *face);
    bool (*occluded)(const void *s, const ray *r, double t_min, double t_max);
    void (*for_each_hit)(const void *s, const ray *r, double t_min, double t_max, visit_fn visit, void *ctx);
    void (*release)(void *s);
};

static bool bvh_closest_of(const void *s, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    return bvh_closest(s, r, t_min, t_max, t, face);
}
static bool bvh_occluded_of(const void *s, const ray *r, double t_min, double t_max) {
    return bvh_occluded(s, r, t_min, t_max);
}
static void bvh_for_each_hit_of(const void *s, const ray *r, double t_min, double t_max, visit_fn visit, void *ctx) {
    bvh_for_each_hit(s, r, t_min, t_max, visit, ctx);
}
static void bvh_free_of(void *s) { bvh_free(s); }
static bool fast_closest_of(const void *s, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    return fast_bvh_closest(s, r, t_min, t_max, t, face);
}
static bool fast_occluded_of(const void *s, const ray *r, double t_min, double t_max) {
    return fast_bvh_occluded(s, r, t_min, t_max);
}
static void fast_for_each_hit_of(const void *s, const ray *r, double t_min, double t_max, visit_fn visit, void *ctx) {
    fast_bvh_for_each_hit(s, r, t_min, t_max, visit, ctx);
}
static void fast_free_of(void *s) { fast_bvh_free(s); }
static bool kd_closest_of(const void *s, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    return kdtree_closest(s, r, t_min, t_max, t, face);
}
static bool kd_occluded_of(const void *s, const ray *r, double t_min, double t_max) {
    return kdtree_occluded(s, r, t_min, t_max);
}
static void kd_for_each_hit_of(const void *s, const ray *r, double t_min, double t_max, visit_fn visit, void *ctx) {
    kdtree_for_each_hit(s, r, t_min, t_max, visit, ctx);
}
static void kd_free_of(void *s) { kdtree_free(s); }

/* Chapters 9 and 10's four, chapter 11's rungs by the SAH (2 to 9, and 11), its rungs 7, 8, 9 and 11 by
 * the median, and rungs 8, 9 and 11 as built without AVX2 (rung 6's tree: the fallback, which the machine
 * running the tests may not need). */
#define ACCEL_COUNT (4 + FAST_BVH_RUNG_TOP - FAST_BVH_RUNG_FIRST + 1 + 8)

/* Builds chapter 11's fast BVH over m at `rung` by `split` (rung 11: rung 9's with float triangles), checks its
 * invariants and puts it in *out. */
static void build_fast(const struct mesh *m, const char *mesh_name, enum bvh_split split, int rung, struct accel *out) {
    static const char *const names[2][FAST_BVH_RUNG_LAST + 1] = {
        {"", "", "fast BVH median rung 2", "fast BVH median rung 3", "fast BVH median rung 4", "fast BVH median rung 5",
         "fast BVH median rung 6", "fast BVH median rung 7", "fast BVH median rung 8", "fast BVH median rung 9", "",
         "fast BVH median rung 11"},
        {"", "", "fast BVH SAH rung 2", "fast BVH SAH rung 3", "fast BVH SAH rung 4", "fast BVH SAH rung 5",
         "fast BVH SAH rung 6", "fast BVH SAH rung 7", "fast BVH SAH rung 8", "fast BVH SAH rung 9", "",
         "fast BVH SAH rung 11"}};
    char why[256];
    const char *name = names[split == BVH_SPLIT_SAH][rung];
    struct fast_bvh *b = fast_bvh_build(m, split, (enum fast_bvh_rung)rung);
    cr_assert_not_null(b, "%s: %s ran out of memory", mesh_name, name);
    cr_assert(fast_bvh_is_valid(b, m, why, sizeof why), "%s: %s invalid: %s", mesh_name, name, why);
    bool float_walk = b->nodes8 != NULL && b->float_range; /* rung 11's float triangle test can run */
    cr_assert(rung != FAST_BVH_RUNG_EXACT || ((b->float_corners != NULL) == float_walk &&
                                              (!float_walk || b->lean_corners == NULL)),
              "%s: %s has no float copy of its triangles where it walks in float, or keeps rung 9's", mesh_name,
              name);
    *out = (struct accel){name, b, fast_closest_of, fast_occluded_of, fast_for_each_hit_of, fast_free_of};
}

/* Builds all the structures over m and checks each one's invariants. */
static void build_all(const struct mesh *m, const char *mesh_name, struct accel out[ACCEL_COUNT]) {
    char why[256];
    struct bvh *bvh_median = bvh_build(m, BVH_SPLIT_MEDIAN), *bvh_sah = bvh_build(m, BVH_SPLIT_SAH);
    struct kdtree *kd_seed = kdtree_build(m, KD_SPLIT_SEED), *kd_sah = kdtree_build(m, KD_SPLIT_SAH);
    cr_assert(bvh_median && bvh_sah && kd_seed && kd_sah, "%s: a build ran out of memory", mesh_name);
    cr_assert(bvh_is_valid(bvh_median, m, why, sizeof why), "%s: BVH median invalid: %s", mesh_name, why);
    cr_assert(bvh_is_valid(bvh_sah, m, why, sizeof why), "%s: BVH SAH invalid: %s", mesh_name, why);
    cr_assert(kdtree_is_valid(kd_seed, m, why, sizeof why), "%s: kd-tree seed invalid: %s", mesh_name, why);
    cr_assert(kdtree_is_valid(kd_sah, m, why, sizeof why), "%s: kd-tree SAH invalid: %s", mesh_name, why);
    out[0] = (struct accel){"BVH median", bvh_median, bvh_closest_of, bvh_occluded_of, bvh_for_each_hit_of, bvh_free_of};
    out[1] = (struct accel){"BVH SAH", bvh_sah, bvh_closest_of, bvh_occluded_of, bvh_for_each_hit_of, bvh_free_of};
    out[2] = (struct accel){"kd-tree seed", kd_seed, kd_closest_of, kd_occluded_of, kd_for_each_hit_of, kd_free_of};
    out[3] = (struct accel){"kd-tree SAH", kd_sah, kd_closest_of, kd_occluded_of, kd_for_each_hit_of, kd_free_of};
    for (int rung = FAST_BVH_RUNG_FIRST; rung <= FAST_BVH_RUNG_TOP; rung++)
        build_fast(m, mesh_name, BVH_SPLIT_SAH, rung, &out[4 + rung - FAST_BVH_RUNG_FIRST]);
    build_fast(m, mesh_name, BVH_SPLIT_SAH, FAST_BVH_RUNG_EXACT, &out[ACCEL_COUNT - 8]);
    build_fast(m, mesh_name, BVH_SPLIT_MEDIAN, FAST_BVH_RUNG_COMPACT, &out[ACCEL_COUNT - 7]);
    build_fast(m, mesh_name, BVH_SPLIT_MEDIAN, FAST_BVH_RUNG_EIGHT, &out[ACCEL_COUNT - 6]);
    build_fast(m, mesh_name, BVH_SPLIT_MEDIAN, FAST_BVH_RUNG_LEAN, &out[ACCEL_COUNT - 5]);
    build_fast(m, mesh_name, BVH_SPLIT_MEDIAN, FAST_BVH_RUNG_EXACT, &out[ACCEL_COUNT - 4]);
    cr_assert_eq(setenv(FAST_BVH_NO_AVX2_VARIABLE, "1", 1), 0);
    build_fast(m, mesh_name, BVH_SPLIT_SAH, FAST_BVH_RUNG_EIGHT, &out[ACCEL_COUNT - 3]);
    build_fast(m, mesh_name, BVH_SPLIT_SAH, FAST_BVH_RUNG_LEAN, &out[ACCEL_COUNT - 2]);
    build_fast(m, mesh_name, BVH_SPLIT_SAH, FAST_BVH_RUNG_EXACT, &out[ACCEL_COUNT - 1]);
    cr_assert_eq(unsetenv(FAST_BVH_NO_AVX2_VARIABLE), 0);
    for (int k = ACCEL_COUNT - 3; k < ACCEL_COUNT; k++) {
        const struct fast_bvh *fallback = out[k].structure;
        cr_assert(fallback->nodes8 == NULL && fallback->lean_corners == NULL && fallback->float_corners == NULL,
                  "%s: %s told there is no AVX2 built 8-wide nodes", mesh_name, out[k].name);
    }
    out[ACCEL_COUNT - 3].name = "fast BVH SAH rung 8 without AVX2";
    out[ACCEL_COUNT - 2].name = "fast BVH SAH rung 9 without AVX2";
    out[ACCEL_COUNT - 1].name = "fast BVH SAH rung 11 without AVX2";
}

/* Builds the kd-tree over m by each rule, checking each one's invariants; returns how many. */
static int build_kdtrees(const struct mesh *m, const char *mesh_name, struct accel out[ACCEL_COUNT]) {
    static const enum kd_split rules[] = {KD_SPLIT_SEED, KD_SPLIT_SAH};
    static const char *const names[] = {"kd-tree seed", "kd-tree SAH"};
    for (int k = 0; k < 2; k++) {
        char why[256];
        struct kdtree *tree = kdtree_build(m, rules[k]);
        cr_assert_not_null(tree, "%s: %s ran out of memory", mesh_name, names[k]);
        cr_assert(kdtree_is_valid(tree, m, why, sizeof why), "%s: %s invalid: %s", mesh_name, names[k], why);
        out[k] = (struct accel){names[k], tree, kd_closest_of, kd_occluded_of, kd_for_each_hit_of, kd_free_of};
    }
    return 2;
}

static void free_all(struct accel a[ACCEL_COUNT]) {
    for (int s = 0; s < ACCEL_COUNT; s++)
        a[s].release(a[s].structure);
}

/* ---- the oracle and the comparison ------------------------------------------------------------ */

struct report {
    uint32_t face;
    double t;
};

struct checker {
    const char *mesh_name;
    const struct mesh *m;
    struct accel accels[ACCEL_COUNT];
    int accel_count;
    double *t_of_face;   /* this ray's t for every face; NAN where triangle_intersect misses */
    uint32_t *hit_faces; /* the faces with a t, hit_count of them */
    size_t hit_count;
    uint32_t *stamp;     /* stamp[face] == generation: already reported on this call */
    uint32_t generation;
    struct report *reports; /* what for_each_hit reported, report_count of them */
    size_t report_count;
    size_t windows;      /* windows checked, for the log */
};

static bool collect_report(void *ctx, double t, uint32_t face) {
    struct checker *c = ctx;
    if (c->report_count < c->m->face_count + 1)
        c->reports[c->report_count] = (struct report){face, t};
    c->report_count++;
    return true;
}

/* Sets c up for m with its structures already built into c->accels. */
static void checker_alloc(struct checker *c) {
    size_t n = c->m->face_count + 1;
    c->t_of_face = malloc(n * sizeof *c->t_of_face);
    c->hit_faces = malloc(n * sizeof *c->hit_faces);
    c->stamp = calloc(n, sizeof *c->stamp);
    c->reports = malloc(n * sizeof *c->reports);
    cr_assert(c->t_of_face && c->hit_faces && c->stamp && c->reports, "out of memory");
}

static void checker_init(struct checker *c, const char *mesh_name, const struct mesh *m) {
    *c = (struct checker){.mesh_name = mesh_name, .m = m};
    build_all(m, mesh_name, c->accels);
    c->accel_count = ACCEL_COUNT;
    checker_alloc(c);
}

/* The same for the kd-trees alone (build_kdtrees). */
static void checker_init_kdtrees(struct checker *c, const char *mesh_name, const struct mesh *m) {
    *c = (struct checker){.mesh_name = mesh_name, .m = m};
    c->accel_count = build_kdtrees(m, mesh_name, c->accels);
    checker_alloc(c);
}

static void checker_free(struct checker *c) {
    for (int s = 0; s < c->accel_count; s++)
        c->accels[s].release(c->accels[s].structure);
    free(c->t_of_face);
    free(c->hit_faces);
    free(c->stamp);
    free(c->reports);
}

/* The brute-force pass: every face's t for ray r, whatever the window. */
static void trace_brute_force(struct checker *c, const ray *r) {
    c->hit_count = 0;
    struct triangle_ray prepared = triangle_ray_make(r); /* triangle_intersect, without redoing this per face */
    for (size_t f = 0; f < c->m->face_count; f++) {
        const uint32_t *v = c->m->faces[f].v;
        double t, u, w;
        if (triangle_intersect_prepared(c->m->vertices[v[0]], c->m->vertices[v[1]], c->m->vertices[v[2]], &prepared,
                                        -INFINITY, INFINITY, &t, &u, &w)) {
            c->t_of_face[f] = t;
            c->hit_faces[c->hit_count++] = (uint32_t)f;
        } else {
            c->t_of_face[f] = NAN;
        }
    }
}

#define RAY_FORMAT "ray (%a, %a, %a) + t (%a, %a, %a), window (%a, %a)"
#define RAY_ARGS(r, t_min, t_max)                                                                         \
    (r)->origin.x, (r)->origin.y, (r)->origin.z, (r)->direction.x, (r)->direction.y, (r)->direction.z,   \
        (t_min), (t_max)

/* Checks every structure's three answers for ray r in the window (t_min, t_max). */
static void check_window(struct checker *c, const ray *r, double t_min, double t_max) {
    bool expect_hit = false;
    double expect_t = INFINITY;
    uint32_t expect_face = UINT32_MAX;
    size_t expect_count = 0;
    for (size_t k = 0; k < c->hit_count; k++) {
        uint32_t f = c->hit_faces[k];
        double t = c->t_of_face[f];
        if (!(t > t_min && t < t_max))
            continue;
        expect_count++;
        if (!expect_hit || t < expect_t || (t == expect_t && f < expect_face)) {
            expect_hit = true;
            expect_t = t;
            expect_face = f;
        }
    }
    c->windows++;
    for (int s = 0; s < c->accel_count; s++) {
        const struct accel *a = &c->accels[s];
        double t = -1.0;
        uint32_t face = UINT32_MAX - 1;
        bool hit = a->closest(a->structure, r, t_min, t_max, &t, &face);
        if (hit != expect_hit || (hit && (t != expect_t || face != expect_face)))
            cr_assert_fail("%s on %s: closest gives %s t=%a face %u, brute force %s t=%a face %u; " RAY_FORMAT, a->name,
                           c->mesh_name, hit ? "hit" : "miss", t, face, expect_hit ? "hit" : "miss", expect_t,
                           expect_face, RAY_ARGS(r, t_min, t_max));
        bool occluded = a->occluded(a->structure, r, t_min, t_max);
        if (occluded != expect_hit)
            cr_assert_fail("%s on %s: occluded says %d, brute force %d; " RAY_FORMAT, a->name, c->mesh_name,
                           occluded, expect_hit, RAY_ARGS(r, t_min, t_max));

        c->report_count = 0;
        c->generation++;
        a->for_each_hit(a->structure, r, t_min, t_max, collect_report, c);
        if (c->report_count != expect_count)
            cr_assert_fail("%s on %s: for_each_hit reported %zu hits, brute force has %zu; " RAY_FORMAT, a->name,
                           c->mesh_name, c->report_count, expect_count, RAY_ARGS(r, t_min, t_max));
        for (size_t k = 0; k < c->report_count; k++) {
            struct report rep = c->reports[k];
            if (rep.face >= c->m->face_count || c->stamp[rep.face] == c->generation)
                cr_assert_fail("%s on %s: for_each_hit reported face %u twice or out of range; " RAY_FORMAT, a->name,
                               c->mesh_name, rep.face, RAY_ARGS(r, t_min, t_max));
            c->stamp[rep.face] = c->generation;
            double want = c->t_of_face[rep.face];
            if (!(want > t_min && want < t_max) || rep.t != want)
                cr_assert_fail("%s on %s: for_each_hit reported face %u at t=%a, brute force t=%a; " RAY_FORMAT,
                               a->name, c->mesh_name, rep.face, rep.t, want, RAY_ARGS(r, t_min, t_max));
        }
    }
}

/* ---- the rays --------------------------------------------------------------------------------- */

enum ray_kind {
    RAY_RANDOM,              /* origin anywhere around the mesh, any direction */
    RAY_AT_FACE,             /* aimed at a point of a face (on an edge a quarter of the time) */
    RAY_AT_VERTEX,           /* aimed at a corner */
    RAY_AT_EDGE,             /* aimed at the middle of an edge */
    RAY_ALONG_AXIS_AT_VERTEX,/* parallel to an axis, exactly through a corner, other components +-0 */
    RAY_ALONG_AXIS_AT_FACE,  /* parallel to an axis, through a point of a face */
    RAY_IN_VERTEX_PLANE,     /* inside the plane x, y or z = a corner's coordinate */
    RAY_ON_PADDED_PLANE,     /* origin on (or in) a plane a structure may cut at: a corner +- the pad */
    RAY_FROM_VERTEX,         /* starting exactly at a corner */
    RAY_FROM_BOX_FACE,       /* starting on a face of the mesh's box, often running inside it */
    RAY_FROM_INSIDE,         /* starting inside the mesh's box */
    RAY_ALONG_AXIS,          /* parallel to an axis from anywhere */
    RAY_ODD_DIRECTION,       /* not of unit length (1e-3, 1e3), or with a denormal component */
    RAY_KINDS
};

struct scene_box {
    vec3 lo, hi, centre;
    double size;  /* largest extent */
    double slack; /* added to distances scaled by size: 1e-3, or the size when smaller (a tiny mesh) */
};

static struct scene_box box_of(const struct mesh *m) {
    struct scene_box b = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}, {0, 0, 0}, 0, 0};
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++) {
            b.lo = vec3_min(b.lo, m->vertices[m->faces[f].v[k]]);
            b.hi = vec3_max(b.hi, m->vertices[m->faces[f].v[k]]);
        }
    if (m->face_count == 0)
        b.lo = b.hi = vec3_make(0, 0, 0);
    b.centre = vec3_scale(vec3_add(b.lo, b.hi), 0.5);
    vec3 e = vec3_sub(b.hi, b.lo);
    b.size = fmax(e.x, fmax(e.y, e.z));
    b.slack = b.size > 0.0 && b.size < 1e-3 ? b.size : 1e-3;
    return b;
}

/* A point in the mesh's box grown by half its size on every side. */
static vec3 around(struct rng *g, const struct scene_box *b) {
    double margin = 0.5 * b->size + b->slack;
    return vec3_make(rng_between(g, b->lo.x - margin, b->hi.x + margin), rng_between(g, b->lo.y - margin, b->hi.y + margin),
                     rng_between(g, b->lo.z - margin, b->hi.z + margin));
}

static vec3 random_corner(struct rng *g, const struct mesh *m) {
    return m->vertices[m->faces[rng_below(g, (uint32_t)m->face_count)].v[rng_below(g, 3)]];
}

static vec3 random_face_point(struct rng *g, const struct mesh *m) {
    const uint32_t *v = m->faces[rng_below(g, (uint32_t)m->face_count)].v;
    double u = rng_unit(g), w = rng_unit(g);
    if (u + w > 1.0) {
        u = 1.0 - u;
        w = 1.0 - w;
    }
    if (rng_below(g, 4) == 0)
        w = 0.0; /* on the edge from corner 0 to corner 1 */
    vec3 a = m->vertices[v[0]];
    return vec3_add(a, vec3_add(vec3_scale(vec3_sub(m->vertices[v[1]], a), u), vec3_scale(vec3_sub(m->vertices[v[2]], a), w)));
}

/* A ray from a random origin towards target (or a random direction if they coincide). */
static ray aimed_at(struct rng *g, const struct scene_box *b, vec3 target) {
    vec3 origin = around(g, b);
    vec3 d = vec3_sub(target, origin);
    double length = vec3_length(d);
    return (ray){origin, length > 0 ? vec3_scale(d, 1.0 / length) : rng_direction(g)};
}

/* The unit vector along axis with the given sign; the other components are +0 or -0 at random. */
static vec3 axis_direction(struct rng *g, int axis, double sign) {
    vec3 d = {rng_below(g, 2) ? 0.0 : -0.0, rng_below(g, 2) ? 0.0 : -0.0, rng_below(g, 2) ? 0.0 : -0.0};
    set_axis(&d, axis, sign);
    return d;
}

/* Makes direction d run inside the plane of `axis` (component +-0), unit length again. */
static vec3 flatten(struct rng *g, vec3 d, int axis) {
    set_axis(&d, axis, rng_below(g, 2) ? 0.0 : -0.0);
    double length = vec3_length(d);
    if (length == 0.0) {
        d = axis_direction(g, (axis + 1) % 3, 1.0);
        set_axis(&d, axis, 0.0);
        return d;
    }
    return vec3_scale(d, 1.0 / length);
}

/* The float a structure would use for a box face at x: x - pad rounded down or x + pad rounded up. */
static double padded_plane(double x, double pad, bool above) {
    float f = (float)(above ? x + pad : x - pad);
    if (above && (double)f < x + pad)
        f = nextafterf(f, INFINITY);
    if (!above && (double)f > x - pad)
        f = nextafterf(f, -INFINITY);
    return f;
}

static ray make_ray(struct rng *g, const struct mesh *m, const struct scene_box *b, enum ray_kind kind) {
    int axis = (int)rng_below(g, 3);
    double sign = rng_below(g, 2) ? 1.0 : -1.0;
    switch (kind) {
    case RAY_AT_FACE:
        return aimed_at(g, b, random_face_point(g, m));
    case RAY_AT_VERTEX:
        return aimed_at(g, b, random_corner(g, m));
    case RAY_AT_EDGE: {
        const uint32_t *v = m->faces[rng_below(g, (uint32_t)m->face_count)].v;
        int k = (int)rng_below(g, 3);
        return aimed_at(g, b, vec3_scale(vec3_add(m->vertices[v[k]], m->vertices[v[(k + 1) % 3]]), 0.5));
    }
    case RAY_ALONG_AXIS_AT_VERTEX:
    case RAY_ALONG_AXIS_AT_FACE: {
        vec3 target = kind == RAY_ALONG_AXIS_AT_VERTEX ? random_corner(g, m) : random_face_point(g, m);
        vec3 origin = target;
        set_axis(&origin, axis, vec3_axis(target, axis) - sign * rng_between(g, 0.1, 2.0) * (b->size + b->slack));
        return (ray){origin, axis_direction(g, axis, sign)};
    }
    case RAY_IN_VERTEX_PLANE: {
        vec3 origin = around(g, b);
        set_axis(&origin, axis, vec3_axis(random_corner(g, m), axis));
        return (ray){origin, flatten(g, rng_direction(g), axis)};
    }
    case RAY_ON_PADDED_PLANE: {
        vec3 origin = around(g, b);
        set_axis(&origin, axis, padded_plane(vec3_axis(random_corner(g, m), axis), ACCEL_PAD * b->size, sign > 0));
        vec3 d = rng_direction(g);
        return (ray){origin, rng_below(g, 2) ? flatten(g, d, axis) : d};
    }
    case RAY_FROM_VERTEX:
        return (ray){random_corner(g, m), rng_direction(g)};
    case RAY_FROM_BOX_FACE: {
        vec3 origin = around(g, b);
        set_axis(&origin, axis, vec3_axis(sign > 0 ? b->hi : b->lo, axis));
        vec3 d = rng_direction(g);
        return (ray){origin, rng_below(g, 2) ? flatten(g, d, axis) : d};
    }
    case RAY_FROM_INSIDE: {
        vec3 origin = rng_below(g, 8) == 0 ? b->centre
                                           : vec3_make(rng_between(g, b->lo.x, b->hi.x), rng_between(g, b->lo.y, b->hi.y),
                                                       rng_between(g, b->lo.z, b->hi.z));
        return (ray){origin, rng_direction(g)};
    }
    case RAY_ALONG_AXIS:
        return (ray){around(g, b), axis_direction(g, axis, sign)};
    case RAY_ODD_DIRECTION: {
        ray r = aimed_at(g, b, random_face_point(g, m));
        uint32_t how = rng_below(g, 3);
        if (how == 2)
            set_axis(&r.direction, axis, sign * 0x1p-1060); /* denormal: 1 / it is infinite */
        else
            r.direction = vec3_scale(r.direction, how == 0 ? 1e-3 : 1e3);
        return r;
    }
    default:
        return (ray){around(g, b), rng_direction(g)};
    }
}

/* Traces `count` rays of every kind in turn against c's mesh, each in three windows: a usual one, one
 * ending exactly at a hit and one starting exactly at it (or, without hits, a random and an empty
 * window). */
static void check_rays(struct checker *c, uint64_t seed, size_t count) {
    struct rng g = {seed};
    struct scene_box b = box_of(c->m);
    static const double usual_min[] = {RAY_T_MIN, 0.0, -INFINITY, SHADOW_T_MIN};
    for (size_t i = 0; i < count; i++) {
        ray r = make_ray(&g, c->m, &b, (enum ray_kind)(i % RAY_KINDS));
        trace_brute_force(c, &r);
        double t_min = usual_min[i % 4];
        double t_max = i % 4 == 3 ? rng_between(&g, 0.0, 3.0 * (b.size + 1.0)) : INFINITY;
        check_window(c, &r, t_min, t_max);
        if (c->hit_count > 0) {
            double at = c->t_of_face[c->hit_faces[rng_below(&g, (uint32_t)c->hit_count)]];
            check_window(c, &r, -INFINITY, at);
            check_window(c, &r, at, INFINITY);
        } else {
            double a = rng_between(&g, -1.0, 2.0 * (b.size + 1.0)), z = rng_between(&g, -1.0, 2.0 * (b.size + 1.0));
            check_window(c, &r, fmin(a, z), fmax(a, z));
            check_window(c, &r, fmax(a, z), fmin(a, z));
        }
    }
}

/* WHITTED_ACCEL_RAYS=K multiplies every ray count by K: `make test-accel-long` runs millions of rays. */
static double ray_scale(void) {
    const char *text = getenv("WHITTED_ACCEL_RAYS");
    double scale = text != NULL ? atof(text) : 1.0;
    return scale >= 1.0 ? scale : 1.0;
}

static size_t rays_for(const struct mesh *m) {
    double rays = ACCEL_TEST_BUDGET / (double)(m->face_count > 0 ? m->face_count : 1);
    rays = rays > ACCEL_TEST_MAX_RAYS ? ACCEL_TEST_MAX_RAYS : rays < ACCEL_TEST_MIN_RAYS ? ACCEL_TEST_MIN_RAYS : rays;
    return (size_t)(rays * ray_scale());
}

/* Builds everything over m, checks rays_for(m) rays, frees m. */
static void check_mesh(const char *name, struct mesh *m, uint64_t seed) {
    struct checker c;
    checker_init(&c, name, m);
    check_rays(&c, seed, rays_for(m));
    cr_log_info("%s: %zu faces, %zu rays, %zu windows: all ten structures agree with brute force", name,
                m->face_count, rays_for(m), c.windows);
    checker_free(&c);
    mesh_free(m);
}

static void check_soups(size_t faces, int seeds) {
    for (int s = 0; s < seeds; s++) {
        char name[64];
        snprintf(name, sizeof name, "soup of %zu (seed %d)", faces, s);
        struct mesh m = make_soup(1000003u * faces + (uint64_t)s, faces);
        check_mesh(name, &m, 77 + (uint64_t)s);
    }
}

/* Loads scenes/models/NAME, or skips the test when it is not there (the teapots are generated). */
static void check_model(const char *path) {
    struct mesh m;
    char err[512];
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        cr_skip_test("%s not found (make models)", path);
    fclose(f);
    cr_assert(mesh_load(path, &m, err, sizeof err), "%s", err);
    check_mesh(path, &m, 4242);
}

/* ---- agreement with brute force --------------------------------------------------------------- */

Test(accel, bvh_and_kdtree_match_brute_force_on_soups_of_1_to_10_triangles, .timeout = ACCEL_TEST_TIMEOUT) {
    check_soups(1, 4);
    check_soups(2, 4);
    check_soups(3, 4);
    check_soups(5, 3);
    check_soups(10, 3);
}

Test(accel, bvh_and_kdtree_match_brute_force_on_soups_of_30_to_300_triangles, .timeout = ACCEL_TEST_TIMEOUT) {
    check_soups(30, 3);
    check_soups(100, 3);
    check_soups(300, 2);
}

Test(accel, bvh_and_kdtree_match_brute_force_on_soups_of_1000_triangles, .timeout = ACCEL_TEST_TIMEOUT) { check_soups(1000, 2); }

Test(accel, bvh_and_kdtree_match_brute_force_on_soups_of_3000_triangles, .timeout = ACCEL_TEST_TIMEOUT) { check_soups(3000, 2); }

Test(accel, bvh_and_kdtree_match_brute_force_on_soups_of_5000_triangles, .timeout = ACCEL_TEST_TIMEOUT) { check_soups(5000, 2); }

Test(accel, bvh_and_kdtree_match_brute_force_on_a_sphere_from_inside_and_outside, .timeout = ACCEL_TEST_TIMEOUT) {
    struct mesh m = make_sphere(24, 48, vec3_make(0.25, -0.5, 1.0), 1.5);
    check_mesh("sphere", &m, 11);
}

Test(accel, bvh_and_kdtree_match_brute_force_on_stacked_axis_aligned_grids, .timeout = ACCEL_TEST_TIMEOUT) {
    struct mesh m = make_grids(16);
    check_mesh("grids", &m, 12);
}

Test(accel, bvh_and_kdtree_match_brute_force_on_bunny, .timeout = ACCEL_TEST_TIMEOUT) { check_model("scenes/models/bunny.ply"); }

Test(accel, bvh_and_kdtree_match_brute_force_on_teapot_5k, .timeout = ACCEL_TEST_TIMEOUT) {
    check_model("scenes/models/teapot-5k.ply");
}

/* ---- behaviour of the interface ---------------------------------------------------------------- */

Test(accel, empty_mesh_builds_and_nothing_hits_it) {
    struct mesh empty = {0};
    struct accel a[ACCEL_COUNT];
    build_all(&empty, "empty mesh", a);
    ray r = {{0, 0, -1}, {0, 0, 1}};
    for (int s = 0; s < ACCEL_COUNT; s++) {
        double t;
        uint32_t face;
        cr_expect_not(a[s].closest(a[s].structure, &r, -INFINITY, INFINITY, &t, &face), "%s", a[s].name);
        cr_expect_not(a[s].occluded(a[s].structure, &r, -INFINITY, INFINITY), "%s", a[s].name);
    }
    free_all(a);
}

Test(accel, coincident_copies_of_a_triangle_give_the_lowest_face_index) {
    struct builder b = {0};
    struct rng g = {5};
    for (int k = 0; k < 40; k++) /* clutter, then 12 copies of one triangle, then more clutter */
        add_triangle(&b, soup_point(&g), soup_point(&g), soup_point(&g));
    uint32_t v0 = add_vertex(&b, vec3_make(0, 0, 2)), v1 = add_vertex(&b, vec3_make(1, 0, 2)),
             v2 = add_vertex(&b, vec3_make(0, 1, 2));
    uint32_t first = (uint32_t)b.m.face_count;
    for (int k = 0; k < 12; k++)
        add_face(&b, v0, v1, v2);
    for (int k = 0; k < 40; k++)
        add_triangle(&b, soup_point(&g), soup_point(&g), soup_point(&g));
    struct accel a[ACCEL_COUNT];
    build_all(&b.m, "copies", a);
    ray r = {{0.25, 0.25, 5.0}, {0, 0, -1}}; /* hits the copies first, at t = 3 */
    for (int s = 0; s < ACCEL_COUNT; s++) {
        double t = 0;
        uint32_t face = 0;
        cr_assert(a[s].closest(a[s].structure, &r, RAY_T_MIN, INFINITY, &t, &face), "%s", a[s].name);
        cr_expect_eq(t, 3.0, "%s: t = %a", a[s].name, t);
        cr_expect_eq(face, first, "%s: face %u, want %u", a[s].name, face, first);
    }
    free_all(a);
    mesh_free(&b.m);
}

/* The triangle of triangle/a_triangle_a_few_units_in_the_last_place_across_is_missed_by_a_ray_passing_far_from_it
 * (test_geometry.c) in front of a large one: the ray passes 1.6 units from the tiny one and every structure
 * must find the large one behind it. With two triangles each tree is one leaf, so rung 9 tests both in its
 * four lanes. */
Test(accel, a_ray_passing_far_from_a_triangle_a_unit_in_the_last_place_across_finds_the_one_behind) {
    struct builder b = {0};
    add_triangle(&b, vec3_make(SPECK_A), vec3_make(SPECK_B), vec3_make(SPECK_C));
    add_triangle(&b, vec3_make(-10, -10, -3), vec3_make(10, -10, -3), vec3_make(0, 10, -3));
    struct accel a[ACCEL_COUNT];
    build_all(&b.m, "a tiny triangle before a large one", a);
    ray r = {{0, 0, 0}, {SPECK_DIRECTION}};
    double behind = 3 / -r.direction.z;
    for (int s = 0; s < ACCEL_COUNT; s++) {
        double t = 0;
        uint32_t face = 0;
        cr_assert(a[s].closest(a[s].structure, &r, RAY_T_MIN, INFINITY, &t, &face), "%s", a[s].name);
        cr_expect_eq(face, 1, "%s: face %u at t = %g, want the large triangle", a[s].name, face, t);
        cr_expect_float_eq(t, behind, 1e-12, "%s: t = %a", a[s].name, t);
        cr_expect_not(a[s].occluded(a[s].structure, &r, RAY_T_MIN, 6.0), "%s: occluded before the large triangle",
                      a[s].name);
    }
    free_all(a);
    mesh_free(&b.m);
}

static bool stop_after_first(void *ctx, double t, uint32_t face) {
    (void)t;
    (void)face;
    (*(int *)ctx)++;
    return false;
}

Test(accel, for_each_hit_stops_as_soon_as_visit_returns_false) {
    struct mesh m = make_grids(8); /* a ray down the z axis crosses three layers */
    struct accel a[ACCEL_COUNT];
    build_all(&m, "grids", a);
    ray r = {{2.3, 3.6, 10.0}, {0, 0, -1}};
    for (int s = 0; s < ACCEL_COUNT; s++) {
        int calls = 0;
        a[s].for_each_hit(a[s].structure, &r, 0.0, INFINITY, stop_after_first, &calls);
        cr_expect_eq(calls, 1, "%s: visit called %d times", a[s].name, calls);
    }
    free_all(a);
    mesh_free(&m);
}

Test(accel, structures_test_few_triangles_and_count_nodes_boxes_and_triangles) {
    struct mesh m = make_sphere(64, 128, vec3_make(0, 0, 0), 1.0); /* 16,128 triangles */
    struct accel a[ACCEL_COUNT];
    build_all(&m, "sphere", a);
    struct rng g = {9};
    for (int s = 0; s < ACCEL_COUNT; s++) {
        stats_reset_thread();
        int rays = 2000;
        for (int i = 0; i < rays; i++) {
            vec3 origin = vec3_scale(rng_direction(&g), 4.0), target = vec3_scale(rng_direction(&g), 0.9);
            ray r = {origin, vec3_normalize(vec3_sub(target, origin))}; /* through the sphere */
            double t;
            uint32_t face;
            a[s].closest(a[s].structure, &r, RAY_T_MIN, INFINITY, &t, &face);
        }
        double per_ray = (double)stats_thread.triangle_tests / rays;
        cr_expect(per_ray < 0.01 * (double)m.face_count, "%s: %.1f triangle tests per ray on %zu triangles", a[s].name,
                  per_ray, m.face_count);
        cr_expect_gt(stats_thread.node_visits, (uint64_t)rays, "%s counts node visits", a[s].name);
        cr_expect_gt(stats_thread.box_tests, 0, "%s counts box tests", a[s].name);
    }
    free_all(a);
    mesh_free(&m);
}

Test(accel, info_describes_a_consistent_tree) {
    struct mesh m = make_soup(31, 2000);
    for (int rule = 0; rule < 2; rule++) {
        struct bvh *b = bvh_build(&m, rule ? BVH_SPLIT_SAH : BVH_SPLIT_MEDIAN);
        struct bvh_info bi;
        bvh_get_info(b, &bi);
        cr_expect(bi.leaves > 0 && bi.leaves < bi.nodes && bi.max_depth > 0, "BVH %d: %zu nodes, %zu leaves", rule,
                  bi.nodes, bi.leaves);
        cr_expect(bi.sah_cost > 0 && bi.sah_cost < 2000.0 && bi.build_ms >= 0, "BVH %d: cost %g", rule, bi.sah_cost);
        bvh_free(b);
        struct kdtree *k = kdtree_build(&m, rule ? KD_SPLIT_SAH : KD_SPLIT_SEED);
        struct kdtree_info ki;
        kdtree_get_info(k, &ki);
        cr_expect(ki.leaves > 0 && ki.leaves < ki.nodes && ki.references >= m.face_count && ki.empty_leaves < ki.leaves,
                  "kd %d: %zu nodes, %zu leaves, %zu references", rule, ki.nodes, ki.leaves, ki.references);
        cr_expect(ki.sah_cost > 0, "kd %d: cost %g", rule, ki.sah_cost);
        kdtree_free(k);
    }
    mesh_free(&m);
}

/* What kdtree_for_each_hit reported: each face's reports, counted. */
struct reports {
    uint8_t *times; /* per face, saturating at 255 */
    size_t total;
};

static bool count_report(void *ctx, double t, uint32_t face) {
    (void)t;
    struct reports *r = ctx;
    r->times[face] += r->times[face] < UINT8_MAX;
    r->total++;
    return true;
}

/* 100,000 copies of one triangle, which a ray crosses all at one t: each must be reported once. The
 * kd-tree kept the faces reported in a list searched from its start, n² steps a ray: ten rays took
 * longer than the 20 s this test allows (a hash set now: each report is a step or two, and the test
 * takes under a second). */
Test(accel, kdtree_reports_a_hundred_thousand_faces_on_one_ray_once_each_and_quickly, .timeout = 20) {
    enum { COPIES = 100000, RAYS = 10 };
    struct builder b = {0};
    for (int k = 0; k < COPIES; k++)
        add_triangle(&b, vec3_make(0, 0, 0), vec3_make(1, 0, 0), vec3_make(0, 1, 0));
    struct kdtree *k = kdtree_build(&b.m, KD_SPLIT_SAH);
    cr_assert_not_null(k);
    struct reports r = {calloc(COPIES, 1), 0};
    cr_assert_not_null(r.times);
    for (int n = 0; n < RAYS; n++) {
        ray through = {{0.1 + 0.05 * n, 0.2, 1}, {0, 0, -1}};
        kdtree_for_each_hit(k, &through, RAY_T_MIN, INFINITY, count_report, &r);
    }
    cr_expect_eq(r.total, (size_t)COPIES * RAYS, "%zu reports", r.total);
    for (int f = 0; f < COPIES; f++)
        cr_assert_eq(r.times[f], RAYS, "face %d reported %d times on %d rays", f, r.times[f], RAYS);
    free(r.times);
    kdtree_free(k);
    mesh_free(&b.m);
}

/* Triangles nested about one centre, each a little smaller than the one before: every plane that cuts
 * the region cuts through most of them, yet the SAH finds each cut worth it, and copied nearly all of
 * them into both sides, level after level (10,000 of them: 9,131 references a triangle, 6.8 s; 100,000
 * others, their sizes spread wider: 5,000, 48 s and 2 GB). The tree stops at KD_MAX_REFERENCES_PER_TRIANGLE, and still answers as the
 * brute-force loop does, ties (the triangles share a plane) to the lowest face. */
Test(accel, kdtree_references_stay_bounded_on_nested_triangles, .timeout = ACCEL_TEST_TIMEOUT) {
    enum { NESTED = 10000 };
    struct mesh m = {malloc(3 * NESTED * sizeof(vec3)), 3 * NESTED, malloc(NESTED * sizeof(struct mesh_face)), NESTED};
    cr_assert(m.vertices != NULL && m.faces != NULL);
    for (uint32_t k = 0; k < NESTED; k++) {
        double s = 10.0 * pow(1.0001, -(double)k);
        m.vertices[3 * k] = vec3_make(-s, -s, 0.0);
        m.vertices[3 * k + 1] = vec3_make(s, -s, 0.0);
        m.vertices[3 * k + 2] = vec3_make(0.0, s, 0.0);
        m.faces[k] = (struct mesh_face){{3 * k, 3 * k + 1, 3 * k + 2}};
    }
    for (int rule = 0; rule < 2; rule++) {
        struct kdtree *tree = kdtree_build(&m, rule ? KD_SPLIT_SAH : KD_SPLIT_SEED);
        struct kdtree_info info;
        kdtree_get_info(tree, &info);
        cr_expect_leq(info.references, 2 * KD_MAX_REFERENCES_PER_TRIANGLE * (size_t)NESTED,
                      "rule %d: %zu references for %d triangles", rule, info.references, NESTED);
        for (int i = 0; i < 24; i++)
            for (int j = 0; j < 24; j++) {
                ray r = {vec3_make(0.3, -0.2, 6.0), vec3_normalize(vec3_make(-0.5 + i / 23.0, -0.5 + j / 23.0, -1.0))};
                struct hit brute = hit_nothing(INFINITY);
                bool brute_hit = triangle_mesh_closest(&m, 0, &r, RAY_T_MIN, &brute);
                double t = 0.0;
                uint32_t face = 0;
                bool hit = kdtree_closest(tree, &r, RAY_T_MIN, INFINITY, &t, &face);
                cr_expect(hit == brute_hit && (!hit || (t == brute.t && (int)face == brute.face)),
                          "rule %d, ray (%d, %d): %d t %.17g face %u, brute force %d t %.17g face %d", rule, i, j, hit, t,
                          face, brute_hit, brute.t, brute.face);
            }
        kdtree_free(tree);
    }
    mesh_free(&m);
}

/* The leaves of the 4-wide subtree (child, count) of b, as (first << 32 | count) into leaves[*n]. */
static void wide_leaves(const struct fast_bvh *b, uint32_t child, uint32_t count, uint64_t *leaves, size_t *n) {
    if (count > 0) {
        leaves[(*n)++] = (uint64_t)child << 32 | count;
        return;
    }
    for (int k = 0; k < FAST_BVH_WIDTH; k++)
        if (b->nodes[child].child[k] != FAST_BVH_NO_CHILD)
            wide_leaves(b, b->nodes[child].child[k], b->nodes[child].count[k], leaves, n);
}

static int compare_leaves(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* Rungs 2 to 4 change only how chapter 10's tree is stored: the same triangles in the same leaf order,
 * the same leaves, in a tree of fewer and shallower nodes. */
Test(accel, rungs_2_to_4_are_chapter_10s_tree_made_wide) {
    struct mesh m = make_soup(37, 3000);
    for (int rule = 0; rule < 2; rule++) {
        enum bvh_split split = rule ? BVH_SPLIT_SAH : BVH_SPLIT_MEDIAN;
        struct bvh *binary = bvh_build(&m, split);
        struct fast_bvh *wide = fast_bvh_build(&m, split, FAST_BVH_RUNG_WIDE);
        cr_assert(binary != NULL && wide != NULL);
        cr_expect_eq(memcmp(binary->faces, wide->faces, m.face_count * sizeof *wide->faces), 0,
                     "rule %d: the triangles are not in chapter 10's leaf order", rule);
        uint64_t *ours = malloc(m.face_count * sizeof *ours), *theirs = malloc(m.face_count * sizeof *theirs);
        size_t n_ours = 0, n_theirs = 0;
        wide_leaves(wide, wide->root_child, wide->root_count, ours, &n_ours);
        for (size_t k = 0; k < binary->node_count; k++)
            if (binary->nodes[k].count > 0)
                theirs[n_theirs++] = (uint64_t)binary->nodes[k].first << 32 | binary->nodes[k].count;
        qsort(ours, n_ours, sizeof *ours, compare_leaves);
        qsort(theirs, n_theirs, sizeof *theirs, compare_leaves);
        cr_expect(n_ours == n_theirs && memcmp(ours, theirs, n_ours * sizeof *ours) == 0,
                  "rule %d: %zu leaves, chapter 10's tree has %zu, or they differ", rule, n_ours, n_theirs);
        cr_expect_lt(wide->node_count, binary->node_count - binary->info.leaves, "rule %d", rule);
        cr_expect_lt(wide->info.max_depth, binary->info.max_depth, "rule %d", rule);
        free(ours);
        free(theirs);
        fast_bvh_free(wide);
        bvh_free(binary);
    }
    mesh_free(&m);
}

/* Rung 5's float build makes a tree as good as chapter 10's by the SAH's own measure (not node for node:
 * its centroids are floats and a small node has fewer slots). */
Test(accel, rung_5_builds_a_tree_as_good_by_the_sah) {
    struct mesh meshes[] = {make_soup(41, 3000), make_sphere(32, 64, vec3_make(0, 0, 0), 1.0), make_grids(6)};
    for (size_t k = 0; k < sizeof meshes / sizeof meshes[0]; k++) {
        struct fast_bvh *collapsed = fast_bvh_build(&meshes[k], BVH_SPLIT_SAH, FAST_BVH_RUNG_PREFETCH);
        struct fast_bvh *built = fast_bvh_build(&meshes[k], BVH_SPLIT_SAH, FAST_BVH_RUNG_BUILD);
        cr_assert(collapsed != NULL && built != NULL);
        double ratio = built->info.sah_cost / collapsed->info.sah_cost;
        cr_expect(ratio > 0.97 && ratio < 1.03, "mesh %zu: rung 5's tree costs %.4f by the SAH, rung 4's %.4f", k,
                  built->info.sah_cost, collapsed->info.sah_cost);
        fast_bvh_free(collapsed);
        fast_bvh_free(built);
        mesh_free(&meshes[k]);
    }
}

/* Whether a and b, built from one mesh of `faces` faces, are the same tree byte for byte: nodes, leaf
 * order, triangles, root and shape; says where they differ in why. */
static bool same_tree(const struct fast_bvh *a, const struct fast_bvh *b, size_t faces, char *why, size_t why_size) {
    size_t node_bytes = a->nodes8 != NULL ? sizeof *a->nodes8 : sizeof *a->nodes;
    const void *a_nodes = a->nodes8 != NULL ? (const void *)a->nodes8 : (const void *)a->nodes;
    const void *b_nodes = b->nodes8 != NULL ? (const void *)b->nodes8 : (const void *)b->nodes;
    const char *differ = NULL;
    if (a->node_count != b->node_count || (a->nodes8 == NULL) != (b->nodes8 == NULL))
        differ = "node count or width";
    else if (memcmp(a_nodes, b_nodes, a->node_count * node_bytes) != 0)
        differ = "nodes";
    else if (memcmp(a->faces, b->faces, faces * sizeof *a->faces) != 0)
        differ = "leaf order (faces)";
    else if ((a->triangles == NULL) != (b->triangles == NULL) ||
             (a->triangles != NULL && memcmp(a->triangles, b->triangles, faces * sizeof *a->triangles) != 0))
        differ = "triangles";
    else if (a->root_child != b->root_child || a->root_count != b->root_count ||
             memcmp(&a->root_box, &b->root_box, sizeof a->root_box) != 0 || a->tree_count != b->tree_count)
        differ = "root";
    else if (a->info.nodes != b->info.nodes || a->info.leaves != b->info.leaves ||
             a->info.max_depth != b->info.max_depth || memcmp(&a->info.sah_cost, &b->info.sah_cost, sizeof(double)) != 0)
        differ = "shape or SAH cost";
    if (differ != NULL)
        snprintf(why, why_size, "%s", differ);
    return differ == NULL;
}

/* The float build (rungs 5, 7 and 8) makes the same tree, byte for byte, on 1, 2 and 4 threads: on more
 * than one, big nodes build their children in tasks that may finish in any order. */
Test(accel, float_build_is_the_same_tree_on_any_number_of_threads, .timeout = ACCEL_TEST_TIMEOUT) {
    static const char *const models[] = {"scenes/models/teapot-5k.ply", "scenes/models/bunny.ply"};
    static const enum fast_bvh_rung rungs[] = {FAST_BVH_RUNG_BUILD, FAST_BVH_RUNG_COMPACT, FAST_BVH_RUNG_EIGHT,
                                               FAST_BVH_RUNG_LEAN};
    static const int threads[] = {2, 4};
    int threads_before = omp_get_max_threads();
    for (size_t i = 0; i < sizeof models / sizeof models[0]; i++) {
        struct mesh m;
        char err[512];
        cr_assert(mesh_load(models[i], &m, err, sizeof err), "%s", err);
        for (size_t r = 0; r < sizeof rungs / sizeof rungs[0]; r++) {
            omp_set_num_threads(1);
            struct fast_bvh *one = fast_bvh_build(&m, BVH_SPLIT_SAH, rungs[r]);
            cr_assert(one != NULL);
            for (size_t t = 0; t < sizeof threads / sizeof threads[0]; t++) {
                omp_set_num_threads(threads[t]);
                cr_assert_eq(omp_get_max_threads(), threads[t]);
                for (int round = 0; round < 3; round++) { /* the tasks finish in another order each time */
                    struct fast_bvh *many = fast_bvh_build(&m, BVH_SPLIT_SAH, rungs[r]);
                    cr_assert(many != NULL);
                    char why[64];
                    cr_expect(same_tree(one, many, m.face_count, why, sizeof why),
                              "%s, rung %d: on %d threads the tree differs from one thread's: %s", models[i],
                              (int)rungs[r], threads[t], why);
                    fast_bvh_free(many);
                }
            }
            fast_bvh_free(one);
        }
        mesh_free(&m);
    }
    omp_set_num_threads(threads_before);
}

/* A grid of small triangles in which every fifth face (3, 8, 13, ...) is a sliver: a sine of 2e-9
 * between its edges, below TRIANGLE_SLIVER_SINE. */
static struct mesh make_grid_with_slivers(size_t count) {
    struct builder b = {0};
    for (size_t f = 0; f < count; f++) {
        vec3 a = vec3_make((double)(f % 100), (double)(f / 100 % 100), (double)(f / 10000));
        vec3 c = f % 5 == 3 ? vec3_add(a, vec3_make(0.5, 1e-9, 0)) : vec3_add(a, vec3_make(0.5, 0.7, 0.3));
        add_triangle(&b, a, vec3_add(a, vec3_make(1, 0, 0)), c);
    }
    return b.m;
}

/* The float build leaves slivers out of the tree and lists them at the end of its faces, the first at the
 * very end, in face order, whatever the number of threads that prepared the prims (face_prims). */
Test(accel, float_build_lists_slivers_last_in_face_order_on_any_number_of_threads, .timeout = ACCEL_TEST_TIMEOUT) {
    enum { FACES = 20000 };
    struct mesh m = make_grid_with_slivers(FACES);
    int threads_before = omp_get_max_threads();
    static const enum fast_bvh_rung rungs[] = {FAST_BVH_RUNG_BUILD, FAST_BVH_RUNG_COMPACT};
    for (size_t r = 0; r < sizeof rungs / sizeof rungs[0]; r++) {
        omp_set_num_threads(1);
        struct fast_bvh *one = fast_bvh_build(&m, BVH_SPLIT_SAH, rungs[r]);
        cr_assert_not_null(one);
        cr_assert_eq(one->tree_count, FACES - FACES / 5, "rung %d: %zu faces in the tree", (int)rungs[r],
                     one->tree_count);
        for (size_t k = 0; k < FACES / 5; k++)
            cr_assert_eq(one->faces[FACES - 1 - k], 5 * k + 3, "rung %d: sliver %zu is face %u", (int)rungs[r], k,
                         one->faces[FACES - 1 - k]);
        for (int threads = 2; threads <= 4; threads += 2) {
            omp_set_num_threads(threads);
            struct fast_bvh *many = fast_bvh_build(&m, BVH_SPLIT_SAH, rungs[r]);
            cr_assert_not_null(many);
            char why[64];
            cr_expect(same_tree(one, many, FACES, why, sizeof why), "rung %d on %d threads: %s", (int)rungs[r],
                      threads, why);
            fast_bvh_free(many);
        }
        fast_bvh_free(one);
    }
    omp_set_num_threads(threads_before);
    mesh_free(&m);
}

/* The SAH tree is the cheaper one by the SAH's own measure (the seed's rule prices nothing), and an
 * empty leaf or more where the triangles leave space empty; on the cost the tree predicts, a tree made
 * with every candidate plane priced should beat median planes by a wide margin on real meshes. */
static void expect_sah_tree_cheaper_than_seed(const char *name, const struct mesh *m, double at_least) {
    struct kdtree *sah = kdtree_build(m, KD_SPLIT_SAH), *seed = kdtree_build(m, KD_SPLIT_SEED);
    cr_assert(sah != NULL && seed != NULL, "%s: a build ran out of memory", name);
    struct kdtree_info a, b;
    kdtree_get_info(sah, &a);
    kdtree_get_info(seed, &b);
    cr_expect(a.sah_cost * at_least <= b.sah_cost, "%s: the SAH tree's predicted cost %.2f is not %.1f times below "
              "the seed's rule's %.2f", name, a.sah_cost, at_least, b.sah_cost);
    cr_expect(a.empty_leaves > 0, "%s: the SAH cut no empty space away (%zu leaves)", name, a.leaves);
    kdtree_free(sah);
    kdtree_free(seed);
}

Test(accel, kdtree_sah_tree_costs_less_than_the_seed_rules, .timeout = ACCEL_TEST_TIMEOUT) {
    struct mesh sphere = make_sphere(24, 48, vec3_make(0.25, -0.5, 1.0), 1.5), grids = make_grids(12);
    expect_sah_tree_cheaper_than_seed("sphere", &sphere, 1.5);
    expect_sah_tree_cheaper_than_seed("grids", &grids, 1.5);
    mesh_free(&sphere);
    mesh_free(&grids);
    struct mesh bunny;
    char err[512];
    cr_assert(mesh_load("scenes/models/bunny.ply", &bunny, err, sizeof err), "%s", err);
    expect_sah_tree_cheaper_than_seed("bunny", &bunny, 2.5);
    mesh_free(&bunny);
}

/* ---- meshes outside float range (issue 16) ----------------------------------------------------- */

/* m with every vertex v replaced by v * scale + shift. */
static void transform_mesh(struct mesh *m, double scale, vec3 shift) {
    for (size_t k = 0; k < m->vertex_count; k++)
        m->vertices[k] = vec3_add(vec3_scale(m->vertices[k], scale), shift);
}

/* Builds the two kd-trees over m (which must not hang: the test's timeout catches that) and checks
 * their answers against the brute-force loop on rays_for(m) rays; frees m. */
static void check_mesh_kdtrees(const char *name, struct mesh *m, uint64_t seed) {
    struct checker c;
    checker_init_kdtrees(&c, name, m);
    check_rays(&c, seed, rays_for(m));
    checker_free(&c);
    mesh_free(m);
}

/* How a group of meshes is checked: build, compare with the brute-force loop, free the mesh. */
typedef void (*mesh_check)(const char *name, struct mesh *m, uint64_t seed);

/* A scene may place a mesh where its coordinates overflow float when the tree rounds its boxes
 * outward (scale 1e39), near the top of double (1e300, 1e308, where the intersection arithmetic itself
 * overflows), below float's normal range (1e-40), or far from the origin (translate 1e39, where
 * double collapses the soup's corners); a mesh may also be flat on an axis, or a single point. Each
 * such mesh goes to `check`; `salt` changes the soups' random seeds. Without `far_from_origin` the
 * soup moved to x = 1e39 (and left at its size) is skipped. */
static void check_meshes_outside_float_range(mesh_check check, uint64_t salt, bool far_from_origin) {
    static const struct {
        const char *name;
        double scale, shift_x;
    } placed[] = {
        {"soup scaled by 1e39", 1e39, 0.0},   {"soup scaled by 1e300", 1e300, 0.0},
        {"soup scaled by 1e308", 1e308, 0.0}, {"soup scaled by 1e-40", 1e-40, 0.0},
        {"soup moved to x = 1e39", 1.0, 1e39}, {"soup from -1e38 to 1e39", 1.1e39, -1e38},
    };
    for (size_t k = 0; k < sizeof placed / sizeof placed[0]; k++) {
        if (!far_from_origin && placed[k].scale == 1.0)
            continue; /* see the BVH tests below */
        struct mesh m = make_soup(1601 + salt + k, 300);
        transform_mesh(&m, placed[k].scale, vec3_make(placed[k].shift_x, 0, 0));
        check(placed[k].name, &m, 21 + salt + k);
    }
    struct mesh flat = make_soup(1701 + salt, 300); /* zero extent on z */
    for (size_t k = 0; k < flat.vertex_count; k++)
        flat.vertices[k].z = 0.5;
    check("soup flat in z = 0.5", &flat, 31 + salt);
    struct builder point = {0}; /* zero extent on every axis: flat boxes */
    for (int k = 0; k < 20; k++)
        add_triangle(&point, vec3_make(1e39, -2, 3), vec3_make(1e39, -2, 3), vec3_make(1e39, -2, 3));
    check("point at x = 1e39", &point.m, 32 + salt);
    /* a well-placed soup with a few faces far out: the near faces must still be found */
    struct mesh mixed = make_soup(1801 + salt, 300);
    for (size_t k = 0; k < 12; k++)
        mixed.vertices[mixed.faces[k * 20].v[k % 3]].x = k % 2 ? 1e300 : -1e39;
    check("soup with corners at 1e300 and -1e39", &mixed, 33 + salt);
}

/* Corners at infinity or NaN (a mesh scaled by 1e308 whose coordinates exceed 1.8 overflows double),
 * each such mesh given to `check`. */
static void check_meshes_with_corners_at_infinity_or_nan(mesh_check check, uint64_t salt) {
    static const double bad[] = {INFINITY, -INFINITY, NAN};
    for (int k = 0; k < 3; k++) {
        struct mesh m = make_soup(1901 + salt + (uint64_t)k, 300);
        for (size_t f = 0; f < 10; f++)
            m.vertices[m.faces[f * 25].v[f % 3]].y = bad[k];
        char name[64];
        snprintf(name, sizeof name, "soup with corners at y = %g", bad[k]);
        check(name, &m, 41 + salt + (uint64_t)k);
    }
    struct mesh all = make_soup(1999 + salt, 100); /* every corner overflowed */
    transform_mesh(&all, 1e308, vec3_make(0, 0, 0));
    transform_mesh(&all, 1e308, vec3_make(0, 0, 0));
    check("soup scaled by 1e616", &all, 44 + salt);
}

/* The kd-tree builds once looped forever on NaN event positions; now every rule finishes and agrees
 * with the brute-force loop. */
Test(accel, kdtree_builds_and_matches_brute_force_on_meshes_outside_float_range, .timeout = ACCEL_TEST_TIMEOUT) {
    check_meshes_outside_float_range(check_mesh_kdtrees, 0, true);
}

Test(accel, kdtree_builds_and_matches_brute_force_with_corners_at_infinity_or_nan, .timeout = ACCEL_TEST_TIMEOUT) {
    check_meshes_with_corners_at_infinity_or_nan(check_mesh_kdtrees, 0);
}

/* ---- BVHs on degenerate extents ------------------------------------------------------------------ */

/* The SAH builds of chapters 10 and 11 drop each centroid into a slot by (centroid - lowest) * scale.
 * A mesh beyond float's or double's range gives infinite or NaN centroids, and a NaN converted to an
 * integer slot was INT_MIN, an index far outside the slots (AddressSanitizer reports it). Every slot
 * index is now clamped at both ends first. On the same meshes as the kd-tree's, every BVH (and every
 * rung) builds a valid tree and answers exactly as the brute-force loop does, but one: a soup of size
 * 1 moved to x = 1e39, where a ray starts some 1e39 mesh sizes away and the triangle test's rounding
 * (about 1e23 there) exceeds any pad relative to the mesh's size (bvh.c says so). Scenes refuse such a
 * placement (scene_meshes.c), so the tracer never meets it. */
Test(accel, bvhs_build_and_match_brute_force_on_meshes_outside_float_range, .timeout = ACCEL_TEST_TIMEOUT) {
    check_meshes_outside_float_range(check_mesh, 1000, false);
}

Test(accel, bvhs_build_and_match_brute_force_with_corners_at_infinity_or_nan, .timeout = ACCEL_TEST_TIMEOUT) {
    check_meshes_with_corners_at_infinity_or_nan(check_mesh, 1000);
}

/* Rung 6 tests boxes in float from the ray's origin rounded to float. Far from the origin, a float
 * step is as large as a small mesh (at 1e4 it is 1e-3), a thousand times the pad of its boxes, and a
 * slab test that ignored where the origin was rounded to would cut off hits there; rung 6 adds the
 * shift to its slack (fast_bvh.c). Every structure must still match the brute-force loop. */
Test(accel, rung_6_matches_brute_force_where_a_float_step_is_as_large_as_the_mesh, .timeout = ACCEL_TEST_TIMEOUT) {
    static const struct {
        const char *name;
        double scale;
        vec3 shift;
    } placed[] = {
        {"soup of size 2e-3 at (1e4, -3e3, 700)", 1e-3, {1e4, -3e3, 700}},
        {"soup of size 2e-2 at (5e3, 5e3, 5e3)", 1e-2, {5e3, 5e3, 5e3}},
        {"soup of size 2e-5 at (-33, 12, 0.1)", 1e-5, {-33, 12, 0.1}},
    };
    for (size_t k = 0; k < sizeof placed / sizeof placed[0]; k++) {
        struct mesh m = make_soup(2101 + k, 300);
        transform_mesh(&m, placed[k].scale, placed[k].shift);
        check_mesh(placed[k].name, &m, 51 + k);
    }
    struct mesh sphere = make_sphere(24, 48, vec3_make(4096.001, -2048.0003, 1024.00007), 3e-3);
    check_mesh("sphere of radius 3e-3 at (4096, -2048, 1024)", &sphere, 57);
}

/* The closed cube [1, 1 + 4 ulp]^3 (ulp = DBL_EPSILON, the step of doubles at 1), twelve triangles. So
 * small that its pad (2^-20 of its size) is lost in rounding: the root's box of the fast BVH, rounded
 * outward to float, has its low faces exactly on the cube's. */
static struct mesh make_ulp_cube(void) {
    struct builder b = {0};
    const double lo = 1.0, hi = 1.0 + 4.0 * DBL_EPSILON;
    for (int k = 0; k < 8; k++)
        add_vertex(&b, vec3_make(k & 1 ? hi : lo, k & 2 ? hi : lo, k & 4 ? hi : lo));
    static const uint32_t quads[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                         {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (int q = 0; q < 6; q++) {
        add_face(&b, quads[q][0], quads[q][1], quads[q][2]);
        add_face(&b, quads[q][0], quads[q][2], quads[q][3]);
    }
    return b.m;
}

/* A ray that runs inside a face's plane of the root's box (an origin component on the plane, that
 * direction component +-0) gets 0 * infinity = NaN in the slab test, which must constrain nothing
 * (aabb.h): such a ray meets the walls standing on that face along their edge. The walks that test the
 * root's box first (rungs 8 to 11, and rung 9's own test of its three slabs at once) must still find
 * them, as the brute-force loop does. */
Test(accel, rays_inside_the_root_boxs_faces_meet_the_walls_standing_on_them) {
    struct mesh m = make_ulp_cube();
    struct checker c;
    checker_init(&c, "cube of 4 ulp at 1", &m);
    const double lo = 1.0, hi = 1.0 + 4.0 * DBL_EPSILON, middle = 1.0 + 2.0 * DBL_EPSILON;
    size_t rays = 0, hit = 0;
    for (int plane = 0; plane < 3; plane++)       /* the ray runs inside plane x, y or z = lo */
        for (int along = 0; along < 3; along++) { /* towards the cube along this axis */
            if (along == plane)
                continue;
            for (int sign = -1; sign <= 1; sign += 2)
                for (int zero = 0; zero < 2; zero++) { /* the plane's direction component +0 or -0 */
                    vec3 origin = {middle, middle, middle}, direction = {0.0, 0.0, 0.0};
                    set_axis(&origin, plane, lo);
                    set_axis(&origin, along, sign > 0 ? lo - 8.0 * DBL_EPSILON : hi + 8.0 * DBL_EPSILON);
                    set_axis(&direction, along, sign);
                    set_axis(&direction, plane, zero ? -0.0 : 0.0);
                    ray r = {origin, direction};
                    trace_brute_force(&c, &r);
                    hit += c.hit_count > 0;
                    rays++;
                    check_window(&c, &r, -INFINITY, INFINITY);
                    check_window(&c, &r, 0.0, INFINITY);
                }
        }
    cr_assert_eq(rays, 24);
    cr_expect_eq(hit, rays, "the brute-force loop finds the walls' edges on %zu of %zu rays", hit, rays);
    checker_free(&c);
    mesh_free(&m);
}

/* Chapter 11's rungs: only 1 to 11, by number or name; fast_bvh_build builds 2 to 9 and nothing else. */
Test(accel, fast_bvh_rungs_are_named_and_checked) {
    static const char *const names[] = {"plain", "wide",    "simd",  "prefetch", "build",      "float",
                                        "compact", "eight", "lean", "packet",   "exact-float"};
    cr_assert_eq(sizeof names / sizeof names[0], FAST_BVH_RUNG_LAST);
    for (int r = FAST_BVH_RUNG_PLAIN; r <= FAST_BVH_RUNG_LAST; r++) {
        char number[12];
        snprintf(number, sizeof number, "%d", r);
        cr_expect_eq(fast_bvh_rung_from_name(names[r - 1]), r, "%s", names[r - 1]);
        cr_expect_eq(fast_bvh_rung_from_name(number), r, "%s", number);
        cr_expect_str_eq(fast_bvh_rung_name(r), names[r - 1]);
    }
    cr_expect_eq(fast_bvh_rung_from_name("12"), 0);
    cr_expect_eq(fast_bvh_rung_from_name("010"), 0);
    cr_expect_eq(fast_bvh_rung_from_name("1 "), 0);
    cr_expect_eq(fast_bvh_rung_from_name(":"), 0); /* the character after '9' */
    cr_expect_eq(fast_bvh_rung_from_name("0"), 0);
    cr_expect_eq(fast_bvh_rung_from_name("fast"), 0);
    cr_expect_str_eq(fast_bvh_rung_name(FAST_BVH_RUNG_LAST + 1), "?");
    struct mesh m = make_soup(7, 20);
    cr_expect_null(fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_PLAIN), "rung 1 is chapter 10's, not built here");
    cr_expect_null(fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_PACKET), "rung 10 walks rung 9's tree");
    struct fast_bvh *exact = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_EXACT);
    cr_expect(exact != NULL && exact->rung == FAST_BVH_RUNG_EXACT, "rung 11 is rung 9's tree, built as rung 11");
    fast_bvh_free(exact);
    cr_expect_null(fast_bvh_build(&m, BVH_SPLIT_SAH, (enum fast_bvh_rung)(FAST_BVH_RUNG_LAST + 1)));
    mesh_free(&m);
}

/* Told there is no AVX2 (FAST_BVH_NO_AVX2_VARIABLE), `rung` (8 or 9) builds rung 6's tree over m, node
 * for node, and nothing 8-wide. */
static void expect_rung_6_without_avx2(const struct mesh *m, enum fast_bvh_rung rung) {
    cr_assert_eq(setenv(FAST_BVH_NO_AVX2_VARIABLE, "1", 1), 0);
    cr_expect_not(fast_bvh_eight_available());
    struct fast_bvh *fallback = fast_bvh_build(m, BVH_SPLIT_SAH, rung);
    struct fast_bvh *six = fast_bvh_build(m, BVH_SPLIT_SAH, FAST_BVH_RUNG_FLOAT);
    cr_assert_eq(unsetenv(FAST_BVH_NO_AVX2_VARIABLE), 0);
    cr_assert(fallback != NULL && six != NULL);
    cr_expect(fallback->nodes8 == NULL && fallback->lean_corners == NULL, "rung %d without AVX2 built 8-wide nodes",
              rung);
    cr_assert_eq(fallback->node_count, six->node_count);
    cr_expect_eq(memcmp(fallback->nodes, six->nodes, six->node_count * sizeof *six->nodes), 0,
                 "rung %d without AVX2 built another tree than rung 6's", rung);
    fast_bvh_free(fallback);
    fast_bvh_free(six);
}

/* Rung 8 builds 8-wide nodes, more than four children each on average, exactly when the processor has AVX2 and is not told
 * otherwise; else rung 6's tree, the same as rung 6 builds, node for node. */
Test(accel, rung_8_is_eight_wide_with_avx2_and_rung_6_without) {
    struct mesh m = make_soup(11, 5000);
    struct fast_bvh *eight = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_EIGHT);
    cr_assert_not_null(eight);
    if (fast_bvh_eight_available()) {
        cr_assert_not_null(eight->nodes8, "AVX2 here, and rung 8 built no 8-wide nodes");
        size_t children = 0;
        for (size_t k = 0; k < eight->node_count; k++)
            for (int c = 0; c < FAST_BVH_WIDTH_EIGHT; c++)
                children += eight->nodes8[k].child[c] != FAST_BVH_NO_CHILD;
        cr_expect_gt(children, FAST_BVH_WIDTH * eight->node_count, "%zu nodes with %zu children: not wider than rung 6's",
                     eight->node_count, children);
    } else {
        cr_log_warn("this processor has no AVX2: rung 8's 8-wide walk is not tested here");
    }
    expect_rung_6_without_avx2(&m, FAST_BVH_RUNG_EIGHT);
    fast_bvh_free(eight);
    mesh_free(&m);
}

/* Rung 9's SAH prices a leaf by its blocks of eight triangles (two of its lanes' tests of four), rung
 * 8's by its triangles: eight small triangles at the corners of a large cube are one leaf on rung 9 (one
 * block, against a node and two blocks below it) and are split on rung 8 (eight tests, against a node
 * and eight tiny boxes). */
Test(accel, rung_9_prices_a_leaf_by_its_blocks_of_eight_triangles) {
    struct builder g = {0};
    for (int k = 0; k < 8; k++) {
        vec3 corner = vec3_make(100.0 * (k & 1), 100.0 * ((k >> 1) & 1), 100.0 * (k >> 2));
        uint32_t a = add_vertex(&g, corner), b = add_vertex(&g, vec3_add(corner, vec3_make(0.01, 0, 0))),
                 c = add_vertex(&g, vec3_add(corner, vec3_make(0, 0.01, 0)));
        add_face(&g, a, b, c);
    }
    struct fast_bvh *lean = fast_bvh_build(&g.m, BVH_SPLIT_SAH, FAST_BVH_RUNG_LEAN);
    struct fast_bvh *eight = fast_bvh_build(&g.m, BVH_SPLIT_SAH, FAST_BVH_RUNG_EIGHT);
    cr_assert(lean != NULL && eight != NULL);
    if (fast_bvh_eight_available()) {
        cr_expect_eq(lean->root_count, 8, "rung 9's root is not one leaf of the eight triangles");
        cr_expect_eq(lean->node_count, 0, "rung 9 made %zu nodes", (size_t)lean->node_count);
    } else {
        cr_log_warn("this processor has no AVX2: rung 9 is rung 6 here");
    }
    cr_expect_eq(eight->root_count, 0, "rung 8 made the eight triangles one leaf");
    cr_expect_geq(eight->node_count, 1);
    fast_bvh_free(lean);
    fast_bvh_free(eight);
    mesh_free(&g.m);
}

/* Rung 9 builds rung 8's tree with its leaves priced by the block (so fewer nodes; rung 11 builds the
 * same tree) and lays the tree's triangles out once more, in aligned blocks of four with zeros past the
 * end and NaN for a triangle whose corners lie on a line (the soup has some), where the processor has
 * AVX2; without it (or told so), rung 6's tree and no copy. */
Test(accel, rung_9_lays_its_triangles_out_in_blocks_of_four_and_is_rung_6_without_avx2) {
    struct mesh m = make_soup(13, 3000);
    struct fast_bvh *lean = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_LEAN);
    struct fast_bvh *eight = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_EIGHT);
    cr_assert(lean != NULL && eight != NULL);
    if (fast_bvh_eight_available()) {
        cr_assert_not_null(lean->nodes8, "AVX2 here, and rung 9 built no 8-wide nodes");
        cr_assert_not_null(lean->lean_corners);
        cr_expect_lt(lean->node_count, eight->node_count, "rung 9's leaves, priced by the block, are not fewer: %zu "
                     "nodes against rung 8's %zu", (size_t)lean->node_count, (size_t)eight->node_count);
        struct fast_bvh *exact = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_EXACT); /* walks rung 9's tree */
        cr_assert_not_null(exact);
        cr_assert_eq(exact->node_count, lean->node_count);
        cr_expect_eq(memcmp(exact->nodes8, lean->nodes8, lean->node_count * sizeof *lean->nodes8), 0,
                     "rung 11 built another tree than rung 9's");
        fast_bvh_free(exact);
        size_t padded = (lean->tree_count + FAST_BVH_LEAN_LANES - 1) / FAST_BVH_LEAN_LANES * FAST_BVH_LEAN_LANES;
        cr_expect_eq((uintptr_t)lean->lean_corners % 32, 0, "the blocks are not aligned for AVX2's loads");
        size_t collinear = 0;
        for (size_t k = 0; k < padded; k++) {
            const struct bvh_triangle *t = k < lean->tree_count ? &lean->triangles[k] : NULL;
            bool on_a_line = t != NULL && triangle_corners_collinear(t->a, t->b, t->c);
            collinear += on_a_line;
            for (int c = 0; c < 3; c++)
                for (int a = 0; a < 3; a++) {
                    double want = t == NULL    ? 0.0
                                  : on_a_line ? NAN
                                              : vec3_axis(c == 0 ? t->a : c == 1 ? t->b : t->c, a);
                    double got = lean->lean_corners[fast_bvh_lean_index(k, c, a)];
                    cr_assert_eq(memcmp(&got, &want, sizeof got), 0, "triangle %zu corner %d axis %d: %a, want %a", k,
                                 c, a, got, want);
                }
        }
        cr_expect_gt(collinear, 0, "the soup put no triangle with corners on a line in the tree");
    } else {
        cr_log_warn("this processor has no AVX2: rung 9's walk is not tested here");
    }
    expect_rung_6_without_avx2(&m, FAST_BVH_RUNG_LEAN);
    fast_bvh_free(lean);
    fast_bvh_free(eight);
    mesh_free(&m);
}

/* float4.h's steps to the next float, on which every float box's outward rounding rests: the neighbours
 * nextafterf gives, at zero, the subnormals, the normal range's ends, infinity, and floats of every
 * exponent and sign. */
static void check_steps(float f) {
    float down = nextafterf(f, -INFINITY), up = nextafterf(f, INFINITY);
    if (f != -INFINITY)
        cr_assert(memcmp(&(float){float_step_down(f)}, &down, sizeof down) == 0, "below %a: %a, not %a", (double)f,
                  (double)float_step_down(f), (double)down);
    if (f != INFINITY)
        cr_assert(memcmp(&(float){float_step_up(f)}, &up, sizeof up) == 0, "above %a: %a, not %a", (double)f,
                  (double)float_step_up(f), (double)up);
}

Test(accel, float_steps_are_nextafterf_at_zero_subnormals_range_ends_and_every_exponent) {
    const float edges[] = {0.0f, -0.0f, FLT_TRUE_MIN, -FLT_TRUE_MIN, 2 * FLT_TRUE_MIN, FLT_MIN, -FLT_MIN,
                           nextafterf(FLT_MIN, 0.0f), FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, 1.0f, -1.0f, 0.5f};
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        check_steps(edges[k]);
    uint32_t bits = 12345u;
    for (int k = 0; k < 200000; k++) {
        bits = bits * 1664525u + 1013904223u;
        float f;
        memcpy(&f, &bits, sizeof f);
        if (!isnan(f))
            check_steps(f);
    }
    /* And the outward roundings built on them: the nearest floats on either side of a double. */
    cr_assert(float_below(0x1.000001p0) == 1.0f && float_above(0x1.000001p0) == nextafterf(1.0f, 2.0f));
    cr_assert(float_below(-0x1p-160) == -FLT_TRUE_MIN && float_above(-0x1p-160) == -0.0f);
    cr_assert(float_below(1e300) == FLT_MAX && float_above(1e300) == INFINITY);
    cr_assert(float_above(-1e300) == -FLT_MAX && float_below(-1e300) == -INFINITY);
    cr_assert(float_below(NAN) == -INFINITY && float_above(NAN) == INFINITY);
    /* Doubles of every exponent and sign, and the floats themselves: below is the largest float <= x, above
     * the smallest >= x. */
    uint64_t wide = 987654321u;
    for (int k = 0; k < 200000; k++) {
        wide = wide * 6364136223846793005u + 1442695040888963407u;
        double x;
        memcpy(&x, &wide, sizeof x);
        if (k % 4 == 0)
            x = (double)(float)x; /* a float: both give it back */
        if (isnan(x))
            continue;
        float below = float_below(x), above = float_above(x);
        cr_assert((double)below <= x && (below == INFINITY || (double)nextafterf(below, INFINITY) > x),
                  "below %a: %a", x, (double)below);
        cr_assert((double)above >= x && (above == -INFINITY || (double)nextafterf(above, -INFINITY) < x),
                  "above %a: %a", x, (double)above);
    }
}
