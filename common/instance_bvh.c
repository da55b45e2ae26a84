/* instance_bvh.c: the top level of chapter 16's two-level hierarchy: a BVH over instances' boxes, its
 * binned SAH build, refit, walk, SAH cost and structure checker (chapter 16).
 *
 * The build is chapter 10's binned SAH (Wald 2007) over box centroids, written again for boxes rather
 * than triangles, and small enough to read in one sitting: bin the centroids along each axis, price
 * every plane between bins by area times count on each side, split at the cheapest, or make a leaf
 * when that is cheaper. */
#include "instance_bvh.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "stats.h"

/* The walk's stack holds at most one node per level (INSTANCE_BVH_DEEPEST + 1) plus one. */
#define INSTANCE_BVH_STACK_SIZE (INSTANCE_BVH_DEEPEST + 2)

/* ==== building ================================================================================ */

/* An instance while building: its box, the box's centre, and its index. */
struct prim {
    struct aabb box;
    vec3 centroid;
    uint32_t index;
};

/* Returns the box around prims [begin, end) and stores the box around their centroids in *centroids. */
static struct aabb range_box(const struct prim *p, uint32_t begin, uint32_t end, struct aabb *centroids) {
    struct aabb box = aabb_empty();
    *centroids = aabb_empty();
    for (uint32_t k = begin; k < end; k++) {
        box = aabb_union(box, p[k].box);
        *centroids = aabb_grow(*centroids, p[k].centroid);
    }
    return box;
}

/* The slot of centroid coordinate c on an axis whose centroids span [lo, lo + extent], clamped to the
 * slots at both ends (a NaN centroid, from an empty box, lands in slot 0). */
static int bin_of(double c, double lo, double extent) {
    double x = (c - lo) / extent * INSTANCE_BVH_BINS;
    if (!(x >= 0.0))
        return 0;
    if (x >= INSTANCE_BVH_BINS - 1)
        return INSTANCE_BVH_BINS - 1;
    return (int)x;
}

/* Looks for the cheapest binned SAH split of prims [begin, end), whose box is `box`. Returns false,
 * leaving them alone, when a leaf is cheaper (and allowed) or no plane separates the centroids;
 * otherwise partitions them and returns where the right side begins in *mid. */
/* TASK 10.2 ALSO: the binned SAH split, chapter 10's over instances' boxes */
static bool split_sah(struct prim *p, uint32_t begin, uint32_t end, struct aabb box, struct aabb centroids,
                      uint32_t *mid) {
    double best_cost = INFINITY; /* area(left) count(left) + area(right) count(right) of the best plane */
    int best_axis = -1, best_plane = 0;
    for (int axis = 0; axis < 3; axis++) {
        double lo = vec3_axis(centroids.min, axis), extent = vec3_axis(centroids.max, axis) - lo;
        if (!(extent > 0.0))
            continue; /* every centroid in one plane: this axis cannot separate them */
        struct aabb bin_box[INSTANCE_BVH_BINS];
        uint32_t bin_count[INSTANCE_BVH_BINS] = {0};
        for (int k = 0; k < INSTANCE_BVH_BINS; k++)
            bin_box[k] = aabb_empty();
        for (uint32_t i = begin; i < end; i++) {
            int k = bin_of(vec3_axis(p[i].centroid, axis), lo, extent);
            bin_box[k] = aabb_union(bin_box[k], p[i].box);
            bin_count[k]++;
        }
        /* From the right: the area and count of everything at or right of slot k. */
        double right_area[INSTANCE_BVH_BINS];
        uint32_t right_count[INSTANCE_BVH_BINS];
        struct aabb side = aabb_empty();
        uint32_t count = 0;
        for (int k = INSTANCE_BVH_BINS - 1; k > 0; k--) {
            side = aabb_union(side, bin_box[k]);
            count += bin_count[k];
            right_area[k] = aabb_surface_area(side);
            right_count[k] = count;
        }
        /* From the left, pricing the plane before each slot k. */
        side = aabb_empty();
        count = 0;
        for (int k = 1; k < INSTANCE_BVH_BINS; k++) {
            side = aabb_union(side, bin_box[k - 1]);
            count += bin_count[k - 1];
            if (count == 0 || right_count[k] == 0)
                continue; /* everything on one side: not a split */
            double cost = aabb_surface_area(side) * count + right_area[k] * right_count[k];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_plane = k;
            }
        }
    }
    if (best_axis < 0)
        return false;
    uint32_t n = end - begin;
    double area = aabb_surface_area(box);
    double split_cost = INSTANCE_BVH_COST_TRAVERSAL + INSTANCE_BVH_COST_INSTANCE * (area > 0.0 ? best_cost / area : n);
    if (n <= INSTANCE_BVH_LEAF_MAX && INSTANCE_BVH_COST_INSTANCE * n <= split_cost)
        return false;
    double lo = vec3_axis(centroids.min, best_axis), extent = vec3_axis(centroids.max, best_axis) - lo;
    uint32_t i = begin, j = end; /* [begin, i) go left, [j, end) go right */
    while (i < j) {
        if (bin_of(vec3_axis(p[i].centroid, best_axis), lo, extent) < best_plane) {
            i++;
        } else {
            struct prim swap = p[i];
            p[i] = p[--j];
            p[j] = swap;
        }
    }
    *mid = i;
    return true;
}

