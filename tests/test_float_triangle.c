/* test_float_triangle.c: rung 11's float triangle test (float_triangle.h) on rays that graze edges and
 * corners: what it says for sure is what the double test says, it says "too close to call" where the ray
 * passes through a corner, and rung 11's walk gives the brute-force loop's answers on those rays.
 *
 * The mesh is a bumpy grid of triangles sharing corners and edges, placed away from the origin (so that
 * the translation's rounding counts), and seen from origins around it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "fast_bvh.h"
#include "fast_bvh_build.h"
#include "fast_bvh_eight.h"
#include "float_triangle.h"
#include "mesh.h"
#include "triangle.h"
#include "uniform.h"

/* The grid: GRID x GRID cells of two triangles, each side 1, at GRID_OFFSET, heights bumped at random. */
#define GRID 12
#define GRID_OFFSET_X 37.25
#define GRID_OFFSET_Y (-11.5)
#define GRID_OFFSET_Z 4.0
/* Rays a kind: aimed at corners, at points of edges, just beside edges, and anywhere on the grid. */
#define GRAZING_RAYS 3000
/* How far beside an edge the third kind aims, relative to the grid's size: a few float units, where the
 * float test is unsure, and far more than a double unit. */
#define BESIDE_EDGE 3e-7

/* The next number of a reproducible stream (uniform.h), uniform in [lo, hi). */
struct draws {
    uint32_t stream, k;
};

static double random_between(struct draws *d, double lo, double hi) { return uniform(d->stream, d->k++, lo, hi); }

/* A whole number from 0 to n - 1 of the stream. */
static uint32_t random_below(struct draws *d, uint32_t n) {
    uint32_t k = (uint32_t)random_between(d, 0.0, n);
    return k < n ? k : n - 1;
}

static struct mesh bumpy_grid(void) {
    struct mesh m = {0};
    m.vertex_count = (GRID + 1) * (GRID + 1);
    m.face_count = 2 * GRID * GRID;
    m.vertices = malloc(m.vertex_count * sizeof *m.vertices);
    m.faces = malloc(m.face_count * sizeof *m.faces);
    cr_assert(m.vertices != NULL && m.faces != NULL);
    struct draws state = {7, 0};
    for (uint32_t j = 0; j <= GRID; j++)
        for (uint32_t i = 0; i <= GRID; i++)
            m.vertices[j * (GRID + 1) + i] = vec3_make(GRID_OFFSET_X + i + random_between(&state, -0.3, 0.3),
                                                       GRID_OFFSET_Y + random_between(&state, -0.5, 0.5),
                                                       GRID_OFFSET_Z + j + random_between(&state, -0.3, 0.3));
    size_t f = 0;
    for (uint32_t j = 0; j < GRID; j++)
        for (uint32_t i = 0; i < GRID; i++) {
            uint32_t a = j * (GRID + 1) + i, b = a + 1, c = a + GRID + 1, d = c + 1;
            m.faces[f++] = (struct mesh_face){{a, b, d}};
            m.faces[f++] = (struct mesh_face){{a, d, c}}; /* the diagonal a-d shared, the other way round */
        }
    return m;
}

/* A ray from a random point above the grid (or below it) towards target. */
static ray ray_towards(struct draws *state, vec3 target) {
    vec3 centre = vec3_make(GRID_OFFSET_X + 0.5 * GRID, GRID_OFFSET_Y, GRID_OFFSET_Z + 0.5 * GRID);
    vec3 origin = vec3_add(centre, vec3_make(random_between(state, -2.0 * GRID, 2.0 * GRID),
                                             random_between(state, 0.5, 3.0 * GRID) * (random_below(state, 4) ? 1 : -1),
                                             random_between(state, -2.0 * GRID, 2.0 * GRID)));
    return (ray){origin, vec3_normalize(vec3_sub(target, origin))};
}

/* The k-th ray of the test: kind k % 4 (a corner, a point of an edge, beside an edge, anywhere); sets
 * *corner to the corner aimed at (for the first kind), else UINT32_MAX. */
static ray grazing_ray(struct draws *state, const struct mesh *m, int k, uint32_t *corner) {
    const struct mesh_face *face = &m->faces[random_below(state, (uint32_t)m->face_count)];
    int e = (int)random_below(state, 3);
    vec3 p = m->vertices[face->v[e]], q = m->vertices[face->v[(e + 1) % 3]];
    double s = random_between(state, 0.0, 1.0);
    vec3 on_edge = vec3_add(p, vec3_scale(vec3_sub(q, p), s));
    *corner = UINT32_MAX;
    switch (k % 4) {
    case 0:
        *corner = face->v[e];
        return ray_towards(state, p);
    case 1:
        return ray_towards(state, on_edge);
    case 2: {
        double step = BESIDE_EDGE * GRID * random_between(state, -1.0, 1.0);
        return ray_towards(state, vec3_add(on_edge, vec3_make(step, 0.0, -step)));
    }
    default:
        return ray_towards(state, vec3_make(GRID_OFFSET_X + random_between(state, 0.0, GRID), GRID_OFFSET_Y,
                                            GRID_OFFSET_Z + random_between(state, 0.0, GRID)));
    }
}

/* What the float test says of the eight triangles of block k / 8 of b for the ray `ready`. */
static __attribute__((target("avx2"))) struct float_triangle_verdict verdict_of_block(const struct fast_bvh *b, size_t k,
                                                                                      const struct triangle_ray *ready) {
    struct float_triangle_ray f;
    struct float_triangle_ray8 f8;
    float_triangle_ray_make(ready, &b->root_box, &f);
    float_triangle_ray_spread(&f, &f8);
    return float_triangle_test8(b->float_corners + float_triangle_index(k - k % FLOAT_TRIANGLE_LANES, 0, 0), &f8);
}

