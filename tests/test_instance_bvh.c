/* test_instance_bvh.c: chapter 16's top-level tree over instance boxes: the built tree passes the
 * structure checker, a walk visits every instance whose box a ray enters (against brute force over
 * all boxes), near child first, shrinking and stopping as the callback says; a refit after the boxes
 * move passes the checker and its SAH cost drifts measurably from a rebuild's; and the checker fails a
 * refit that forgets a parent's box, and other broken trees, with a sentence. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "instance_bvh.h"
#include "stats.h"
#include "uniform.h"

/* ---- scenes of boxes ---------------------------------------------------------------------------- */

#define BOX_COUNT 3000

/* Fills boxes[0 .. count) with random boxes (sides 0.1 to 3) centred in [-20, 20]^3, from stream `stream`;
 * the last 40 are one box repeated (centroids no plane separates) and one is empty (an instance of
 * nothing). */
static void random_boxes(struct aabb *boxes, size_t count, uint32_t stream) {
    for (size_t k = 0; k < count; k++) {
        vec3 centre = uniform_vec3(stream, (uint32_t)k, -20, 20);
        vec3 half = uniform_vec3(stream + 1, (uint32_t)k, 0.05, 1.5);
        boxes[k] = (struct aabb){vec3_sub(centre, half), vec3_add(centre, half)};
    }
    for (size_t k = count - 40; k < count; k++)
        boxes[k] = (struct aabb){{1, 2, 3}, {1.5, 2.5, 3.5}};
    boxes[count / 2] = aabb_empty();
}

static struct instance_bvh *build(const struct aabb *boxes, size_t count) {
    char err[256] = "";
    struct instance_bvh *b = instance_bvh_build(boxes, count, err, sizeof err);
    cr_assert_not_null(b, "%s", err);
    char why[256] = "";
    cr_assert(instance_bvh_is_valid(b, boxes, count, why, sizeof why), "%s", why);
    return b;
}

/* A random ray: origin in [-30, 30]^3, aimed at a random point of [-20, 20]^3; one in eight with a zero
 * direction component (parallel to a slab) and one in eight with two. */
static ray random_ray(uint32_t k) {
    vec3 origin = uniform_vec3(20, k, -30, 30), target = uniform_vec3(21, k, -20, 20);
    vec3 d = vec3_sub(target, origin);
    if (k % 8 == 1)
        d.y = 0;
    if (k % 8 == 2)
        d.x = d.z = 0;
    return (ray){origin, vec3_normalize(d)};
}

/* ---- walking against brute force ---------------------------------------------------------------- */

/* What a walk saw: how often each instance was visited, the order, and an optional rule for *t_max. */
struct walk_log {
    const struct aabb *boxes;
    vec3 origin, inv;
    unsigned *visits;
    size_t total, first;
    bool shrink;    /* lower *t_max to the entry of each entered box (a nearest-hit search) */
    bool stop;      /* stop at the first visit */
};

static bool log_visit(void *context, size_t index, double t_min, double *t_max) {
    struct walk_log *log = context;
    if (log->total++ == 0)
        log->first = index;
    log->visits[index]++;
    double entry;
    if (log->shrink && aabb_hit(&log->boxes[index], log->origin, log->inv, t_min, fmin(*t_max, DBL_MAX), &entry))
        *t_max = entry;
    return !log->stop;
}

/* Walks r through b, logging into *log (visits zeroed first); returns the final t_max. */
static double walk(const struct instance_bvh *b, const struct aabb *boxes, size_t count, ray r, double t_min,
                   double t_max, struct walk_log *log) {
    memset(log->visits, 0, count * sizeof *log->visits);
    log->boxes = boxes;
    log->origin = r.origin;
    log->inv = aabb_inverse_direction(r.direction);
    log->total = 0;
    instance_bvh_walk(b, &r, t_min, &t_max, log_visit, log);
    return t_max;
}

/* Brute force: does r enter box k with t in [t_min, t_max] (the slab test's answer), and where. */
static bool brute_enters(const struct aabb *box, ray r, double t_min, double t_max, double *entry) {
    return aabb_hit(box, r.origin, aabb_inverse_direction(r.direction), fmax(t_min, -DBL_MAX), fmin(t_max, DBL_MAX),
                    entry);
}

#define RAYS 2000

/* Walks r through b up to t_max and expects every box of boxes[0 .. count) that r enters by then to be
 * visited once, and no box twice. Returns how many it entered; adds the walk's visits to *visited. */
