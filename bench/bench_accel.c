/* bench_accel.c: times the acceleration structures of chapters 9, 10 and 11 on real models.
 *
 *     bench_accel [--embree] [--repeats N] [--only NAME] [--size WxH] [--csv FILE] MODEL.ply...
 *
 * For each model: a camera fitted to its bounding sphere, 800x600 pixels (--size WxH), one camera ray per pixel,
 * one point light and, from every hit, one shadow ray towards it; one thread. Each structure is built
 * and the frame traced --repeats times (default 3), in rounds that take every structure in turn, and
 * the fastest of each is reported: build ms,
 * frame ms, million rays per second, and the counters per ray. The brute-force loop ("naive") would
 * take hours on big models, so it traces only a few evenly spaced rows and its time is scaled up to the
 * whole frame; its row says "(sampled)". With --embree (when built with Embree, see bench/bench.mk)
 * Intel Embree 3 traces the same rays as the yardstick and every row gets its ratio to it. --only NAME
 * runs just the structure called NAME (and BVH-SAH, the reference), e.g. for a profiler; NAME may list
 * several, separated by commas ("rung 9 lean,rung 11 exact-float"), which then take turns.
 *
 * --csv FILE also writes the tables' rows to FILE as CSV, for scripts: a header line (CSV_HEADER below),
 * then one line per model and structure, the numbers exact (every printed value can be recomputed from
 * them), an empty field where the table prints "-". It is written to FILE.tmp and renamed when every
 * model is done, so a run that fails or is interrupted leaves no half file; if FILE cannot be written
 * the program says `bench_accel: FILE: why` and exits with status 3.
 *
 * Every structure must find exactly the brute-force answer, so each frame is also checked pixel by
 * pixel against the BVH-SAH frame: the nearest face, its t to the last bit, and the shadow. The rows
 * "rung N" are chapter 11's ladder (rung 1 is chapter 10's BVH-SAH); each gets its ratio to the rung
 * below (rung 8's to rung 6, which it widens; without AVX2 it is rung 6 again; rung 11's to rung 9,
 * whose tree it walks). Under the table, rung 11's row is followed by what its float triangle test said:
 * the share of its triangles dropped as sure misses, and the shares tested again in double (sure hits,
 * for their t, and those too close to call). Embree works
 * in float, so it is only expected to agree on nearly every pixel; its count of differing pixels is
 * printed for information.
 *
 * The clock is the processor time of the process (CLOCK_PROCESS_CPUTIME_ID), not the wall clock: on a
 * shared machine with more runnable work than cores, wall times of the same frame varied by a factor
 * of two between runs, while processor time counts only the time the benchmark itself ran. It still
 * varies with what shares the caches, so every row is the best of its rounds. All builds, ours and
 * Embree's, are timed around the call that makes the structure, on that clock. */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <omp.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "clock.h"
#include "fast_bvh.h"
#include "fast_bvh_build.h"
#include "fast_bvh_eight.h"
#include "fast_bvh_packet.h"
#include "float_triangle.h"
#include "camera.h"
#include "kdtree.h"
#include "mesh.h"
#include "mesh_load.h"
#include "stats.h"
#include "triangle.h"

/* The default frame; --size WxH sets another (the tests use a small one to stay fast). */
#define BENCH_WIDTH 800
#define BENCH_HEIGHT 600
/* The largest side --size accepts: far beyond any useful frame, and small enough that
 * width * height pixels of bookkeeping always fit in memory sizes and in an int. */
#define BENCH_MAX_SIDE 16384
#define BENCH_VFOV_DEGREES 40.0
/* The brute-force rows are chosen to cost about this many triangle tests in all (~4 s at about
 * 8 ns a test), and never fewer than BENCH_NAIVE_MIN_ROWS rows. */
#define BENCH_NAIVE_BUDGET_TESTS 5e8
#define BENCH_NAIVE_MIN_ROWS 3

#ifdef WHITTED_EMBREE
/* Defined in embree_ref.c: builds and traces the same frame with Embree; see there. */
bool embree_ref_frame(const struct mesh *m, const struct camera *cam, vec3 light, int packet,
                      bool shadow_packets, int repeats, double *build_ms, double *frame_ms, unsigned char *pixels,
                      char *err, size_t err_size);
#endif


/* The benchmark's clock, in milliseconds: the processor time of the whole process (see the comment at
 * the top). */
static double processor_ms(void) { return 1e3 * clock_processor_seconds(); }

/* ---- the structures behind one interface -------------------------------------------------------- */

enum structure { NAIVE, KDTREE, BVH, FAST_BVH, FAST_BVH_PACKETS };

struct accel {
    const char *name;     /* as the table and --only say it */
    const char *csv_name; /* the stable machine name in the CSV's "structure" column */
    enum structure structure;
    int rule;  /* an enum kd_split for KDTREE, an enum bvh_split for BVH, an enum fast_bvh_rung for FAST_BVH
                  and FAST_BVH_PACKETS (built by the SAH; the packets' camera rays walk that rung's tree) */
    int below; /* the row of the rung below, for the ratio; -1 when not a rung */
};

/* A structure built over the model, as one row of the table has it. */
struct built {
    enum structure structure;
    const struct mesh *mesh;   /* NAIVE: the faces tested one by one */
    struct kdtree *kdtree;     /* KDTREE */
    struct bvh *bvh;           /* BVH */
    struct fast_bvh *fast_bvh; /* FAST_BVH */
};

