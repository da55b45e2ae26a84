/* bvh.c: bounding volume hierarchy: median and binned-SAH builds, ordered traversal (chapter 10).
 *
 * The build sorts the triangles into a binary tree of chapter 5's boxes. Each node has the box around
 * its triangles; an interior node has two children, a leaf a run of triangles. BVH_SPLIT_MEDIAN is the
 * dissertation's rule (halve the triangles by centroid along the longest axis). BVH_SPLIT_SAH is the
 * binned surface area heuristic of Wald, "On fast construction of SAH-based bounding volume
 * hierarchies" (IEEE RT 2007): the centroids are dropped into BVH_BINS slots per axis, and of the
 * planes between slots the one minimising
 *     BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * (area(L) * count(L) + area(R) * count(R)) / area(node)
 * is taken, unless a leaf (BVH_COST_TRIANGLE * count) is cheaper. The ratio of a child's area to its
 * parent's is the chance that a random ray through the parent also crosses the child (MacDonald and
 * Booth 1990), so the sum is the expected cost of a ray that reaches the node.
 *
 * The traversal keeps a stack of nodes still to visit, each with the distance at which the ray enters
 * its box. At an interior node it tests both children's boxes with chapter 5's slab test (aabb_hit)
 * and visits the nearer first; a node that starts beyond the best hit so far is skipped. A shadow ray
 * stops at its first hit.
 *
 * Exact agreement with the brute-force loop. A query must return the very face and t that testing
 * every face with triangle_intersect would. Four things make sure of it (triangle.h states each rule):
 *  - Triangles are tested with triangle_crossing_prepared (triangle.h), the very arithmetic
 *    triangle_intersect uses (the ray made ready once per query), on the very corners the mesh holds,
 *    so t is the same double to the last bit.
 *  - A box may only be skipped when no triangle inside can be reported hit. The triangle test rounds:
 *    it may call a ray that passes a hair outside a triangle a hit. So every triangle's box is grown by
 *    triangle_box_pad, far more than any such rounding error and far too little to cost anything.
 *  - Needle-thin triangles (triangle_is_sliver), whose rounding errors no pad covers, are kept out of
 *    the tree and tested by every ray.
 *  - Ties: a box is skipped only when it starts strictly after the best hit so far, and a triangle at
 *    the same t as the best replaces it only with a lower face index (triangle_hit_wins).
 * What is left: a ray starting more than about a thousand mesh sizes away, or one meeting a triangle's
 * plane at a grazing angle below about 1e-8 radians, has rounding errors the pad may not cover. Neither
 * occurs in tests/test_accel.c's hundreds of thousands of chosen rays nor, as far as we know, in a scene.
 *
 * Everything here is plain double-precision C, written to be read. Chapter 11 (fast_bvh.c) makes the
 * same tree fast: four children per node, float boxes, vector instructions, prefetching. */
#include "bvh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "clock.h"
#include "stats.h"
#include "triangle.h"

/* The traversal stack holds at most one node per level of the tree (BVH_DEEPEST + 1 of them) plus one. */
#define BVH_STACK_SIZE (BVH_DEEPEST + 2)

/* ==== building ================================================================================ */

/* A triangle while building: its padded box, the centre of that box, and its face number. */
struct bvh_prim {
    struct aabb box;
    vec3 centroid;
    uint32_t face;
};

struct builder {
    struct bvh_prim *prims; /* the splits reorder them into leaf order */
    struct bvh *b;
    enum bvh_split split;
    double root_area;
    size_t leaves, max_depth;
    double sah_cost;
};

/* The box around prims [begin, end), and the box around their centroids. */
static void range_boxes(const struct bvh_prim *p, uint32_t begin, uint32_t end, struct aabb *box,
                        struct aabb *centroids) {
    *box = aabb_empty();
    *centroids = aabb_empty();
    for (uint32_t k = begin; k < end; k++) {
        *box = aabb_union(*box, p[k].box);
        *centroids = aabb_grow(*centroids, p[k].centroid);
    }
}