static size_t expect_entered_boxes_visited(const struct instance_bvh *b, const struct aabb *boxes, size_t count,
                                           ray r, double t_max, unsigned *visits, size_t *visited) {
    struct walk_log log = {.visits = visits};
    walk(b, boxes, count, r, RAY_T_MIN, t_max, &log);
    size_t entered_count = 0;
    for (size_t i = 0; i < count; i++) {
        double entry;
        bool entered = brute_enters(&boxes[i], r, RAY_T_MIN, t_max, &entry);
        cr_assert(visits[i] <= 1, "instance %zu visited %u times", i, visits[i]);
        cr_assert(!entered || visits[i] == 1, "the ray from (%g %g %g) enters box %zu at t = %g, but the walk never "
                  "visited it", r.origin.x, r.origin.y, r.origin.z, i, entry);
        entered_count += entered;
    }
    *visited += log.total;
    return entered_count;
}

Test(instance_bvh, a_walk_visits_every_box_the_ray_enters_once) {
    static struct aabb boxes[BOX_COUNT];
    static unsigned visits[BOX_COUNT];
    random_boxes(boxes, BOX_COUNT, 1);
    struct instance_bvh *b = build(boxes, BOX_COUNT);
    size_t entered = 0, visited = 0;
    for (uint32_t k = 0; k < RAYS; k++) {
        double t_max = k % 2 ? INFINITY : uniform(22, k, 5, 40);
        entered += expect_entered_boxes_visited(b, boxes, BOX_COUNT, random_ray(k), t_max, visits, &visited);
    }
    cr_log_info("%zu boxes entered by %d rays; %zu visits (leaves hold a few)", entered, RAYS, visited);
    cr_expect_gt(entered, (size_t)(2 * RAYS), "the rays enter boxes, a few each (the test tests something)");
    cr_expect_lt(visited, 4 * entered + INSTANCE_BVH_LEAF_MAX * RAYS, "the walk visits little more");
    instance_bvh_free(b);
}

Test(instance_bvh, a_shrinking_walk_finds_the_nearest_box_and_visits_fewer_nodes) {
    static struct aabb boxes[BOX_COUNT];
    static unsigned visits[BOX_COUNT];
    random_boxes(boxes, BOX_COUNT, 3);
    struct instance_bvh *b = build(boxes, BOX_COUNT);
    uint64_t all_nodes = 0, nearest_nodes = 0;
    for (uint32_t k = 0; k < RAYS; k++) {
        ray r = random_ray(k);
        double nearest = INFINITY, entry;
        for (size_t i = 0; i < BOX_COUNT; i++)
            if (brute_enters(&boxes[i], r, RAY_T_MIN, INFINITY, &entry))
                nearest = fmin(nearest, entry);
        struct walk_log log = {.visits = visits};
        stats_reset_thread();
        walk(b, boxes, BOX_COUNT, r, RAY_T_MIN, INFINITY, &log);
        all_nodes += stats_thread.instance_node_visits;
        log.shrink = true;
        stats_reset_thread();
        double found = walk(b, boxes, BOX_COUNT, r, RAY_T_MIN, INFINITY, &log);
        nearest_nodes += stats_thread.instance_node_visits;
        cr_assert(found == nearest, "ray %u: the walk's nearest entry %.17g, brute force's %.17g", k, found, nearest);
    }
    cr_log_info("top-level nodes per ray: %.2f visiting all, %.2f for the nearest", (double)all_nodes / RAYS,
                (double)nearest_nodes / RAYS);
    cr_expect_gt(nearest_nodes, (uint64_t)RAYS, "node visits are counted");
    cr_expect_lt(2 * nearest_nodes, all_nodes, "near child first lets a nearest-hit walk skip most of the tree");
    instance_bvh_free(b);
}