/* Builds the subtree over prims [begin, end) at `depth` into b's nodes and returns its index. */
static uint32_t build_node(struct instance_bvh *b, struct prim *p, uint32_t begin, uint32_t end, size_t depth) {
    uint32_t index = (uint32_t)b->node_count++;
    struct aabb centroids;
    struct aabb box = range_box(p, begin, end, &centroids);
    uint32_t n = end - begin, mid = begin;
    bool split = n > 1 && depth < INSTANCE_BVH_MAX_DEPTH && split_sah(p, begin, end, box, centroids, &mid);
    if (!split && n > INSTANCE_BVH_LEAF_MAX) { /* too deep for the SAH, or the centroids coincide: halve */
        mid = begin + n / 2;
        split = true;
    }
    if (!split) {
        b->nodes[index] = (struct instance_bvh_node){box, 0, 0, begin, n};
        return index;
    }
    uint32_t left = build_node(b, p, begin, mid, depth + 1);
    uint32_t right = build_node(b, p, mid, end, depth + 1);
    b->nodes[index] = (struct instance_bvh_node){box, left, right, 0, 0};
    return index;
}

struct instance_bvh *instance_bvh_build(const struct aabb *boxes, size_t count, char *err, size_t err_size) {
    if (count > INSTANCE_BVH_MAX_INSTANCES) {
        snprintf(err, err_size, "%zu instances are too many for the top-level tree (at most %zu)", count,
                 INSTANCE_BVH_MAX_INSTANCES);
        return NULL;
    }
    struct instance_bvh *b = calloc(1, sizeof *b);
    struct prim *prims = malloc((count + 1) * sizeof *prims);
    if (b != NULL) {
        b->nodes = malloc((2 * count + 1) * sizeof *b->nodes);
        b->instances = malloc((count + 1) * sizeof *b->instances);
    }
    if (b == NULL || prims == NULL || b->nodes == NULL || b->instances == NULL) {
        snprintf(err, err_size, "out of memory building the top-level tree over %zu instances", count);
        free(prims);
        instance_bvh_free(b);
        return NULL;
    }
    for (size_t k = 0; k < count; k++)
        prims[k] = (struct prim){boxes[k], vec3_scale(vec3_add(boxes[k].min, boxes[k].max), 0.5), (uint32_t)k};
    b->instance_count = count;
    if (count > 0)
        build_node(b, prims, 0, (uint32_t)count, 0);
    for (size_t k = 0; k < count; k++)
        b->instances[k] = prims[k].index;
    free(prims);
    return b;
}

void instance_bvh_free(struct instance_bvh *b) {
    if (b == NULL)
        return;
    free(b->nodes);
    free(b->instances);
    free(b);
}

/* ==== refitting =============================================================================== */