static void swap_prims(struct bvh_prim *p, uint32_t i, uint32_t j) {
    struct bvh_prim t = p[i];
    p[i] = p[j];
    p[j] = t;
}

/* Reorders prims [begin, end) so that prim nth has the centroid it would have if they were sorted
 * along axis, with none larger before it and none smaller after (quickselect, Hoare's FIND, with a
 * three-way partition so that many equal centroids cost nothing extra). */
static void select_nth(struct bvh_prim *p, uint32_t begin, uint32_t end, uint32_t nth, int axis) {
    while (end - begin > 1) {
        double pivot = vec3_axis(p[begin + (end - begin) / 2].centroid, axis);
        uint32_t less = begin, i = begin, greater = end; /* [begin,less) < pivot, [greater,end) > pivot */
        while (i < greater) {
            double key = vec3_axis(p[i].centroid, axis);
            if (key < pivot)
                swap_prims(p, less++, i++);
            else if (key > pivot)
                swap_prims(p, i, --greater);
            else
                i++;
        }
        if (nth < less)
            end = less;
        else if (nth >= greater)
            begin = greater;
        else
            return;
    }
}

/* The dissertation's split: half the prims on each side, by centroid, along the longest axis of the
 * centroids' box. Returns where the right half begins. */
/* TASK 10.1: BVH build: the median split */
static uint32_t split_median(struct builder *bd, uint32_t begin, uint32_t end, const struct aabb *centroids) {
    vec3 extent = vec3_sub(centroids->max, centroids->min);
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (vec3_axis(extent, a) > vec3_axis(extent, axis))
            axis = a;
    uint32_t mid = begin + (end - begin) / 2;
    select_nth(bd->prims, begin, end, mid, axis);
    return mid;
}

/* The slot of a centroid c on an axis whose centroids span [lo, lo + extent]: floor((c - lo) / extent
 * * BVH_BINS), clamped to the slots at both ends, so that rounding at the top, and a NaN or infinite
 * centroid (a mesh beyond double's range), still land in a slot (a NaN in slot 0). */
static int bin_of(double c, double lo, double extent) {
    double x = (c - lo) / extent * BVH_BINS;
    if (!(x >= 0.0))
        return 0;
    if (x >= BVH_BINS - 1)
        return BVH_BINS - 1;
    return (int)x;
}

/* Looks for the cheapest binned SAH split of prims [begin, end), whose box is *box. Returns false,
 * leaving the prims alone, when a leaf is cheaper or no plane separates the centroids; otherwise
 * partitions them and stores where the right side begins in *mid. */
/* TASK 10.2: BVH build: the binned SAH */
static bool split_sah(struct builder *bd, uint32_t begin, uint32_t end, const struct aabb *box,
                      const struct aabb *centroids, uint32_t *mid) {
    struct bvh_prim *p = bd->prims;
    uint32_t n = end - begin;
    double best_cost = INFINITY; /* area(L) * count(L) + area(R) * count(R) of the best plane */
    int best_axis = -1, best_plane = 0;
    for (int a = 0; a < 3; a++) {
        double lo = vec3_axis(centroids->min, a), extent = vec3_axis(centroids->max, a) - lo;
        if (!(extent > 0.0))
            continue; /* all centroids in one plane: this axis cannot separate them */
        struct {
            struct aabb box;
            uint32_t count;
        } bins[BVH_BINS];
        for (int k = 0; k < BVH_BINS; k++) {
            bins[k].box = aabb_empty();
            bins[k].count = 0;
        }
        for (uint32_t i = begin; i < end; i++) {
            int k = bin_of(vec3_axis(p[i].centroid, a), lo, extent);
            bins[k].box = aabb_union(bins[k].box, p[i].box);
            bins[k].count++;
        }
        /* Sweep from the right: the area and count of everything right of the plane before slot k. */
        double right_area[BVH_BINS];
        uint32_t right_count[BVH_BINS];
        struct aabb side = aabb_empty();
        uint32_t count = 0;
        for (int k = BVH_BINS - 1; k > 0; k--) {
            side = aabb_union(side, bins[k].box);
            count += bins[k].count;
            right_area[k] = aabb_surface_area(side);
            right_count[k] = count;
        }
        /* Sweep from the left, pricing each plane on the way. */
        side = aabb_empty();
        count = 0;
        for (int k = 1; k < BVH_BINS; k++) {
            side = aabb_union(side, bins[k - 1].box);
            count += bins[k - 1].count;
            if (count == 0 || right_count[k] == 0)
                continue; /* everything on one side: not a split */
            double cost = aabb_surface_area(side) * count + right_area[k] * right_count[k];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = a;
                best_plane = k;
            }
        }
    }
    if (best_axis < 0)
        return false;
    double split_cost = BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * best_cost / aabb_surface_area(*box);
    if (n <= BVH_MAX_LEAF_SIZE && BVH_COST_TRIANGLE * n <= split_cost)
        return false;
    uint32_t i = begin, j = end; /* [begin, i) go left, [j, end) go right */
    double lo = vec3_axis(centroids->min, best_axis), extent = vec3_axis(centroids->max, best_axis) - lo;
    while (i < j) {
        if (bin_of(vec3_axis(p[i].centroid, best_axis), lo, extent) < best_plane)
            i++;
        else
            swap_prims(p, i, --j);
    }
    *mid = i;
    return true;
}

