/* test_fast_bvh_packet.c: rung 10's packets give every ray exactly the answers of fast_bvh_closest and
 * fast_bvh_occluded, which tests/test_accel.c proves equal to the brute-force loop's: coherent camera
 * rays, the shadow rays of their hits towards a light, scattered rays, rays through corners and along
 * edges (ties), rays edge-on to axis-aligned faces, windows ending or starting exactly at a hit, some
 * lanes off, on rung 9's tree (the one rung 10 walks: its leaves tested four
 * triangles at a time), on rung 8's 8-wide tree, on rung 6's (rung 8 without AVX2), on rung 7's compact
 * leaves and on rung 2's tree. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "fast_bvh.h"
#include "fast_bvh_build.h"
#include "fast_bvh_eight.h"
#include "fast_bvh_packet.h"
#include "mesh_load.h"
#include "stats.h"

/* Packets of each sort per tree. */
#define PACKET_TEST_ROUNDS 400

/* A value that no answer has: a lane left alone keeps it. */
#define UNTOUCHED_T -7.25
#define UNTOUCHED_FACE 0xdeadbeefu

struct rng {
    uint64_t state;
};

/* xorshift64*: reproducible, and enough for picking rays. */
static uint64_t rng_next(struct rng *g) {
    g->state ^= g->state >> 12;
    g->state ^= g->state << 25;
    g->state ^= g->state >> 27;
    return g->state * 0x2545f4914f6cdd1dull;
}

static double rng_in(struct rng *g, double lo, double hi) {
    return lo + (hi - lo) * ((double)(rng_next(g) >> 11) * 0x1.0p-53);
}

static uint32_t rng_to(struct rng *g, uint32_t n) { return (uint32_t)(rng_next(g) % n); }

/* What a packet is checked against: the tree, and a name for messages. */
struct subject {
    const struct fast_bvh *b;
    const char *name;
    size_t packets, hits;    /* packets checked and lanes that hit, for the log */
    size_t occluded;         /* lanes occluded, of all packets */
    size_t shadow_packets, shadow_lanes, shadow_occluded; /* packets of shadow rays, their lanes, those occluded */
};

/* Asks the packet whether anything lies on its rays and asserts that every lane in `active` has
 * fast_bvh_occluded's answer, and no other lane is said to be occluded. Returns the lanes occluded. */
static size_t check_occluded_packet(struct subject *s, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                                  const double t_min[FAST_BVH_PACKET_SIZE],
                                  const double t_max[FAST_BVH_PACKET_SIZE]) {
    unsigned occluded = fast_bvh_occluded_packet(s->b, rays, active, t_min, t_max);
    size_t count = 0;
    cr_assert_eq(occluded & ~active, 0, "%s: lanes 0x%x occluded, only 0x%x were asked", s->name, occluded, active);
    for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
        bool single = (active >> k & 1) && fast_bvh_occluded(s->b, &rays[k], t_min[k], t_max[k]);
        const ray *r = &rays[k];
        cr_assert_eq((occluded >> k & 1) != 0, single,
                     "%s: lane %d of 0x%x, ray (%a, %a, %a) + t (%a, %a, %a) in (%a, %a): packet %s, single ray %s",
                     s->name, k, active, r->origin.x, r->origin.y, r->origin.z, r->direction.x, r->direction.y,
                     r->direction.z, t_min[k], t_max[k], occluded >> k & 1 ? "occluded" : "clear",
                     single ? "occluded" : "clear");
        count += single;
    }
    s->occluded += count;
    return count;
}

/* Walks the packet and asserts that every lane in `active` has fast_bvh_closest's answer, bit for bit,
 * and that the other lanes were not written; then the same for fast_bvh_occluded's. */