Test(instance_bvh, the_near_child_comes_first_and_a_false_visit_stops_the_walk) {
    enum { ROW = 64 };
    struct aabb boxes[ROW];
    unsigned visits[ROW];
    for (int k = 0; k < ROW; k++) /* a row of unit boxes along x, numbered from left to right */
        boxes[k] = (struct aabb){{2.0 * k, 0, 0}, {2.0 * k + 1, 1, 1}};
    struct instance_bvh *b = build(boxes, ROW);
    struct walk_log log = {.visits = visits, .stop = true};
    walk(b, boxes, ROW, (ray){{-10, 0.5, 0.5}, {1, 0, 0}}, RAY_T_MIN, INFINITY, &log);
    cr_expect(log.total == 1 && log.first == 0, "from the left: %zu visits, first %zu", log.total, log.first);
    walk(b, boxes, ROW, (ray){{200, 0.5, 0.5}, {-1, 0, 0}}, RAY_T_MIN, INFINITY, &log);
    cr_expect(log.total == 1 && log.first == ROW - 1, "from the right: %zu visits, first %zu", log.total, log.first);
    log.stop = false;
    walk(b, boxes, ROW, (ray){{-10, 0.5, 0.5}, {1, 0, 0}}, RAY_T_MIN, 40.5, &log); /* reaches x = 30.5 */
    for (int k = 0; k < ROW; k++)
        cr_expect(visits[k] == (2 * k <= 30 ? 1u : 0u) || (visits[k] == 1 && 2 * k <= 30 + 2 * INSTANCE_BVH_LEAF_MAX),
                  "box %d at x = %d visited %u times with the ray ending at x = 30.5", k, 2 * k, visits[k]);
    instance_bvh_free(b);
}

Test(instance_bvh, no_instances_and_one_instance) {
    char err[64] = "", why[128] = "";
    struct instance_bvh *none = instance_bvh_build(NULL, 0, err, sizeof err);
    cr_assert_not_null(none, "%s", err);
    cr_expect(instance_bvh_is_valid(none, NULL, 0, why, sizeof why), "%s", why);
    cr_expect(instance_bvh_sah_cost(none) == 0);
    unsigned visits[1];
    struct walk_log log = {.visits = visits};
    walk(none, NULL, 0, (ray){{0, 0, 0}, {0, 0, 1}}, 0, INFINITY, &log);
    cr_expect(log.total == 0);
    instance_bvh_free(none);
    struct aabb one = {{-1, -1, -1}, {1, 1, 1}};
    struct instance_bvh *single = build(&one, 1);
    walk(single, &one, 1, (ray){{0, 0, -5}, {0, 0, 1}}, 0, INFINITY, &log);
    cr_expect(log.total == 1 && visits[0] == 1);
    cr_expect(instance_bvh_sah_cost(single) == INSTANCE_BVH_COST_INSTANCE);
    instance_bvh_free(single);
}

Test(instance_bvh, too_many_instances_are_refused_with_a_sentence) {
    char err[256] = "";
    cr_expect_null(instance_bvh_build(NULL, INSTANCE_BVH_MAX_INSTANCES + 1, err, sizeof err));
    cr_expect_str_eq(err, "2147483649 instances are too many for the top-level tree (at most 2147483648)");
}

/* ---- refitting ---------------------------------------------------------------------------------- */

/* Moves every box of `from` by a random step of up to `reach` on each axis into `to`. */
static void move_boxes(const struct aabb *from, struct aabb *to, size_t count, double reach, uint32_t stream) {
    for (size_t k = 0; k < count; k++) {
        vec3 step = uniform_vec3(stream, (uint32_t)k, -reach, reach);
        to[k] = (struct aabb){vec3_add(from[k].min, step), vec3_add(from[k].max, step)};
    }
}

Test(instance_bvh, a_refit_passes_the_checker_and_its_sah_cost_drifts_from_a_rebuilds) {
    static struct aabb boxes[BOX_COUNT], moved[BOX_COUNT];
    static unsigned visits[BOX_COUNT];
    random_boxes(boxes, BOX_COUNT, 5);
    struct instance_bvh *b = build(boxes, BOX_COUNT);
    double built = instance_bvh_sah_cost(b);
    instance_bvh_refit(b, boxes);
    cr_expect(instance_bvh_sah_cost(b) == built, "a refit to the same boxes changes nothing");
    static const double reaches[] = {1, 5, 20, 50};
    double previous_drift = 1.0;
    for (int step = 0; step < 4; step++) {
        move_boxes(boxes, moved, BOX_COUNT, reaches[step], 6 + step);
        instance_bvh_refit(b, moved);
        char why[256] = "";
        cr_assert(instance_bvh_is_valid(b, moved, BOX_COUNT, why, sizeof why), "after moving by %g: %s", reaches[step],
                  why);
        struct instance_bvh *rebuilt = build(moved, BOX_COUNT);
        double drift = instance_bvh_sah_cost(b) / instance_bvh_sah_cost(rebuilt);
        cr_log_info("boxes moved up to %g: refit SAH cost %.1f, rebuilt %.1f (x %.2f)", reaches[step],
                    instance_bvh_sah_cost(b), instance_bvh_sah_cost(rebuilt), drift);
        cr_expect_gt(drift, previous_drift, "the refitted tree grows worse as the boxes wander farther");
        previous_drift = drift;
        instance_bvh_free(rebuilt);
        /* and the refitted tree still finds every box */
        size_t visited = 0;
        for (uint32_t k = 0; k < RAYS / 10; k++)
            expect_entered_boxes_visited(b, moved, BOX_COUNT, random_ray(k), INFINITY, visits, &visited);
    }
    cr_expect_gt(previous_drift, 2.0, "boxes scattered across the scene make the refit far worse than a rebuild");
    instance_bvh_free(b);
}