/* Builds a's structure over m into *out, timing it into *build_ms (0 for the brute-force loop, which
 * builds nothing) and putting its own predicted cost per ray in *sah_cost. Returns false when memory
 * runs out. */
static bool build(const struct accel *a, const struct mesh *m, struct built *out, double *build_ms,
                  double *sah_cost) {
    *out = (struct built){a->structure, m, NULL, NULL, NULL};
    double start = processor_ms();
    switch (a->structure) {
    case NAIVE:
        *build_ms = 0.0;
        *sah_cost = (double)m->face_count;
        return true;
    case KDTREE:
        out->kdtree = kdtree_build(m, (enum kd_split)a->rule);
        break;
    case BVH:
        out->bvh = bvh_build(m, (enum bvh_split)a->rule);
        break;
    case FAST_BVH:
    case FAST_BVH_PACKETS:
        out->fast_bvh = fast_bvh_build(m, BVH_SPLIT_SAH, (enum fast_bvh_rung)a->rule);
        break;
    }
    *build_ms = processor_ms() - start;
    struct kdtree_info kd_info;
    if (out->kdtree != NULL)
        kdtree_get_info(out->kdtree, &kd_info);
    *sah_cost = out->kdtree != NULL ? kd_info.sah_cost
              : out->bvh != NULL    ? out->bvh->info.sah_cost
              : out->fast_bvh != NULL ? out->fast_bvh->info.sah_cost
                                      : 0.0;
    return out->kdtree != NULL || out->bvh != NULL || out->fast_bvh != NULL;
}

static void destroy(struct built *b) {
    kdtree_free(b->kdtree);
    bvh_free(b->bvh);
    fast_bvh_free(b->fast_bvh);
}

/* The brute-force loop: every face, every ray. */
static bool naive_closest(const struct mesh *m, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    bool found = false;
    struct triangle_ray prepared = triangle_ray_make(r); /* once for all faces, as triangle_mesh_closest does */
    double u, v;
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *c = m->faces[k].v;
        if (triangle_intersect_prepared(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]], &prepared, t_min,
                                        t_max, &t_max, &u, &v)) {
            found = true;
            *face = (uint32_t)k;
        }
    }
    if (found)
        *t = t_max;
    return found;
}

static bool naive_occluded(const struct mesh *m, const ray *r, double t_min, double t_max) {
    struct triangle_ray prepared = triangle_ray_make(r);
    double t, u, v;
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *c = m->faces[k].v;
        if (triangle_intersect_prepared(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]], &prepared, t_min,
                                        t_max, &t, &u, &v))
            return true;
    }
    return false;
}

/* The nearest face b's structure finds on r with t_min < t < t_max. */
static bool closest(const struct built *b, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    switch (b->structure) {
    case KDTREE:
        return kdtree_closest(b->kdtree, r, t_min, t_max, t, face);
    case BVH:
        return bvh_closest(b->bvh, r, t_min, t_max, t, face);
    case FAST_BVH:
    case FAST_BVH_PACKETS:
        return fast_bvh_closest(b->fast_bvh, r, t_min, t_max, t, face);
    default:
        return naive_closest(b->mesh, r, t_min, t_max, t, face);
    }
}

/* Whether b's structure finds anything on r with t_min < t < t_max. */
static bool occluded(const struct built *b, const ray *r, double t_min, double t_max) {
    switch (b->structure) {
    case KDTREE:
        return kdtree_occluded(b->kdtree, r, t_min, t_max);
    case BVH:
        return bvh_occluded(b->bvh, r, t_min, t_max);
    case FAST_BVH:
    case FAST_BVH_PACKETS:
        return fast_bvh_occluded(b->fast_bvh, r, t_min, t_max);
    default:
        return naive_occluded(b->mesh, r, t_min, t_max);
    }
}

/* In the order the table prints them; BVH-SAH (index ACCEL_REFERENCE) is traced first and is the
 * frame the others are checked against. */
static const struct accel accels[] = {
    {"naive", "naive", NAIVE, 0, -1},
    {"kd-seed", "kd-seed", KDTREE, KD_SPLIT_SEED, -1},
    {"kd-SAH", "kd-sah", KDTREE, KD_SPLIT_SAH, -1},
    {"BVH-median", "bvh-median", BVH, BVH_SPLIT_MEDIAN, -1},
    {"BVH-SAH (rung 1 plain)", "bvh-sah", BVH, BVH_SPLIT_SAH, -1},
    {"rung 2 wide", "rung-2", FAST_BVH, FAST_BVH_RUNG_WIDE, 4},
    {"rung 3 simd", "rung-3", FAST_BVH, FAST_BVH_RUNG_SIMD, 5},
    {"rung 4 prefetch", "rung-4", FAST_BVH, FAST_BVH_RUNG_PREFETCH, 6},
    {"rung 5 build", "rung-5", FAST_BVH, FAST_BVH_RUNG_BUILD, 7},
    {"rung 6 float", "rung-6", FAST_BVH, FAST_BVH_RUNG_FLOAT, 8},
    {"rung 7 compact", "rung-7", FAST_BVH, FAST_BVH_RUNG_COMPACT, 9},
    {"rung 8 eight", "rung-8", FAST_BVH, FAST_BVH_RUNG_EIGHT, 9}, /* rung 6 on eight lanes: compared with 6 */
    {"rung 9 lean", "rung-9", FAST_BVH, FAST_BVH_RUNG_LEAN, 11},  /* rung 8's kind of tree, less per ray: with 8 */
    {"rung 10 packet", "rung-10", FAST_BVH_PACKETS, FAST_BVH_RUNG_LEAN, 12}, /* rung 9's tree: compared with 9 */
    {"rung 11 exact-float", "rung-11", FAST_BVH, FAST_BVH_RUNG_EXACT, 12}, /* rung 9's tree: compared with 9 */
};
#define ACCEL_COUNT (sizeof accels / sizeof accels[0])
#define ACCEL_NAIVE 0
#define ACCEL_REFERENCE 4
#define ACCEL_PACKETS 13 /* rung 10's row */
#define ACCEL_EXACT 14   /* rung 11's row */