static void check_packet(struct subject *s, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                         const double t_min[FAST_BVH_PACKET_SIZE], const double t_max[FAST_BVH_PACKET_SIZE]) {
    double t[FAST_BVH_PACKET_SIZE];
    uint32_t face[FAST_BVH_PACKET_SIZE];
    for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
        t[k] = UNTOUCHED_T;
        face[k] = UNTOUCHED_FACE;
    }
    unsigned found = fast_bvh_closest_packet(s->b, rays, active, t_min, t_max, t, face);
    cr_assert_eq(found & ~active, 0, "%s: lanes 0x%x found something, only 0x%x were asked", s->name, found, active);
    s->packets++;
    for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
        double single_t = UNTOUCHED_T;
        uint32_t single_face = UNTOUCHED_FACE;
        bool hit = (active >> k & 1) &&
                   fast_bvh_closest(s->b, &rays[k], t_min[k], t_max[k], &single_t, &single_face);
        const ray *r = &rays[k];
        cr_assert_eq((found >> k & 1) != 0, hit,
                     "%s: lane %d of 0x%x, ray (%a, %a, %a) + t (%a, %a, %a) in (%a, %a): packet %s, single ray %s",
                     s->name, k, active, r->origin.x, r->origin.y, r->origin.z, r->direction.x, r->direction.y,
                     r->direction.z, t_min[k], t_max[k], found >> k & 1 ? "hits" : "misses", hit ? "hits" : "misses");
        cr_assert(memcmp(&t[k], &single_t, sizeof t[k]) == 0 && face[k] == single_face,
                  "%s: lane %d, ray (%a, %a, %a) + t (%a, %a, %a): packet t %a face %u, single ray t %a face %u",
                  s->name, k, r->origin.x, r->origin.y, r->origin.z, r->direction.x, r->direction.y, r->direction.z,
                  t[k], face[k], single_t, single_face);
        s->hits += hit;
    }
    check_occluded_packet(s, rays, active, t_min, t_max);
}

/* The shadow rays of the hits of a packet of camera rays towards the point light, in the window the
 * frame of chapter 11's benchmark traces them in; checked as a packet. */
static void check_shadow_packet(struct subject *s, const ray camera_rays[FAST_BVH_PACKET_SIZE], vec3 light) {
    double t_min[FAST_BVH_PACKET_SIZE], t_max[FAST_BVH_PACKET_SIZE], t[FAST_BVH_PACKET_SIZE];
    uint32_t face[FAST_BVH_PACKET_SIZE];
    ray rays[FAST_BVH_PACKET_SIZE];
    unsigned lit = 0;
    for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
        rays[k] = camera_rays[k];
        t_min[k] = RAY_T_MIN;
        t_max[k] = INFINITY;
        if (!fast_bvh_closest(s->b, &camera_rays[k], RAY_T_MIN, INFINITY, &t[k], &face[k]))
            continue;
        vec3 point = ray_at(camera_rays[k], t[k]), to_light = vec3_sub(light, point);
        double distance = vec3_length(to_light);
        rays[k] = (ray){point, vec3_scale(to_light, 1.0 / distance)};
        t_min[k] = SHADOW_T_MIN;
        t_max[k] = distance - SHADOW_T_MIN;
        lit |= 1u << k;
    }
    s->shadow_occluded += check_occluded_packet(s, rays, lit, t_min, t_max);
    s->shadow_packets += lit != 0;
    s->shadow_lanes += (size_t)__builtin_popcount(lit);
}

/* A ray through a corner, the middle of an edge (both shared by several faces: ties) or a face's
 * centre, from a random point of the box around the mesh; a quarter of the time parallel to an axis,
 * the other components +-0, so that it runs edge-on along axis-aligned faces. */
static ray ray_at_feature(struct rng *g, const struct mesh *m, vec3 lo, vec3 hi) {
    const uint32_t *v = m->faces[rng_to(g, (uint32_t)m->face_count)].v;
    vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
    vec3 targets[3] = {a, vec3_scale(vec3_add(a, b), 0.5), vec3_scale(vec3_add(vec3_add(a, b), c), 1.0 / 3.0)};
    vec3 target = targets[rng_to(g, 3)];
    vec3 size = vec3_sub(hi, lo);
    vec3 origin = {rng_in(g, lo.x - size.x, hi.x + size.x), rng_in(g, lo.y - size.y, hi.y + size.y),
                   rng_in(g, lo.z - size.z, hi.z + size.z)};
    if (rng_to(g, 4) == 0) {
        int axis = (int)rng_to(g, 3);
        double sign = rng_to(g, 2) ? 1.0 : -1.0;
        vec3 d = {rng_to(g, 2) ? 0.0 : -0.0, rng_to(g, 2) ? 0.0 : -0.0, rng_to(g, 2) ? 0.0 : -0.0};
        double *along = axis == 0 ? &d.x : axis == 1 ? &d.y : &d.z;
        *along = sign;
        double *start = axis == 0 ? &origin.x : axis == 1 ? &origin.y : &origin.z;
        origin = target;
        *start -= sign * (1.0 + fabs(*start)) * 2.0;
        return (ray){origin, d};
    }
    vec3 d = vec3_sub(target, origin);
    double length = vec3_length(d);
    return (ray){origin, length > 0.0 ? vec3_scale(d, 1.0 / length) : vec3_make(0, 0, 1)};
}