/* Builds the subtree over prims [begin, end) at the given depth and returns its node's index. */
static uint32_t build_node(struct builder *bd, uint32_t begin, uint32_t end, size_t depth) {
    uint32_t index = (uint32_t)bd->b->node_count++;
    struct bvh_node *node = &bd->b->nodes[index];
    struct aabb centroids;
    range_boxes(bd->prims, begin, end, &node->box, &centroids);
    double area_ratio = bd->root_area > 0.0 ? aabb_surface_area(node->box) / bd->root_area : 1.0;
    uint32_t n = end - begin, mid = begin;
    bool split = false;
    if (bd->split == BVH_SPLIT_MEDIAN) {
        split = n > BVH_MEDIAN_LEAF_SIZE;
        if (split)
            mid = split_median(bd, begin, end, &centroids);
    } else if (n > 1) {
        split = depth < BVH_MAX_DEPTH && split_sah(bd, begin, end, &node->box, &centroids, &mid);
        if (!split && n > BVH_MAX_LEAF_SIZE) { /* too deep for the SAH, or no plane separates: halve */
            mid = split_median(bd, begin, end, &centroids);
            split = true;
        }
    }
    if (split && (mid <= begin || mid >= end))
        split = false; /* a side left empty is no split; never from these rules, but a leaf keeps a wrong one safe */
    if (!split) {
        node->first = begin;
        node->count = n;
        bd->leaves++;
        bd->max_depth = depth > bd->max_depth ? depth : bd->max_depth;
        bd->sah_cost += BVH_COST_TRIANGLE * n * area_ratio;
        return index;
    }
    bd->sah_cost += BVH_COST_TRAVERSAL * area_ratio;
    node->count = 0;
    uint32_t left = build_node(bd, begin, mid, depth + 1);
    uint32_t right = build_node(bd, mid, end, depth + 1);
    bd->b->nodes[index].left = left; /* `node` is still valid (the array never moves), but plainer so */
    bd->b->nodes[index].right = right;
    return index;
}

bool bvh_face_box(const struct mesh *m, size_t face, double pad, struct aabb *box) {
    const uint32_t *v = m->faces[face].v;
    vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
    if (triangle_is_sliver(a, b, c))
        return false;
    *box = aabb_pad(aabb_grow(aabb_grow(aabb_grow(aabb_empty(), a), b), c), pad);
    return true;
}

void bvh_copy_triangles(const struct mesh *m, const uint32_t *faces, size_t count, struct bvh_triangle *triangles) {
    for (size_t k = 0; k < count; k++) {
        const uint32_t *v = m->faces[faces[k]].v;
        triangles[k] = (struct bvh_triangle){m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]]};
    }
}