/* TASK 16.2: refitting the top level: the same tree, its boxes from the leaves up */
void instance_bvh_refit(struct instance_bvh *b, const struct aabb *boxes) {
    /* Children come after their parents in nodes[], so going backwards meets every child before its
     * parent: one pass from the last node to the root recomputes every box from below. */
    for (size_t k = b->node_count; k-- > 0;) {
        struct instance_bvh_node *node = &b->nodes[k];
        struct aabb box = aabb_empty();
        if (node->count > 0) {
            for (uint32_t i = node->first; i < node->first + node->count; i++)
                box = aabb_union(box, boxes[b->instances[i]]);
        } else {
            box = aabb_union(b->nodes[node->left].box, b->nodes[node->right].box);
        }
        node->box = box;
    }
}

/* ==== walking ================================================================================= */

/* TASK 10.3 ALSO: the near-first walk, chapter 10's over instances' boxes */
void instance_bvh_walk(const struct instance_bvh *b, const ray *r, double t_min, double *t_max,
                       instance_bvh_visit visit, void *context) {
    if (b->node_count == 0)
        return;
    /* The box tests' window ends at the largest finite double, not infinity, so that a ray parallel to
     * a slab and outside it (entered and left both at +infinity) misses, as in chapter 10. */
    double box_min = fmax(t_min, -DBL_MAX);
    vec3 inv = aabb_inverse_direction(r->direction);
    struct {
        uint32_t node;
        double entry;
    } stack[INSTANCE_BVH_STACK_SIZE];
    int top = 0;
    double entry;
    if (aabb_hit(&b->nodes[0].box, r->origin, inv, box_min, fmin(*t_max, DBL_MAX), &entry)) {
        stack[top].node = 0;
        stack[top++].entry = entry;
    }
    while (top > 0) {
        top--;
        const struct instance_bvh_node *node = &b->nodes[stack[top].node];
        if (stack[top].entry > *t_max)
            continue; /* entered only beyond what visit has found: nothing in it is nearer */
        stats_thread.instance_node_visits++;
        if (node->count > 0) {
            for (uint32_t i = node->first; i < node->first + node->count; i++)
                if (!visit(context, b->instances[i], t_min, t_max))
                    return;
            continue;
        }
        double box_max = fmin(*t_max, DBL_MAX);
        double enter_left = INFINITY, enter_right = INFINITY; /* stay so for a box the ray misses */
        bool left = aabb_hit(&b->nodes[node->left].box, r->origin, inv, box_min, box_max, &enter_left);
        bool right = aabb_hit(&b->nodes[node->right].box, r->origin, inv, box_min, box_max, &enter_right);
        uint32_t near = node->left, far = node->right;
        double near_entry = enter_left, far_entry = enter_right;
        bool near_hit = left, far_hit = right;
        if (enter_right < enter_left) { /* the right child comes first */
            near = node->right;
            far = node->left;
            near_entry = enter_right;
            far_entry = enter_left;
            near_hit = right;
            far_hit = left;
        }
        if (far_hit) { /* pushed first, so taken after the near one */
            stack[top].node = far;
            stack[top++].entry = far_entry;
        }
        if (near_hit) {
            stack[top].node = near;
            stack[top++].entry = near_entry;
        }
    }
}

/* ==== measuring and checking ================================================================== */

double instance_bvh_sah_cost(const struct instance_bvh *b) {
    if (b->node_count == 0)
        return 0.0;
    double root_area = aabb_surface_area(b->nodes[0].box), cost = 0.0;
    for (size_t k = 0; k < b->node_count; k++) {
        const struct instance_bvh_node *node = &b->nodes[k];
        double ratio = root_area > 0.0 ? aabb_surface_area(node->box) / root_area : 1.0;
        cost += ratio * (node->count > 0 ? INSTANCE_BVH_COST_INSTANCE * node->count : INSTANCE_BVH_COST_TRAVERSAL);
    }
    return cost;
}