/* The gallery's fault: a refit that recomputes the leaves' boxes and forgets their parents'. */
static void refit_leaves_only(struct instance_bvh *b, const struct aabb *boxes) {
    for (size_t k = 0; k < b->node_count; k++) {
        struct instance_bvh_node *node = &b->nodes[k];
        if (node->count == 0)
            continue;
        node->box = aabb_empty();
        for (uint32_t i = node->first; i < node->first + node->count; i++)
            node->box = aabb_union(node->box, boxes[b->instances[i]]);
    }
}

Test(instance_bvh, the_checker_fails_a_refit_that_forgets_a_parents_box) {
    static struct aabb boxes[BOX_COUNT], moved[BOX_COUNT];
    random_boxes(boxes, BOX_COUNT, 7);
    struct instance_bvh *b = build(boxes, BOX_COUNT);
    move_boxes(boxes, moved, BOX_COUNT, 5, 8);
    refit_leaves_only(b, moved);
    char why[256] = "";
    cr_expect(!instance_bvh_is_valid(b, moved, BOX_COUNT, why, sizeof why));
    cr_log_info("the checker: %s", why);
    unsigned node, child;
    cr_expect(sscanf(why, "node %u's box does not hold its child %u's box", &node, &child) == 2, "%s", why);
    instance_bvh_free(b);
}

Test(instance_bvh, the_checker_names_other_faults) {
    struct aabb boxes[8];
    for (int k = 0; k < 8; k++)
        boxes[k] = (struct aabb){{10.0 * k, 0, 0}, {10.0 * k + 1, 1, 1}};
    struct instance_bvh *b = build(boxes, 8);
    char why[256] = "";
    /* an instance in two leaves */
    uint32_t saved = b->instances[1];
    b->instances[1] = b->instances[0];
    cr_expect(!instance_bvh_is_valid(b, boxes, 8, why, sizeof why));
    cr_expect(strstr(why, "is in two leaves") != NULL, "%s", why);
    b->instances[1] = saved;
    /* a box that moved without a refit */
    boxes[5].max.y = 7;
    cr_expect(!instance_bvh_is_valid(b, boxes, 8, why, sizeof why));
    cr_expect(strstr(why, "'s box does not hold instance 5's box") != NULL, "%s", why);
    instance_bvh_refit(b, boxes);
    cr_expect(instance_bvh_is_valid(b, boxes, 8, why, sizeof why), "%s", why);
    /* a tree over a different number of instances */
    cr_expect(!instance_bvh_is_valid(b, boxes, 7, why, sizeof why));
    cr_expect_str_eq(why, "the tree holds 8 instances, not 7");
    /* a child that points back up */
    b->nodes[0].right = 0;
    cr_expect(!instance_bvh_is_valid(b, boxes, 8, why, sizeof why));
    cr_expect_str_eq(why, "node 0's child 0 is not after it");
    instance_bvh_free(b);
}

Test(instance_bvh, the_stats_report_prints_top_level_node_visits) {
    struct stats s = {.primary_rays = 10, .node_visits = 30, .instance_node_visits = 25};
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    cr_assert_not_null(out);
    stats_print(out, &s);
    fclose(out);
    cr_expect(strstr(text, "  instance nodes                25\n") != NULL, "%s", text);
    cr_expect(strstr(text, "  instance nodes              2.50\n") != NULL, "%s", text);
    struct stats sum = {0};
    stats_add(&sum, &s);
    stats_add(&sum, &s);
    cr_expect(sum.instance_node_visits == 50);
    free(text);
}