struct bvh *bvh_build(const struct mesh *m, enum bvh_split split) {
    double start = clock_seconds();
    size_t n = m->face_count;
    struct bvh *b = n <= BVH_MAX_FACES ? calloc(1, sizeof *b) : NULL;
    if (b == NULL)
        return NULL;
    b->triangle_count = n;
    b->nodes = malloc((2 * n + 1) * sizeof *b->nodes);
    b->faces = malloc((n + 1) * sizeof *b->faces);
    struct bvh_prim *prims = malloc((n + 1) * sizeof *prims);
    if (b->nodes == NULL || b->faces == NULL || prims == NULL) {
        free(prims);
        bvh_free(b);
        return NULL;
    }
    /* One prim per face, its box padded; slivers to the end of faces[]. */
    double pad = triangle_box_pad(m);
    size_t tree = 0, slivers = 0;
    for (size_t f = 0; f < n; f++) {
        struct bvh_prim *p = &prims[tree];
        if (!bvh_face_box(m, f, pad, &p->box)) {
            b->faces[n - ++slivers] = (uint32_t)f;
            continue;
        }
        p->centroid = vec3_scale(vec3_add(p->box.min, p->box.max), 0.5);
        p->face = (uint32_t)f;
        tree++;
    }
    b->tree_count = tree;
    struct builder bd = {prims, b, split, 0.0, 0, 0, 0.0};
    if (tree > 0) {
        struct aabb root, centroids;
        range_boxes(prims, 0, (uint32_t)tree, &root, &centroids);
        bd.root_area = aabb_surface_area(root);
        build_node(&bd, 0, (uint32_t)tree, 0);
    }
    /* The triangles in leaf order, as the intersection test wants them; the slivers after them.
     * Allocated once the prims are freed, so that the two are never held at once. */
    for (size_t k = 0; k < tree; k++)
        b->faces[k] = prims[k].face;
    free(prims);
    b->triangles = malloc((n + 1) * sizeof *b->triangles);
    if (b->triangles == NULL) {
        bvh_free(b);
        return NULL;
    }
    bvh_copy_triangles(m, b->faces, n, b->triangles);
    b->info = (struct bvh_info){b->node_count, bd.leaves, bd.max_depth, 0.0,
                                bd.sah_cost + BVH_COST_TRIANGLE * slivers, slivers};
    b->info.build_ms = 1e3 * (clock_seconds() - start);
    return b;
}

void bvh_free(struct bvh *b) {
    if (b == NULL)
        return;
    free(b->nodes);
    free(b->triangles);
    free(b->faces);
    free(b);
}

void bvh_get_info(const struct bvh *b, struct bvh_info *info) { *info = b->info; }

/* ==== traversal =============================================================================== */

/* The three questions one traversal answers. */
enum query {
    QUERY_CLOSEST, /* nearest hit: near child first, boxes beyond the best hit skipped */
    QUERY_ANY,     /* any hit: stop at the first */
    QUERY_ALL,     /* every hit: visit everything the ray crosses */
};

struct query_state {
    enum query kind;
    double t;      /* QUERY_CLOSEST: best t so far (t_max until something is found) */
    uint32_t face; /* QUERY_CLOSEST: its face */
    bool found;
    bool (*visit)(void *ctx, double t, uint32_t face); /* QUERY_ALL */
    void *ctx;
};

/* Tests triangles [first, first + count) for the query against the ray r made ready by
 * triangle_ray_make, with triangle_crossing_prepared (triangle.h), the arithmetic of
 * triangle_intersect, so t is bit-identical to the brute-force loop's. A nearer hit lowers *box_max,
 * the far end of the window boxes are tested in. Returns false when the walk should stop (QUERY_ANY
 * found a hit, or QUERY_ALL's visit said so). */