double instance_bvh_expected_instances(const struct instance_bvh *b, uint32_t *crowded) {
    if (b->node_count == 0)
        return 0.0;
    double root_area = aabb_surface_area(b->nodes[0].box), sum = 0.0, most = -1.0;
    for (size_t k = 0; k < b->node_count; k++) {
        const struct instance_bvh_node *node = &b->nodes[k];
        if (node->count == 0)
            continue;
        double share = (root_area > 0.0 ? aabb_surface_area(node->box) / root_area : 1.0) * node->count;
        sum += share;
        if (share > most && crowded != NULL) {
            most = share;
            *crowded = b->instances[node->first];
        }
    }
    return sum;
}

/* Checks node `index`'s children or instances, marking what it reaches in reached[] (nodes) and
 * placed[] (instances). Returns false with the fault in why. */
static bool node_is_valid(const struct instance_bvh *b, const struct aabb *boxes, size_t index, unsigned char *reached,
                          unsigned char *placed, char *why, size_t why_size) {
    const struct instance_bvh_node *node = &b->nodes[index];
    if (node->count > 0) {
        if (node->count > INSTANCE_BVH_LEAF_MAX || node->first > b->instance_count ||
            node->count > b->instance_count - node->first) {
            snprintf(why, why_size, "leaf %zu holds instances %u to %u of %zu (at most %d a leaf)", index, node->first,
                     node->first + node->count - 1, b->instance_count, INSTANCE_BVH_LEAF_MAX);
            return false;
        }
        for (uint32_t i = node->first; i < node->first + node->count; i++) {
            uint32_t instance = b->instances[i];
            if (instance >= b->instance_count || placed[instance]) {
                snprintf(why, why_size, "leaf %zu: instance %u is %s", index, instance,
                         instance >= b->instance_count ? "not an instance" : "in two leaves");
                return false;
            }
            placed[instance] = 1;
            if (!aabb_holds(&node->box, &boxes[instance])) {
                snprintf(why, why_size, "leaf %zu's box does not hold instance %u's box", index, instance);
                return false;
            }
        }
        return true;
    }
    uint32_t children[2] = {node->left, node->right};
    for (int c = 0; c < 2; c++) {
        size_t child = children[c];
        if (child <= index || child >= b->node_count || reached[child]) {
            snprintf(why, why_size, "node %zu's child %zu is %s", index, child,
                     child <= index ? "not after it" : child >= b->node_count ? "not a node" : "reached twice");
            return false;
        }
        reached[child] = 1;
        if (!aabb_holds(&node->box, &b->nodes[child].box)) {
            snprintf(why, why_size, "node %zu's box does not hold its child %zu's box", index, child);
            return false;
        }
    }
    return true;
}

bool instance_bvh_is_valid(const struct instance_bvh *b, const struct aabb *boxes, size_t count, char *why,
                           size_t why_size) {
    if (b->instance_count != count) {
        snprintf(why, why_size, "the tree holds %zu instances, not %zu", b->instance_count, count);
        return false;
    }
    if (count == 0 ? b->node_count != 0 : b->node_count == 0 || b->node_count > 2 * count - 1) {
        snprintf(why, why_size, "%zu nodes for %zu instances", b->node_count, count);
        return false;
    }
    unsigned char *reached = calloc(b->node_count + 1, 1), *placed = calloc(count + 1, 1);
    bool valid = reached != NULL && placed != NULL;
    if (!valid)
        snprintf(why, why_size, "out of memory checking the top-level tree");
    /* Children come after their parents, so in index order every node is reached before it is checked. */
    if (valid && count > 0)
        reached[0] = 1;
    for (size_t k = 0; valid && k < b->node_count; k++) {
        if (!reached[k]) {
            snprintf(why, why_size, "node %zu is not reached from the root", k);
            valid = false;
        } else {
            valid = node_is_valid(b, boxes, k, reached, placed, why, why_size);
        }
    }
    for (size_t i = 0; valid && i < count; i++) {
        if (!placed[i]) {
            snprintf(why, why_size, "instance %zu is in no leaf", i);
            valid = false;
        }
    }
    free(reached);
    free(placed);
    return valid;
}