/* ---- the frame --------------------------------------------------------------------------------- */

/* What one pixel saw: the nearest face (UINT32_MAX for none), its t, and whether the light is hidden. */
struct pixel {
    double t;
    uint32_t face;
    bool shadowed;
};

struct frame {
    double ms;
    struct stats counters;        /* all rays */
    struct float_triangle_counts float_counts; /* rung 11's float triangle test, all rays */
    uint64_t primary_tests;       /* triangle tests spent on camera rays alone */
};

/* The shadow ray from where camera ray r hit, at t, towards the light, traced over SHADOW_T_MIN < t <
 * *t_max (the distance to the light less SHADOW_T_MIN). */
static ray shadow_ray(const ray *r, double t, vec3 light, double *t_max) {
    vec3 point = ray_at(*r, t);
    vec3 to_light = vec3_sub(light, point);
    double distance = vec3_length(to_light);
    *t_max = distance - SHADOW_T_MIN;
    return (ray){point, vec3_scale(to_light, 1.0 / distance)};
}

/* The shadow ray of pixel p, whose camera ray r hit at p->t: whether the light is hidden. */
static bool shadowed(const struct built *structure, const ray *r, const struct pixel *p, vec3 light) {
    double t_max;
    ray shadow = shadow_ray(r, p->t, light, &t_max);
    stats_thread.shadow_rays++;
    return occluded(structure, &shadow, SHADOW_T_MIN, t_max);
}

/* Rung 10: the whole frame with the camera rays in packets of FAST_BVH_PACKET_COLUMNS x
 * FAST_BVH_PACKET_ROWS pixels, as chapter 11 packs them (fast_bvh_closest_packet), and the shadow rays of
 * their hits in a packet of the same pixels (fast_bvh_occluded_packet), into pixels as trace_frame does. */
static void trace_frame_in_packets(const struct built *structure, const struct camera *cam, vec3 light,
                                   struct pixel *pixels, struct frame *out) {
    stats_reset_thread();
    float_triangle_thread = (struct float_triangle_counts){0, 0, 0};
    uint64_t primary_tests = 0;
    double start = processor_ms();
    for (int y = 0; y < cam->height; y += FAST_BVH_PACKET_ROWS)
        for (int x = 0; x < cam->width; x += FAST_BVH_PACKET_COLUMNS) {
            ray rays[FAST_BVH_PACKET_SIZE];
            double t_min[FAST_BVH_PACKET_SIZE], t_max[FAST_BVH_PACKET_SIZE], t[FAST_BVH_PACKET_SIZE];
            uint32_t face[FAST_BVH_PACKET_SIZE];
            /* the window starts at ray_t_min(eye), RAY_T_MIN as trace_frame's unless the eye is beyond 1e5 */
            unsigned active = fast_bvh_camera_packet(cam, x, y, cam->width, cam->height, rays, t_min, t_max);
            stats_thread.primary_rays += (uint64_t)__builtin_popcount(active);
            uint64_t before = stats_thread.triangle_tests;
            unsigned found = fast_bvh_closest_packet(structure->fast_bvh, rays, active, t_min, t_max, t, face);
            primary_tests += stats_thread.triangle_tests - before;
            ray shadows[FAST_BVH_PACKET_SIZE];
            double shadow_min[FAST_BVH_PACKET_SIZE], shadow_max[FAST_BVH_PACKET_SIZE];
            for (unsigned rest = found; rest != 0; rest &= rest - 1) {
                int k = __builtin_ctz(rest);
                shadows[k] = shadow_ray(&rays[k], t[k], light, &shadow_max[k]);
                shadow_min[k] = SHADOW_T_MIN;
            }
            stats_thread.shadow_rays += (uint64_t)__builtin_popcount(found);
            unsigned dark = found != 0 ? fast_bvh_occluded_packet(structure->fast_bvh, shadows, found, shadow_min,
                                                                  shadow_max)
                                       : 0;
            for (unsigned rest = active; rest != 0; rest &= rest - 1) {
                int k = __builtin_ctz(rest);
                int i = x + k % FAST_BVH_PACKET_COLUMNS, j = y + k / FAST_BVH_PACKET_COLUMNS;
                struct pixel p = {INFINITY, UINT32_MAX, false};
                if (found >> k & 1)
                    p = (struct pixel){t[k], face[k], (dark >> k & 1) != 0};
                pixels[(size_t)j * cam->width + i] = p;
            }
        }
    out->ms = processor_ms() - start;
    out->counters = stats_thread;
    out->float_counts = float_triangle_thread;
    out->primary_tests = primary_tests;
}