/* Packets of every sort on tree s over mesh m (box lo .. hi). */
static void check_packets(struct subject *s, const struct mesh *m, uint64_t seed) {
    struct rng g = {seed};
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < m->vertex_count; k++) {
        lo = vec3_min(lo, m->vertices[k]);
        hi = vec3_max(hi, m->vertices[k]);
    }
    vec3 centre = vec3_scale(vec3_add(lo, hi), 0.5);
    double size = vec3_length(vec3_sub(hi, lo));
    ray rays[FAST_BVH_PACKET_SIZE];
    double t_min[FAST_BVH_PACKET_SIZE], t_max[FAST_BVH_PACKET_SIZE];
    for (int round = 0; round < PACKET_TEST_ROUNDS; round++) {
        /* Coherent: a 4 x 2 block of a camera's pixels, as chapter 11 packs them; all lanes or some. */
        struct camera cam;
        char err[128];
        vec3 eye = vec3_add(centre, vec3_scale(vec3_make(rng_in(&g, -1, 1), rng_in(&g, -1, 1), rng_in(&g, -1, 1)),
                                               size * rng_in(&g, 0.3, 2.0)));
        int width = 16 + (int)rng_to(&g, 200);
        if (!camera_init(&cam, eye, centre, vec3_make(0, 1, 0), rng_in(&g, 10, 90), width, width * 3 / 4, err,
                         sizeof err))
            continue; /* the eye straight above the centre: no picture (a rare draw) */
        int x = (int)rng_to(&g, (uint32_t)width), y = (int)rng_to(&g, (uint32_t)(width * 3 / 4));
        for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
            rays[k] = camera_ray(&cam, x + k % 4, y + k / 4);
            t_min[k] = RAY_T_MIN;
            t_max[k] = INFINITY;
        }
        check_packet(s, rays, 0xffu, t_min, t_max);
        check_packet(s, rays, (unsigned)rng_to(&g, 256), t_min, t_max);
        /* Their shadow rays, towards a light outside the box or inside it (among the triangles). */
        vec3 light = vec3_add(centre, vec3_scale(vec3_make(rng_in(&g, -1, 1), rng_in(&g, -1, 1), rng_in(&g, -1, 1)),
                                                 size * rng_in(&g, 0.0, 2.0)));
        check_shadow_packet(s, rays, light);
        /* Scattered: eight unrelated rays at corners, edges and faces, some edge-on, in windows that
         * start before 0 (the single-ray fallback), at 0, at RAY_T_MIN, or end early. */
        static const double starts[] = {RAY_T_MIN, 0.0, -INFINITY, SHADOW_T_MIN};
        for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
            rays[k] = ray_at_feature(&g, m, lo, hi);
            t_min[k] = starts[rng_to(&g, 4)];
            t_max[k] = rng_to(&g, 4) == 0 ? rng_in(&g, 0.0, 3.0 * size) : INFINITY;
        }
        check_packet(s, rays, 0xffu, t_min, t_max);
        check_packet(s, rays, (unsigned)rng_to(&g, 256), t_min, t_max);
        /* One ray eight times, its windows ending or starting exactly at its own hits: the tie rule and
         * the window's ends. */
        ray r = ray_at_feature(&g, m, lo, hi);
        double t_hit;
        uint32_t face;
        for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
            rays[k] = r;
            t_min[k] = k < 4 ? RAY_T_MIN : 0.0;
            t_max[k] = INFINITY;
        }
        if (fast_bvh_closest(s->b, &r, RAY_T_MIN, INFINITY, &t_hit, &face)) {
            t_max[1] = t_hit;                       /* ends at the hit: not found, the one before may be */
            t_min[2] = t_hit;                       /* starts at it: the next one */
            t_max[3] = nextafter(t_hit, INFINITY);  /* just past it: found */
            t_min[5] = nextafter(t_hit, -INFINITY); /* just before it: found */
        }
        check_packet(s, rays, 0xffu, t_min, t_max);
    }
}