static bool has_corner(const struct mesh *m, uint32_t face, uint32_t corner) {
    const uint32_t *v = m->faces[face].v;
    return v[0] == corner || v[1] == corner || v[2] == corner;
}

Test(float_triangle, is_never_sure_where_the_double_test_says_otherwise_and_unsure_at_corners) {
    if (!fast_bvh_eight_available()) {
        cr_log_warn("this processor has no AVX2: rung 11's float test is not tested here");
        return;
    }
    struct mesh m = bumpy_grid();
    struct fast_bvh *b = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_EXACT);
    cr_assert(b != NULL && b->float_corners != NULL && b->tree_count == m.face_count);
    struct draws state = {1, 0};
    size_t unsure_at_corners = 0, sure_hits = 0, sure_misses = 0;
    for (int k = 0; k < 4 * GRAZING_RAYS; k++) {
        uint32_t corner;
        ray r = grazing_ray(&state, &m, k, &corner);
        struct triangle_ray ready = triangle_ray_make(&r);
        for (size_t j = 0; j < b->tree_count; j++) {
            struct float_triangle_verdict said = verdict_of_block(b, j, &ready);
            unsigned lane = 1u << (j % FLOAT_TRIANGLE_LANES);
            const struct bvh_triangle *t = &b->triangles[j];
            double hit_t, u, v;
            bool crossed = triangle_crossing_prepared(t->a, t->b, t->c, &ready, &hit_t, &u, &v);
            cr_assert(!(said.sure_miss & lane) || !crossed,
                      "ray %d (%a %a %a -> %a %a %a): float says face %u is surely missed; the double test hits it", k,
                      r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z, b->faces[j]);
            cr_assert(!(said.sure_hit & lane) || crossed,
                      "ray %d: float says face %u is surely hit; the double test misses it", k, b->faces[j]);
            if (crossed && corner != UINT32_MAX && has_corner(&m, b->faces[j], corner)) {
                cr_assert(!(said.sure_hit & lane),
                          "ray %d through corner %u: float is sure it hits face %u, whose edges pass through the ray", k,
                          corner, b->faces[j]);
                unsure_at_corners++;
            }
            sure_hits += (said.sure_hit & lane) != 0;
            sure_misses += (said.sure_miss & lane) != 0;
        }
    }
    cr_assert_gt(unsure_at_corners, GRAZING_RAYS, "too few rays crossed the triangles around the corner they aim at");
    cr_assert_gt(sure_hits, GRAZING_RAYS, "the float test was hardly ever sure of a hit");
    cr_assert_gt(sure_misses, (size_t)GRAZING_RAYS * m.face_count / 2, "the float test dropped too few triangles");
    fast_bvh_free(b);
    mesh_free(&m);
}

/* The brute-force loop's nearest face on r (UINT32_MAX for none) and its t. */
static uint32_t brute_force_nearest(const struct mesh *m, const ray *r, double *t) {
    uint32_t nearest = UINT32_MAX;
    *t = INFINITY;
    for (uint32_t f = 0; f < m->face_count; f++) {
        const uint32_t *v = m->faces[f].v;
        double u, w;
        if (triangle_intersect(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]], r, RAY_T_MIN, *t, t, &u, &w))
            nearest = f;
    }
    return nearest;
}

Test(float_triangle, rung_11_gives_the_brute_force_answers_on_grazing_rays_and_counts_its_verdicts) {
    struct mesh m = bumpy_grid();
    struct fast_bvh *b = fast_bvh_build(&m, BVH_SPLIT_SAH, FAST_BVH_RUNG_EXACT);
    cr_assert_not_null(b);
    float_triangle_thread = (struct float_triangle_counts){0, 0, 0};
    struct draws state = {2, 0};
    for (int k = 0; k < 4 * GRAZING_RAYS; k++) {
        uint32_t corner;
        ray r = grazing_ray(&state, &m, k, &corner);
        double want_t, got_t = NAN;
        uint32_t want = brute_force_nearest(&m, &r, &want_t), got = UINT32_MAX;
        bool found = fast_bvh_closest(b, &r, RAY_T_MIN, INFINITY, &got_t, &got);
        cr_assert_eq(found, want != UINT32_MAX, "ray %d: rung 11 %s, the brute-force loop %s", k,
                     found ? "hits" : "misses", want != UINT32_MAX ? "hits" : "misses");
        if (found) {
            cr_assert_eq(got, want, "ray %d: rung 11 finds face %u, the brute-force loop %u", k, got, want);
            cr_assert(got_t == want_t, "ray %d: rung 11's t %a, the brute-force loop's %a", k, got_t, want_t);
        }
        cr_assert_eq(fast_bvh_occluded(b, &r, RAY_T_MIN, INFINITY), want != UINT32_MAX, "ray %d: occluded", k);
    }
    if (b->float_corners != NULL) {
        struct float_triangle_counts said = float_triangle_thread;
        cr_expect_gt(said.too_close, 0, "no triangle was too close to call on rays through corners and edges");
        cr_expect_gt(said.sure_hits, 0);
        cr_expect_gt(said.tests, said.sure_hits + said.too_close, "the float test dropped nothing");
    }
    fast_bvh_free(b);
    mesh_free(&m);
}