/* Traces the rows listed in rows[0..row_count) into pixels (indexed by j * width + i). */
static void trace_frame(const struct built *structure, const struct camera *cam, vec3 light, const int *rows,
                        int row_count, struct pixel *pixels, struct frame *out) {
    stats_reset_thread();
    float_triangle_thread = (struct float_triangle_counts){0, 0, 0};
    uint64_t primary_tests = 0;
    double start = processor_ms();
    for (int k = 0; k < row_count; k++) {
        int j = rows[k];
        for (int i = 0; i < cam->width; i++) {
            ray r = camera_ray(cam, i, j);
            stats_thread.primary_rays++;
            struct pixel p = {INFINITY, UINT32_MAX, false};
            uint64_t before = stats_thread.triangle_tests;
            bool hit = closest(structure, &r, RAY_T_MIN, INFINITY, &p.t, &p.face);
            primary_tests += stats_thread.triangle_tests - before;
            if (hit)
                p.shadowed = shadowed(structure, &r, &p, light);
            pixels[(size_t)j * cam->width + i] = p;
        }
    }
    out->ms = processor_ms() - start;
    out->counters = stats_thread;
    out->float_counts = float_triangle_thread;
    out->primary_tests = primary_tests;
}

/* Pixels of the listed rows where a and b differ (face, t or shadow). */
static long count_differences(const struct pixel *a, const struct pixel *b, int width, const int *rows, int row_count) {
    long differ = 0;
    for (int k = 0; k < row_count; k++)
        for (int i = 0; i < width; i++) {
            size_t at = (size_t)rows[k] * width + i;
            if (a[at].face != b[at].face || a[at].shadowed != b[at].shadowed ||
                (a[at].face != UINT32_MAX && a[at].t != b[at].t))
                differ++;
        }
    return differ;
}

/* A camera that sees the whole bounding sphere of m from the front, a little above and to the right
 * (the models are y-up), and a light above and behind the camera's right shoulder. */
static bool fit_camera(const struct mesh *m, int width, int height, struct camera *cam, vec3 *light) {
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < m->vertex_count; k++) {
        lo = vec3_min(lo, m->vertices[k]);
        hi = vec3_max(hi, m->vertices[k]);
    }
    vec3 centre = vec3_scale(vec3_add(lo, hi), 0.5);
    double radius = 0.5 * vec3_length(vec3_sub(hi, lo));
    double distance = radius / sin(0.5 * BENCH_VFOV_DEGREES * M_PI / 180.0);
    vec3 eye = vec3_add_scaled(centre, vec3_normalize(vec3_make(0.45, 0.35, 1.0)), distance);
    *light = vec3_add_scaled(centre, vec3_make(2.0, 4.0, 3.0), radius);
    char err[128];
    return camera_init(cam, eye, centre, vec3_make(0, 1, 0), BENCH_VFOV_DEGREES, width, height, err, sizeof err);
}

/* ---- the table --------------------------------------------------------------------------------- */

struct row {
    bool done;
    int below; /* as in struct accel */
    char label[48];
    const char *csv_name; /* as in struct accel; "embree" for Embree's row */
    int sampled_rows;     /* rows the brute-force loop traced; 0 for every other row */
    double build_ms, frame_ms, sah_cost;
    double rays, triangle_tests, node_visits, primary_rays, primary_tests;
    struct float_triangle_counts float_counts; /* rung 11: what its float triangle test said, in its best frame */
    long differ;
    bool compared;
};

/* The numeric columns of a row, in the order the table prints them (and the CSV writes them). */
enum column {
    COLUMN_BUILD_MS,
    COLUMN_FRAME_MS,
    COLUMN_MRAYS_PER_S,
    COLUMN_TRI_PER_RAY,
    COLUMN_NODES_PER_RAY,
    COLUMN_TRI_PER_CAMERA_RAY,
    COLUMN_SAH_COST,
    COLUMN_FRAME_OVER_EMBREE,
    COLUMN_BUILD_OVER_EMBREE,
    COLUMN_FRAME_OVER_BELOW,
    COLUMN_BUILD_OVER_BELOW,
    COLUMN_COUNT
};

/* Fills values[COLUMN_COUNT] for row r (one of rows[], or embree): NAN where the column does not apply
 * (the table's "-", the CSV's empty field). below is the row of the rung below r, or NULL; embree is
 * Embree's row, or NULL when Embree did not run. */
static void row_values(const struct row *r, const struct row *below, const struct row *embree,
                       double values[COLUMN_COUNT]) {
    bool counted = r->primary_rays > 0; /* ours count their tests; Embree does not tell */
    values[COLUMN_BUILD_MS] = r->build_ms > 0 ? r->build_ms : NAN;
    values[COLUMN_FRAME_MS] = r->frame_ms;
    values[COLUMN_MRAYS_PER_S] = r->rays / (r->frame_ms * 1e3);
    values[COLUMN_TRI_PER_RAY] = counted ? r->triangle_tests / r->rays : NAN;
    values[COLUMN_NODES_PER_RAY] = counted ? r->node_visits / r->rays : NAN;
    values[COLUMN_TRI_PER_CAMERA_RAY] = counted ? r->primary_tests / r->primary_rays : NAN;
    values[COLUMN_SAH_COST] = counted ? r->sah_cost : NAN;
    values[COLUMN_FRAME_OVER_EMBREE] = embree != NULL ? r->frame_ms / embree->frame_ms : NAN;
    values[COLUMN_BUILD_OVER_EMBREE] = embree != NULL && r->build_ms > 0 ? r->build_ms / embree->build_ms : NAN;
    values[COLUMN_FRAME_OVER_BELOW] = below != NULL ? r->frame_ms / below->frame_ms : NAN;
    values[COLUMN_BUILD_OVER_BELOW] = below != NULL ? r->build_ms / below->build_ms : NAN;
}