static bool test_triangles(const struct bvh *b, const struct triangle_ray *r, uint32_t first, uint32_t count,
                           double t_min, double t_max, struct query_state *q, double *box_max) {
    for (uint32_t k = first; k < first + count; k++) {
        const struct bvh_triangle *tri = &b->triangles[k];
        double t, u, v;
        stats_thread.triangle_tests++;
        if (!triangle_crossing_prepared(tri->a, tri->b, tri->c, r, &t, &u, &v) || !(t > t_min && t < t_max))
            continue;
        uint32_t face = b->faces[k];
        if (q->kind == QUERY_ANY) {
            q->found = true;
            return false;
        }
        if (q->kind == QUERY_ALL) {
            q->found = true;
            if (!q->visit(q->ctx, t, face))
                return false;
        } else if (triangle_hit_wins(t, face, q->t, q->face)) { /* q->t is t_max until the first hit */
            q->found = true;
            q->t = t;
            q->face = face;
            *box_max = t; /* from now on only boxes starting at or before t matter */
        }
    }
    return true;
}

/* A node still to visit, with the distance at which the ray enters its box. */
struct stack_entry {
    uint32_t node;
    double entry;
};

/* Walks the tree for one query, after the slivers. Returns q->found. */
/* TASK 10.3: ordered BVH traversal */
static bool traverse(const struct bvh *b, const ray *r, double t_min, double t_max, struct query_state *q) {
    q->found = false;
    q->t = t_max;
    /* The box tests' window: infinite ends replaced by the largest finite doubles, so that a ray
     * parallel to a slab and outside it (entry and exit both +infinity) is a miss. */
    double box_min = fmax(t_min, -DBL_MAX), box_max = fmin(t_max, DBL_MAX);
    struct triangle_ray ready = triangle_ray_make(r); /* the triangle test's per-ray work, done once per query */
    uint32_t slivers = (uint32_t)(b->triangle_count - b->tree_count);
    if (!test_triangles(b, &ready, (uint32_t)b->tree_count, slivers, t_min, t_max, q, &box_max) || b->tree_count == 0)
        return q->found;
    vec3 inv = aabb_inverse_direction(r->direction); /* the slab tests' per-ray work */
    struct stack_entry stack[BVH_STACK_SIZE];
    int top = 0;
    double entry;
    if (aabb_hit(&b->nodes[0].box, r->origin, inv, box_min, box_max, &entry))
        stack[top++] = (struct stack_entry){0, entry};
    while (top > 0) {
        struct stack_entry e = stack[--top];
        if (e.entry > box_max)
            continue; /* starts after the best hit: nothing in it can be nearer (or tie and win) */
        const struct bvh_node *n = &b->nodes[e.node];
        stats_thread.node_visits++;
        if (n->count > 0) {
            if (!test_triangles(b, &ready, n->first, n->count, t_min, t_max, q, &box_max))
                break;
            continue;
        }
        double enter_left = INFINITY, enter_right = INFINITY; /* stay so for a box the ray misses */
        bool left = aabb_hit(&b->nodes[n->left].box, r->origin, inv, box_min, box_max, &enter_left);
        bool right = aabb_hit(&b->nodes[n->right].box, r->origin, inv, box_min, box_max, &enter_right);
        struct stack_entry near = {n->left, enter_left}, far = {n->right, enter_right};
        bool near_hit = left, far_hit = right;
        if (q->kind == QUERY_CLOSEST && enter_right < enter_left) { /* the right child comes first */
            near = (struct stack_entry){n->right, enter_right};
            far = (struct stack_entry){n->left, enter_left};
            near_hit = right;
            far_hit = left;
        }
        if (far_hit) /* pushed first, so taken after the near one */
            stack[top++] = far;
        if (near_hit)
            stack[top++] = near;
    }
    return q->found;
}

bool bvh_closest(const struct bvh *b, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    struct query_state q = {.kind = QUERY_CLOSEST};
    if (!traverse(b, r, t_min, t_max, &q))
        return false;
    *t = q.t;
    *face = q.face;
    return true;
}

bool bvh_occluded(const struct bvh *b, const ray *r, double t_min, double t_max) {
    struct query_state q = {.kind = QUERY_ANY};
    return traverse(b, r, t_min, t_max, &q);
}

void bvh_for_each_hit(const struct bvh *b, const ray *r, double t_min, double t_max,
                      bool (*visit)(void *ctx, double t, uint32_t face), void *ctx) {
    struct query_state q = {.kind = QUERY_ALL, .visit = visit, .ctx = ctx};
    traverse(b, r, t_min, t_max, &q);
}