/* Axis-aligned unit squares, two triangles each, stacked three deep and standing on end: rays along
 * the axes meet their faces edge-on and their shared edges and corners. */
static struct mesh make_squares(int n) {
    struct mesh m = {0};
    m.vertices = malloc(sizeof *m.vertices * (size_t)(4 * 3 * n * n));
    m.faces = malloc(sizeof *m.faces * (size_t)(2 * 3 * n * n));
    cr_assert(m.vertices != NULL && m.faces != NULL);
    for (int axis = 0; axis < 3; axis++)
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                uint32_t v = (uint32_t)m.vertex_count;
                for (int c = 0; c < 4; c++) {
                    double p[3];
                    p[axis] = (double)(i % 3);
                    p[(axis + 1) % 3] = (double)(j + (c & 1));
                    p[(axis + 2) % 3] = (double)(i / 3 + (c >> 1));
                    m.vertices[m.vertex_count++] = vec3_make(p[0], p[1], p[2]);
                }
                m.faces[m.face_count++] = (struct mesh_face){{v, v + 1, v + 2}};
                m.faces[m.face_count++] = (struct mesh_face){{v + 1, v + 3, v + 2}};
            }
    return m;
}

/* Checks packets on mesh m on every tree rung 10 may walk. */
static void check_trees(const char *name, const struct mesh *m, uint64_t seed) {
    static const struct {
        enum fast_bvh_rung rung;
        bool without_avx2;
        const char *what;
    } trees[] = {{FAST_BVH_RUNG_LEAN, false, "rung 9's tree (rung 10's)"},
                 {FAST_BVH_RUNG_EIGHT, false, "rung 8's tree"},
                 {FAST_BVH_RUNG_EIGHT, true, "rung 8's tree without AVX2 (rung 6's)"},
                 {FAST_BVH_RUNG_COMPACT, false, "rung 7's compact leaves"},
                 {FAST_BVH_RUNG_WIDE, false, "rung 2's tree"}};
    for (size_t k = 0; k < sizeof trees / sizeof trees[0]; k++) {
        if (trees[k].without_avx2)
            cr_assert_eq(setenv(FAST_BVH_NO_AVX2_VARIABLE, "1", 1), 0);
        struct fast_bvh *b = fast_bvh_build(m, BVH_SPLIT_SAH, trees[k].rung);
        cr_assert_eq(unsetenv(FAST_BVH_NO_AVX2_VARIABLE), 0);
        cr_assert_not_null(b);
        if (trees[k].rung == FAST_BVH_RUNG_EIGHT || trees[k].rung == FAST_BVH_RUNG_LEAN)
            cr_assert_eq(b->nodes8 != NULL, !trees[k].without_avx2 && fast_bvh_eight_available(),
                         "%s: %s is not the tree asked for", name, trees[k].what);
        if (trees[k].rung == FAST_BVH_RUNG_LEAN)
            cr_assert_eq(b->lean_corners != NULL, b->nodes8 != NULL, "%s: %s has no lean leaves", name,
                         trees[k].what);
        char label[160];
        snprintf(label, sizeof label, "%s, %s", name, trees[k].what);
        struct subject s = {b, label, 0, 0, 0, 0, 0, 0};
        check_packets(&s, m, seed);
        cr_assert_gt(s.hits, s.packets, "%s: too few hits (%zu in %zu packets) to prove anything", label, s.hits,
                     s.packets);
        cr_assert_gt(s.shadow_packets, PACKET_TEST_ROUNDS / 4, "%s: too few packets of shadow rays (%zu)", label,
                     s.shadow_packets);
        cr_assert(s.shadow_occluded > s.shadow_lanes / 10 && s.shadow_occluded < s.shadow_lanes - s.shadow_lanes / 10,
                  "%s: %zu of %zu shadow rays occluded: too few or too many to prove anything", label,
                  s.shadow_occluded, s.shadow_lanes);
        cr_log_info("%s: %zu packets, %zu lanes hit, every lane as fast_bvh_closest, %zu occluded, as "
                    "fast_bvh_occluded; %zu packets of shadow rays, %zu of their %zu lanes occluded",
                    label, s.packets, s.hits, s.occluded, s.shadow_packets, s.shadow_occluded, s.shadow_lanes);
        fast_bvh_free(b);
    }
}