/* The row of the rung below rows[k], or NULL when rows[k] is not a rung or that rung did not run. */
static const struct row *row_below(const struct row *rows, size_t k) {
    return rows[k].below >= 0 && rows[rows[k].below].done ? &rows[rows[k].below] : NULL;
}

/* Row k of the table, rows[k] for k < count and embree (may be NULL) for k == count, with its values
 * (row_values) in values; NULL when that row did not run. */
static const struct row *table_row(const struct row *rows, size_t count, const struct row *embree, size_t k,
                                   double values[COLUMN_COUNT]) {
    const struct row *r = k < count ? &rows[k] : embree;
    if (r == NULL || !r->done)
        return NULL;
    bool with_embree = embree != NULL && embree->done;
    row_values(r, k < count ? row_below(rows, k) : NULL, with_embree ? embree : NULL, values);
    return r;
}

/* Prints x in a column of width w, or "-" when it does not apply (NAN). */
static void print_number(int w, double x, int decimals) {
    if (isnan(x))
        printf(" %*s", w, "-");
    else
        printf(" %*.*f", w, decimals, x);
}

static void print_table(const struct row *rows, size_t count, const struct row *embree) {
    static const int widths[COLUMN_COUNT] = {9, 10, 8, 8, 9, 9, 8, 8, 8, 8, 8};
    static const int decimals[COLUMN_COUNT] = {1, 1, 2, 2, 2, 2, 1, 2, 2, 2, 2};
    printf("  %-26s %9s %10s %8s %8s %9s %9s %8s %8s %8s %8s %8s  %s\n", "structure", "build ms", "frame ms", "Mrays/s",
           "tri/ray", "nodes/ray", "tri/cam", "SAH cost", "frame/E", "build/E", "frame/<", "build/<",
           "pixels as BVH-SAH's?");
    for (size_t k = 0; k <= count; k++) {
        double values[COLUMN_COUNT];
        const struct row *r = table_row(rows, count, embree, k, values);
        if (r == NULL)
            continue;
        printf("  %-26s", r->label);
        for (int c = 0; c < COLUMN_COUNT; c++)
            print_number(widths[c], values[c], decimals[c]);
        if (r->compared)
            printf("  %s", r->differ == 0 ? "all equal" : "NO");
        else if (r != embree)
            printf("  (the reference)");
        if (r->differ != 0)
            printf(" (%ld differ)", r->differ);
        printf("\n");
    }
    printf("  tri/ray, nodes/ray: triangle tests and node visits per ray (camera and shadow); tri/cam: triangle\n"
           "  tests per camera ray; SAH cost: the structure's own prediction, in triangle tests per ray;\n"
           "  frame/E, build/E: time over Embree's; frame/<, build/<: time over the rung below's; pixels: nearest face, its t to the last bit, and the shadow,\n"
           "  on every pixel (on the sampled rows for the brute-force loop)\n");
}

/* ---- the CSV ----------------------------------------------------------------------------------- */

/* The CSV's first line; the numeric columns from build_ms to build_over_below are enum column's. */
#define CSV_HEADER                                                                                        \
    "model,triangles,structure,build_ms,frame_ms,mrays_per_s,tri_per_ray,nodes_per_ray,tri_per_camera_ray," \
    "sah_cost,frame_over_embree,build_over_embree,frame_over_below,build_over_below,sampled_rows,"        \
    "pixels_differing"
/* A double printed with this many digits after the point or fewer reads back as the same double, unless
 * it is below about 1e-23; such a value (none occurs here) falls back to %.17g, which always does. */
#define CSV_MAX_DECIMALS 40

/* Writes ",x" to csv: nothing after the comma when x is NAN; otherwise x in plain decimal notation with
 * the fewest digits after the point that read back as exactly x, so that a script formatting the
 * field as the table does prints what the table printed. */
static void csv_number(FILE *csv, double x) {
    fputc(',', csv);
    if (isnan(x))
        return;
    char text[400]; /* room for DBL_MAX (309 digits) with CSV_MAX_DECIMALS decimals */
    for (int d = 0; d <= CSV_MAX_DECIMALS; d++) {
        snprintf(text, sizeof text, "%.*f", d, x);
        if (strtod(text, NULL) == x || isinf(x)) {
            fputs(text, csv);
            return;
        }
    }
    fprintf(csv, "%.17g", x);
}

/* Writes one CSV line per row that ran (rows[0..count), then Embree's when it ran) for the model
 * `model` of `triangles` faces. Write errors are left for the caller to find with ferror. */
static void csv_write_rows(FILE *csv, const char *model, size_t triangles, const struct row *rows, size_t count,
                           const struct row *embree) {
    for (size_t k = 0; k <= count; k++) {
        double values[COLUMN_COUNT];
        const struct row *r = table_row(rows, count, embree, k, values);
        if (r == NULL)
            continue;
        fprintf(csv, "%s,%zu,%s", model, triangles, r->csv_name);
        for (int c = 0; c < COLUMN_COUNT; c++)
            csv_number(csv, values[c]);
        fputc(',', csv);
        if (r->sampled_rows > 0)
            fprintf(csv, "%d", r->sampled_rows);
        fputc(',', csv);
        if (r->compared || r == embree) /* the reference has no count: it is what the others are compared to */
            fprintf(csv, "%ld", r->differ);
        fputc('\n', csv);
    }
}

/* The model's name for the CSV: path's base name without its extension ("scenes/models/bunny.ply" ->
 * "bunny"), into name (size bytes). */
static void model_name(const char *path, char *name, size_t size) {
    const char *base = strrchr(path, '/');
    base = base != NULL ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    int length = dot != NULL && dot != base ? (int)(dot - base) : (int)strlen(base);
    snprintf(name, size, "%.*s", length, base);
}

/* What the command line asked for. */
struct options {
    bool with_embree;
    int repeats;
    const char *only;  /* NULL: every structure */
    int width, height; /* the frame, in pixels */
    FILE *csv;         /* NULL without --csv */
};

/* Whether name is one of the comma-separated names in list. */
static bool named_in(const char *list, const char *name) {
    size_t length = strlen(name);
    for (const char *p = list; p != NULL; p = strchr(p, ',') != NULL ? strchr(p, ',') + 1 : NULL)
        if (strncmp(p, name, length) == 0 && (p[length] == ',' || p[length] == '\0'))
            return true;
    return false;
}

/* Benchmarks the model at path as the comment at the top says: prints its table and, with --csv, writes
 * its rows. Returns 0, or 1 after a message on standard error when the model cannot be loaded or
 * memory runs out. */