static void check_model(const char *path, uint64_t seed) {
    struct mesh m;
    char err[512];
    cr_assert(mesh_load(path, &m, err, sizeof err), "%s", err);
    check_trees(path, &m, seed);
    mesh_free(&m);
}

Test(packet, every_lane_is_the_single_rays_answer_on_the_teapot) { check_model("scenes/models/teapot-5k.ply", 11); }

Test(packet, every_lane_is_the_single_rays_answer_on_the_bunny) { check_model("scenes/models/bunny.ply", 12); }

Test(packet, every_lane_is_the_single_rays_answer_on_axis_aligned_squares) {
    struct mesh m = make_squares(9);
    check_trees("axis-aligned squares", &m, 13);
    mesh_free(&m);
}

/* The packet walks the tree once for its rays: on a camera's neighbouring pixels it visits fewer nodes
 * than its rays one by one (else it is no packet), and tests the same triangles or a few more; on rung
 * 8's tree and on rung 9's, which rung 10 walks. */
static void check_shared_walk(const struct mesh *m, enum fast_bvh_rung rung, const char *what) {
    char err[512];
    struct fast_bvh *b = fast_bvh_build(m, BVH_SPLIT_SAH, rung);
    cr_assert_not_null(b);
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < m->vertex_count; k++) {
        lo = vec3_min(lo, m->vertices[k]);
        hi = vec3_max(hi, m->vertices[k]);
    }
    vec3 centre = vec3_scale(vec3_add(lo, hi), 0.5);
    struct camera cam;
    cr_assert(camera_init(&cam, vec3_add(centre, vec3_make(0, 0, 1.5 * vec3_length(vec3_sub(hi, lo)))), centre,
                          vec3_make(0, 1, 0), 30, 64, 48, err, sizeof err), "%s", err);
    struct stats packets = {0}, singles = {0};
    for (int y = 0; y < 48; y += 2)
        for (int x = 0; x < 64; x += 4) {
            ray rays[FAST_BVH_PACKET_SIZE];
            double t_min[FAST_BVH_PACKET_SIZE], t_max[FAST_BVH_PACKET_SIZE], t[FAST_BVH_PACKET_SIZE];
            uint32_t face[FAST_BVH_PACKET_SIZE];
            for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
                rays[k] = camera_ray(&cam, x + k % 4, y + k / 4);
                t_min[k] = RAY_T_MIN;
                t_max[k] = INFINITY;
            }
            stats_reset_thread();
            fast_bvh_closest_packet(b, rays, 0xffu, t_min, t_max, t, face);
            stats_add(&packets, &stats_thread);
            stats_reset_thread();
            for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++)
                fast_bvh_closest(b, &rays[k], t_min[k], t_max[k], &t[k], &face[k]);
            stats_add(&singles, &stats_thread);
        }
    cr_log_info("bunny, %s, 64 x 48 camera rays: %llu node visits in packets, %llu one by one; triangle tests %llu, "
                "%llu", what, (unsigned long long)packets.node_visits, (unsigned long long)singles.node_visits,
                (unsigned long long)packets.triangle_tests, (unsigned long long)singles.triangle_tests);
    cr_expect_lt(2 * packets.node_visits, singles.node_visits, "%s: packets visited %llu nodes, single rays %llu", what,
                 (unsigned long long)packets.node_visits, (unsigned long long)singles.node_visits);
    cr_expect_lt(packets.triangle_tests, singles.triangle_tests + singles.triangle_tests / 4,
                 "%s: packets tested %llu triangles, single rays %llu", what,
                 (unsigned long long)packets.triangle_tests, (unsigned long long)singles.triangle_tests);
    fast_bvh_free(b);
}

Test(packet, a_packet_of_camera_rays_shares_its_walk) {
    struct mesh m;
    char err[512];
    cr_assert(mesh_load("scenes/models/bunny.ply", &m, err, sizeof err), "%s", err);
    check_shared_walk(&m, FAST_BVH_RUNG_EIGHT, "rung 8's tree");
    check_shared_walk(&m, FAST_BVH_RUNG_LEAN, "rung 9's tree");
    mesh_free(&m);
}