static int bench_model(const char *path, const struct options *options) {
    bool with_embree = options->with_embree;
    int repeats = options->repeats;
    const char *only = options->only;
    struct mesh m;
    char err[512];
    if (!mesh_load(path, &m, err, sizeof err)) {
        fprintf(stderr, "bench_accel: %s\n", err);
        return 1;
    }
    struct camera cam;
    vec3 light;
    if (!fit_camera(&m, options->width, options->height, &cam, &light)) {
        fprintf(stderr, "bench_accel: %s: cannot fit a camera (no vertices?)\n", path);
        mesh_free(&m);
        return 1;
    }
    size_t pixel_count = (size_t)cam.width * cam.height;
    struct pixel *reference = malloc(pixel_count * sizeof *reference);
    struct pixel *pixels = malloc(pixel_count * sizeof *pixels);
    int *all_rows = malloc((size_t)cam.height * sizeof *all_rows);
    int *sampled_rows = malloc((size_t)cam.height * sizeof *sampled_rows);
    if (reference == NULL || pixels == NULL || all_rows == NULL || sampled_rows == NULL) {
        fprintf(stderr, "bench_accel: out of memory\n");
        return 1;
    }
    for (int j = 0; j < cam.height; j++)
        all_rows[j] = j;

    /* The brute-force loop's rows: evenly spaced, as many as the budget allows. */
    double naive_tests_per_row = (double)m.face_count * cam.width * 1.5; /* ~half the rays cast shadows */
    int naive_rows = (int)(BENCH_NAIVE_BUDGET_TESTS / (naive_tests_per_row > 1 ? naive_tests_per_row : 1));
    naive_rows = naive_rows < BENCH_NAIVE_MIN_ROWS ? BENCH_NAIVE_MIN_ROWS : naive_rows;
    naive_rows = naive_rows > cam.height ? cam.height : naive_rows;
    for (int k = 0; k < naive_rows; k++)
        sampled_rows[k] = (int)((k + 0.5) * cam.height / naive_rows);

    printf("%s: %zu triangles, %dx%d, 1 camera ray per pixel + 1 shadow ray per hit, 1 thread, best of %d,\n"
           "processor time\n",
           path, m.face_count, cam.width, cam.height, repeats);
    fflush(stdout);

    struct row rows[ACCEL_COUNT] = {0};
    size_t order[ACCEL_COUNT] = {ACCEL_REFERENCE};
    for (size_t k = 0, n = 1; k < ACCEL_COUNT; k++)
        if (k != ACCEL_REFERENCE)
            order[n++] = k;
    struct row embree = {0};
    embree.build_ms = INFINITY;
    embree.frame_ms = INFINITY;
    /* Embree's packets of 4 and 8 camera rays, for rung 10: their best frame times with the shadow rays
     * one by one ([p][0]) and in packets of the same pixels ([p][1]). */
    static const int embree_packets[] = {4, 8};
    double embree_packet_ms[2][2] = {{INFINITY, INFINITY}, {INFINITY, INFINITY}};
    /* Round after round, every structure once per round (interleaved, so that a busy spell of a shared
     * machine slows all of them alike rather than one of them throughout); the best of the rounds is
     * kept. The reference goes first in each round, Embree last; the brute-force loop runs in the first round
     * only. */
    for (int run = 0; run < repeats; run++) {
        for (size_t o = 0; o < ACCEL_COUNT; o++) {
            size_t k = order[o];
            const struct accel *a = &accels[k];
            if (only != NULL && k != ACCEL_REFERENCE && !named_in(only, a->name))
                continue;
            struct row *row = &rows[k];
            bool naive = k == ACCEL_NAIVE;
            if (naive && run > 0)
                continue;
            const int *list = naive ? sampled_rows : all_rows;
            int list_count = naive ? naive_rows : cam.height;
            if (run == 0) {
                snprintf(row->label, sizeof row->label, "%s", a->name);
                row->csv_name = a->csv_name;
                row->sampled_rows = naive ? naive_rows : 0;
                if (naive && naive_rows < cam.height)
                    snprintf(row->label, sizeof row->label, "%s (sampled, %d rows)", a->name, naive_rows);
                row->below = a->below;
                row->build_ms = INFINITY;
                row->frame_ms = INFINITY;
            }
            double build_ms = 0, sah_cost = 0;
            struct built structure;
            if (!build(a, &m, &structure, &build_ms, &sah_cost)) {
                fprintf(stderr, "bench_accel: %s: out of memory building %s\n", path, a->name);
                return 1;
            }
            struct frame f;
            if (a->structure == FAST_BVH_PACKETS)
                trace_frame_in_packets(&structure, &cam, light, pixels, &f);
            else
                trace_frame(&structure, &cam, light, list, list_count, k == ACCEL_REFERENCE ? reference : pixels, &f);
            destroy(&structure);
            double scale = (double)cam.height / list_count; /* extrapolation of the sampled rows */
            row->build_ms = build_ms < row->build_ms ? build_ms : row->build_ms;
            if (f.ms * scale < row->frame_ms) {
                row->frame_ms = f.ms * scale;
                row->sah_cost = sah_cost;
                row->rays = (double)(f.counters.primary_rays + f.counters.shadow_rays) * scale;
                row->primary_rays = (double)f.counters.primary_rays * scale;
                row->triangle_tests = (double)f.counters.triangle_tests * scale;
                row->node_visits = (double)f.counters.node_visits * scale;
                row->primary_tests = (double)f.primary_tests * scale;
                row->float_counts = f.float_counts;
            }
            if (k != ACCEL_REFERENCE) {
                long differ = count_differences(reference, pixels, cam.width, list, list_count);
                row->differ = differ > row->differ ? differ : row->differ;
                row->compared = true;
            }
            row->done = true;
        }
#ifdef WHITTED_EMBREE
        if (with_embree) {
            unsigned char *codes = malloc(pixel_count);
            double build_ms, frame_ms;
            if (codes == NULL ||
                !embree_ref_frame(&m, &cam, light, 1, false, 1, &build_ms, &frame_ms, codes, err, sizeof err)) {
                fprintf(stderr, "bench_accel: %s: %s\n", path, codes == NULL ? "out of memory" : err);
                return 1;
            }
            snprintf(embree.label, sizeof embree.label, "Embree 3 (float, 1 thread)");
            embree.csv_name = "embree";
            embree.build_ms = build_ms < embree.build_ms ? build_ms : embree.build_ms;
            embree.frame_ms = frame_ms < embree.frame_ms ? frame_ms : embree.frame_ms;
            long differ = 0, hits = 0;
            for (size_t p = 0; p < pixel_count; p++) {
                int ours = reference[p].face == UINT32_MAX ? 0 : reference[p].shadowed ? 2 : 1;
                differ += codes[p] != ours;
                hits += codes[p] != 0;
            }
            embree.rays = (double)(pixel_count + hits);
            embree.differ = differ;
            embree.done = true;
            for (int p = 0; p < 4 && (only == NULL || named_in(only, "rung 10 packet")); p++) {
                double *best = &embree_packet_ms[p / 2][p % 2];
                if (!embree_ref_frame(&m, &cam, light, embree_packets[p / 2], p % 2 == 1, 1, &build_ms, &frame_ms,
                                      codes, err, sizeof err)) {
                    fprintf(stderr, "bench_accel: %s: %s\n", path, err);
                    return 1;
                }
                *best = frame_ms < *best ? frame_ms : *best;
            }
            free(codes);
        }
#else
        (void)with_embree;
#endif
        fprintf(stderr, "  round %d of %d done\n", run + 1, repeats);
    }

    print_table(rows, ACCEL_COUNT, with_embree ? &embree : NULL);
    if (embree.done)
        printf("  Embree's pixels are compared with BVH-SAH's hit/miss and shadow only: it works in float, so a\n"
               "  few grazing rays may go the other way\n");
    const struct float_triangle_counts *said = &rows[ACCEL_EXACT].float_counts;
    if (rows[ACCEL_EXACT].done && said->tests > 0) {
        double tests = (double)said->tests, sure = (double)said->sure_hits, close = (double)said->too_close;
        printf("  rung 11's float triangle test: %.2f triangles a ray in float; of them %.2f %% dropped as sure\n"
               "    misses, %.2f %% sure hits and %.3f %% too close to call, both tested again in double\n",
               tests / rows[ACCEL_EXACT].rays, 100.0 * (tests - sure - close) / tests, 100.0 * sure / tests,
               100.0 * close / tests);
    }
    const struct row *packets = &rows[ACCEL_PACKETS];
    for (int p = 0; p < 2 && packets->done && embree.done && !isinf(embree_packet_ms[p][0]); p++) {
        const double *ms = embree_packet_ms[p], faster = ms[0] < ms[1] ? ms[0] : ms[1];
        printf("  Embree 3 rtcIntersect%d (camera rays in packets of %d): frame %.1f ms with the shadow rays one by\n"
               "    one (rtcOccluded1), %.1f ms with them in packets of %d (rtcOccluded%d); rung 10 packet / the\n"
               "    faster: %.2f\n",
               embree_packets[p], embree_packets[p], ms[0], ms[1], embree_packets[p], embree_packets[p],
               packets->frame_ms / faster);
    }
    printf("\n");
    fflush(stdout);
    if (options->csv != NULL) {
        char name[256];
        model_name(path, name, sizeof name);
        csv_write_rows(options->csv, name, m.face_count, rows, ACCEL_COUNT, with_embree ? &embree : NULL);
    }
    free(reference);
    free(pixels);
    free(all_rows);
    free(sampled_rows);
    mesh_free(&m);
    return 0;
}

/* Reads "WxH" (each side 1 to BENCH_MAX_SIDE) into *width and *height; false when text is not that. */
static bool parse_size(const char *text, int *width, int *height) {
    char rest;
    return sscanf(text, "%dx%d%c", width, height, &rest) == 2 && *width >= 1 && *width <= BENCH_MAX_SIDE &&
           *height >= 1 && *height <= BENCH_MAX_SIDE;
}

/* Says `bench_accel: FILE: why` (why: strerror(error)) and returns 3, the exit status of a CSV that
 * cannot be written. */
static int csv_error(const char *path, int error) {
    fprintf(stderr, "bench_accel: %s: %s\n", path, strerror(error));
    return 3;
}

int main(int argc, char **argv) {
    struct options options = {false, 3, NULL, BENCH_WIDTH, BENCH_HEIGHT, NULL};
    const char *csv_path = NULL;
    int first = 1;
    omp_set_num_threads(1); /* every build and frame on one thread, as Embree's */
    for (; first < argc && argv[first][0] == '-'; first++) {
        if (strcmp(argv[first], "--embree") == 0)
            options.with_embree = true;
        else if (strcmp(argv[first], "--repeats") == 0 && first + 1 < argc && atoi(argv[first + 1]) > 0)
            options.repeats = atoi(argv[++first]);
        else if (strcmp(argv[first], "--only") == 0 && first + 1 < argc)
            options.only = argv[++first];
        else if (strcmp(argv[first], "--csv") == 0 && first + 1 < argc)
            csv_path = argv[++first];
        else if (strcmp(argv[first], "--size") == 0 && first + 1 < argc) {
            if (!parse_size(argv[++first], &options.width, &options.height)) {
                fprintf(stderr, "bench_accel: --size '%s': expected WIDTHxHEIGHT, each from 1 to %d, e.g. 800x600\n",
                        argv[first], BENCH_MAX_SIDE);
                return 2;
            }
        } else
            break;
    }
    if (first >= argc || argv[first][0] == '-') {
        fprintf(stderr, "usage: bench_accel [--embree] [--repeats N] [--only NAME] [--size WxH] [--csv FILE] "
                        "MODEL.ply...\n");
        return 2;
    }
#ifndef WHITTED_EMBREE
    if (options.with_embree) {
        fprintf(stderr, "bench_accel: built without Embree (install libembree-dev and rebuild: make bench)\n");
        return 2;
    }
#endif
    /* The CSV goes to FILE.tmp, opened before the first model so that a path that cannot be written
     * fails at once rather than after the whole run, and renamed to FILE at the end. */
    char *csv_tmp = NULL;
    if (csv_path != NULL) {
        size_t size = strlen(csv_path) + sizeof ".tmp";
        csv_tmp = malloc(size);
        if (csv_tmp == NULL) {
            fprintf(stderr, "bench_accel: out of memory\n");
            return 1;
        }
        snprintf(csv_tmp, size, "%s.tmp", csv_path);
        options.csv = fopen(csv_tmp, "w");
        if (options.csv == NULL) {
            int error = errno;
            free(csv_tmp);
            return csv_error(csv_path, error);
        }
        fprintf(options.csv, "%s\n", CSV_HEADER);
    }
    if (!fast_bvh_eight_available())
        fprintf(stderr, "bench_accel: no AVX2 here (or %s is set): rung 8's and 9's rows are rung 6's tree and walk\n",
                FAST_BVH_NO_AVX2_VARIABLE);
    int status = 0;
    for (int k = first; k < argc; k++)
        status |= bench_model(argv[k], &options);
    if (options.csv != NULL) {
        int error = 0; /* errno of the first step that failed */
        if (fflush(options.csv) != 0 || ferror(options.csv))
            error = errno != 0 ? errno : EIO;
        if (fclose(options.csv) != 0 && error == 0)
            error = errno;
        if (error == 0 && status == 0 && rename(csv_tmp, csv_path) != 0)
            error = errno;
        if (error != 0 || status != 0)
            remove(csv_tmp);
        free(csv_tmp);
        if (error != 0)
            return csv_error(csv_path, error);
        if (status != 0)
            fprintf(stderr, "bench_accel: %s: not written, since a model failed\n", csv_path);
    }
    return status;
}
