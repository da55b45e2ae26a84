/* kdtree.c: the kd-tree (chapter 9): its two rules for choosing planes, the build, and the walk from
 * front to back with mailboxes. docs/09-kdtree.md explains each part; the comments say what each
 * function does and where the seed, the literature and our exactness rules come in. */
#include "kdtree.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stats.h"
#include "triangle.h"

/* The SAH's prices of a node step and a triangle test (docs/09-kdtree.md says why 2 to 1). */
#define KD_COST_TRAVERSAL 2.0
#define KD_COST_TRIANGLE 1.0
#define KD_EMPTY_BONUS 0.2    /* a cut leaving one side empty costs 20 % less (Wald and Havran) */
#define KD_MIN_SPLIT_COUNT 2  /* SAH nodes with fewer triangles are leaves */
#define KD_MAX_DEPTH_BASE 8.0 /* the SAH's depth limit is 8 + 1.3 log2(N), as in pbrt */
#define KD_MAX_DEPTH_PER_LEVEL 1.3

/* The dissertation's rule stops at 2 triangles, and at a depth it does not give: we take log2(N) + 2. */
#define KD_SEED_LEAF_SIZE 2
#define KD_SEED_EXTRA_DEPTH 2
/* Our addition: a node whose plane would send more than this share of its triangles both ways is a
 * leaf (without it, 5,000 random triangles made 608 million references). */
#define KD_SEED_MAX_STRADDLING 0.5

#define KD_BOX_PAD (1.0 / 1048576.0) /* triangle boxes grow by this fraction of the mesh's size */
/* Needle-thin triangles (the sine of the angle at corner a below this, not zero) stay out of the tree and
 * are tested by every ray, as in bvh.c: a margin of safety. */
#define KD_SLIVER_SINE 1e-6
/* Tolerance of the t comparisons that prune the walk, relative to the ray's distance from the mesh plus
 * the mesh's size: far above the rounding of a plane's t, far below any real gap. */
#define KD_T_TOLERANCE 1e-9
#define KD_MAILBOX_SIZE 32 /* faces remembered per ray */

/* ==== choosing a plane ========================================================================== */

/* A bound of a triangle's box on one axis: where the box starts or ends, or both when it is flat. */
enum event_type { EVENT_END, EVENT_PLANAR, EVENT_START };
struct event {
    float position;
    uint32_t face;
    enum event_type type;
};

static int by_position(const void *a, const void *b) {
    const struct event *x = a, *y = b;
    return (x->position > y->position) - (x->position < y->position);
}

/* What a node is built from: its faces and, for the SAH, their boxes' bounds on each axis in order. */
struct triangles {
    uint32_t *faces;
    size_t count;
    struct event *events[3]; /* NULL for the seed's rule */
    size_t event_count[3];
};

/* One build: the tree it grows, the triangles' padded boxes, scratch space and limits. */
struct builder {
    struct kdtree *tree;
    size_t node_capacity, ref_capacity;
    const struct aabb *boxes;
    unsigned char *sides; /* per face: the sides of the plane being cut that it goes to */
    double *centres;      /* seed_plane's */
    size_t depth_limit;
    size_t reference_limit; /* KD_MAX_REFERENCES_PER_TRIANGLE times the triangles: past it, only leaves */
    double root_area;
};

static void set_axis(vec3 *v, int axis, double value) { *(axis == 0 ? &v->x : axis == 1 ? &v->y : &v->z) = value; }

enum side { SIDE_LEFT = 1, SIDE_RIGHT = 2, SIDE_BOTH = 3 };

/* Left when the box starts before the plane, right when it ends after it, both when it is flat in it. */
static inline enum side classify(const struct aabb *b, int axis, double split) {
    double lo = vec3_axis(b->min, axis), hi = vec3_axis(b->max, axis);
    bool flat_in_plane = lo == split && hi == split;
    return (lo < split || flat_in_plane ? SIDE_LEFT : 0) | (hi > split || flat_in_plane ? SIDE_RIGHT : 0);
}

/* What cutting `box` (of surface area `area`) at `split` on `axis` costs a ray that crosses it, with
 * n_left and n_right triangles on the two sides: one step, then each side's triangles weighted by the
 * chance that the ray crosses that side, the ratio of the areas. With the box's extents e_b, e_c across
 * the axis, a half of length l along it has area 2 (e_b e_c + l (e_b + e_c)). */
static double plane_cost(struct aabb box, double area, int axis, double split, size_t n_left, size_t n_right) {
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    double extent_b = vec3_axis(box.max, b) - vec3_axis(box.min, b);
    double extent_c = vec3_axis(box.max, c) - vec3_axis(box.min, c);
    double below = split - vec3_axis(box.min, axis), above = vec3_axis(box.max, axis) - split;
    double cross = extent_b * extent_c, side = extent_b + extent_c;
    double bonus = n_left == 0 || n_right == 0 ? 1.0 - KD_EMPTY_BONUS : 1.0;
    return KD_COST_TRAVERSAL +
           KD_COST_TRIANGLE * bonus * 2.0 * ((cross + below * side) * n_left + (cross + above * side) * n_right) / area;
}

/* The SAH's plane for a node over t with region `box`. Between two bounds the counts stay fixed and the
 * cost changes linearly, so the cheapest plane is at a bound: a sweep along each axis's sorted bounds
 * prices every bound inside the region, a triangle counting left of p once its box has started and right
 * until it has ended. The cheapest wins if it beats the leaf (ties: lowest axis, then lowest p). */
/* TASK 9.2: the surface area heuristic */
static bool sah_plane(const struct builder *bd, const struct triangles *t, struct aabb box, size_t depth,
                      int *best_axis, float *best_split) {
    double area = aabb_surface_area(box), best_cost = KD_COST_TRIANGLE * (double)t->count;
    *best_axis = -1;
    if (t->count < KD_MIN_SPLIT_COUNT || depth >= bd->depth_limit || !(area > 0.0))
        return false;
    for (int axis = 0; axis < 3; axis++) {
        const struct event *e = t->events[axis];
        size_t n = t->event_count[axis], left = 0, right = t->count;
        for (size_t i = 0; i < n;) {
            float p = e[i].position;
            size_t at[3] = {0, 0, 0}; /* the ends, flat boxes (they go both ways) and starts at p */
            for (; i < n && e[i].position == p; i++)
                at[e[i].type]++;
            right -= at[EVENT_END] + at[EVENT_PLANAR];
            if (p > vec3_axis(box.min, axis) && p < vec3_axis(box.max, axis)) {
                double cost = plane_cost(box, area, axis, p, left + at[EVENT_PLANAR], right + at[EVENT_PLANAR]);
                if (cost < best_cost) {
                    best_cost = cost;
                    *best_axis = axis;
                    *best_split = p;
                }
            }
            left += at[EVENT_START] + at[EVENT_PLANAR];
        }
    }
    return *best_axis >= 0;
}

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The seed's plane for a node over t with region `box`: on each axis the median of the triangles'
 * centres (of their boxes clipped to the region); the axis whose plane leaves the most triangles whole
 * wins (ties to x, then y). An axis where boxes reach infinity has no median. Returns false for a leaf:
 * at KD_SEED_LEAF_SIZE triangles, at the depth limit, or when more than KD_SEED_MAX_STRADDLING of them
 * would straddle the plane. */
/* TASK 9.1: the dissertation's split rule */
static bool seed_plane(const struct builder *bd, const struct triangles *t, struct aabb box, size_t depth,
                       int *best_axis, float *best_split) {
    size_t best_whole = 0;
    *best_axis = -1;
    if (t->count <= KD_SEED_LEAF_SIZE || depth >= bd->depth_limit)
        return false;
    for (int axis = 0; axis < 3; axis++) {
        bool finite = true;
        for (size_t k = 0; k < t->count; k++) {
            const struct aabb *b = &bd->boxes[t->faces[k]];
            double lo = fmax(vec3_axis(b->min, axis), vec3_axis(box.min, axis));
            double hi = fmin(vec3_axis(b->max, axis), vec3_axis(box.max, axis));
            bd->centres[k] = 0.5 * lo + 0.5 * hi;
            finite = finite && isfinite(bd->centres[k]);
        }
        if (!finite)
            continue;
        qsort(bd->centres, t->count, sizeof *bd->centres, by_value);
        float split = (float)bd->centres[t->count / 2];
        size_t whole = 0;
        for (size_t k = 0; k < t->count; k++)
            whole += classify(&bd->boxes[t->faces[k]], axis, split) != SIDE_BOTH;
        if (*best_axis < 0 || whole > best_whole) {
            *best_axis = axis;
            *best_split = split;
            best_whole = whole;
        }
    }
    return *best_axis >= 0 && (double)(t->count - best_whole) <= KD_SEED_MAX_STRADDLING * (double)t->count;
}

/* ==== building ================================================================================== */

static void free_triangles(struct triangles *t) {
    free(t->faces);
    for (int axis = 0; axis < 3; axis++)
        free(t->events[axis]);
}

/* Returns block resized to `bytes` (a new block for NULL). When memory runs out the program ends with a
 * message and exit status 1, as on bad input: a tree that does not fit cannot be traced. */
static void *resize(void *block, size_t bytes) {
    void *resized = realloc(block, bytes);
    if (resized == NULL) {
        fprintf(stderr, "kd-tree: out of memory (a block of %zu bytes)\n", bytes);
        exit(EXIT_FAILURE);
    }
    return resized;
}

/* Fills left and right with t's faces and events whose boxes reach each side of the plane `split` on
 * `axis`, in t's order, so the events stay sorted. */
static void split_triangles(struct builder *bd, const struct triangles *t, int axis, float split,
                            struct triangles *left, struct triangles *right) {
    *left = (struct triangles){resize(NULL, (t->count + 1) * sizeof(uint32_t)), 0, {NULL, NULL, NULL}, {0, 0, 0}};
    *right = (struct triangles){resize(NULL, (t->count + 1) * sizeof(uint32_t)), 0, {NULL, NULL, NULL}, {0, 0, 0}};
    for (size_t k = 0; k < t->count; k++) {
        uint32_t face = t->faces[k];
        bd->sides[face] = (unsigned char)classify(&bd->boxes[face], axis, split);
        if (bd->sides[face] & SIDE_LEFT)
            left->faces[left->count++] = face;
        if (bd->sides[face] & SIDE_RIGHT)
            right->faces[right->count++] = face;
    }
    for (int a = 0; a < 3 && t->events[a] != NULL; a++) {
        left->events[a] = resize(NULL, (t->event_count[a] + 1) * sizeof(struct event));
        right->events[a] = resize(NULL, (t->event_count[a] + 1) * sizeof(struct event));
        for (size_t i = 0; i < t->event_count[a]; i++) {
            const struct event *e = &t->events[a][i];
            if (bd->sides[e->face] & SIDE_LEFT)
                left->events[a][left->event_count[a]++] = *e;
            if (bd->sides[e->face] & SIDE_RIGHT)
                right->events[a][right->event_count[a]++] = *e;
        }
    }
}

/* Makes nodes[index] a leaf over t's faces, and counts it into the tree's description. */
static void make_leaf(struct builder *bd, uint32_t index, const struct triangles *t, double share, size_t depth) {
    struct kdtree_info *info = &bd->tree->info;
    if (info->references + t->count >= bd->ref_capacity) { /* >=: the first leaf allocates, even if empty */
        bd->ref_capacity = 2 * bd->ref_capacity + t->count + 64;
        bd->tree->refs = resize(bd->tree->refs, bd->ref_capacity * sizeof(uint32_t));
    }
    bd->tree->nodes[index] = (struct kd_node){KD_LEAF, 0.0f, 0, (uint32_t)info->references, (uint32_t)t->count};
    memcpy(bd->tree->refs + info->references, t->faces, t->count * sizeof(uint32_t));
    info->references += t->count;
    info->sah_cost += KD_COST_TRIANGLE * (double)t->count * share;
    info->leaves++;
    info->empty_leaves += t->count == 0;
    info->max_depth = depth > info->max_depth ? depth : info->max_depth;
}

/* Builds the subtree of a node over t (freed here) with region `box`, adding each node's term to the
 * tree's SAH cost weighted by `share`, the chance that a ray crossing the root crosses the node. */
static void build(struct builder *bd, enum kd_split rule, struct triangles *t, struct aabb box, size_t depth) {
    struct kdtree *k = bd->tree;
    if (k->info.nodes >= UINT32_MAX || k->info.references + t->count > UINT32_MAX) {
        fprintf(stderr, "kd-tree: more than 2^32 nodes or references\n");
        exit(EXIT_FAILURE);
    }
    if (k->info.nodes == bd->node_capacity) {
        bd->node_capacity = 2 * bd->node_capacity + 64;
        k->nodes = resize(k->nodes, bd->node_capacity * sizeof *k->nodes);
    }
    uint32_t index = (uint32_t)k->info.nodes++;
    double share = bd->root_area > 0.0 ? aabb_surface_area(box) / bd->root_area : 1.0;
    int axis = -1;
    float split = 0.0f;
    bool within_limit = k->info.references + t->count <= bd->reference_limit;
    bool cut = within_limit && (rule == KD_SPLIT_SEED ? seed_plane(bd, t, box, depth, &axis, &split)
                                                      : sah_plane(bd, t, box, depth, &axis, &split));
    if (!cut) {
        make_leaf(bd, index, t, share, depth);
        free_triangles(t);
        return;
    }
    struct triangles left, right;
    split_triangles(bd, t, axis, split, &left, &right);
    free_triangles(t);
    k->info.sah_cost += KD_COST_TRAVERSAL * share;
    k->nodes[index] = (struct kd_node){axis, split, 0, 0, 0};
    struct aabb below = box, above = box;
    set_axis(&below.max, axis, split);
    set_axis(&above.min, axis, split);
    build(bd, rule, &left, below, depth + 1);
    k->nodes[index].above = (uint32_t)k->info.nodes;
    build(bd, rule, &right, above, depth + 1);
}

/* The box of triangle a, b, c grown by pad and rounded outward to float. A bound that is not a number (a
 * corner at infinity or NaN) becomes infinite: the box still holds the triangle, and no cost is NaN.
 * Where the pad is lost in rounding (a mesh a few units in the last place across, pad > 0 but
 * x - pad == x), the bound still moves one float step outward: a box must never end exactly on its
 * triangle's corner, or a plane there would leave the triangle on one side only. */
static struct aabb padded_box(vec3 a, vec3 b, vec3 c, double pad) {
    vec3 lo = vec3_min(a, vec3_min(b, c)), hi = vec3_max(a, vec3_max(b, c));
    struct aabb box;
    for (int axis = 0; axis < 3; axis++) {
        double min = vec3_axis(lo, axis) - pad, max = vec3_axis(hi, axis) + pad;
        bool min_moved = min < vec3_axis(lo, axis) || pad == 0.0, max_moved = max > vec3_axis(hi, axis) || pad == 0.0;
        float down = (float)min, up = (float)max;
        set_axis(&box.min, axis,
                 isnan(min) ? -INFINITY : down > min || (down == min && !min_moved) ? nextafterf(down, -INFINITY) : down);
        set_axis(&box.max, axis,
                 isnan(max) ? INFINITY : up < max || (up == max && !max_moved) ? nextafterf(up, INFINITY) : up);
    }
    return box;
}

struct kdtree *kdtree_build(const struct mesh *m, enum kd_split split) {
    size_t n = m->face_count;
    if (n > UINT32_MAX)
        return NULL; /* face numbers are 32 bits */
    struct kdtree *k = resize(NULL, sizeof *k);
    *k = (struct kdtree){.triangles = resize(NULL, (n + 1) * sizeof *k->triangles), .face_count = n,
                         .slivers = resize(NULL, (n + 1) * sizeof *k->slivers)};
    struct aabb *boxes = resize(NULL, (n + 1) * sizeof *boxes);
    struct builder bd = {.tree = k, .boxes = boxes, .sides = resize(NULL, n + 1),
                         .centres = resize(NULL, (n + 1) * sizeof(double))};
    struct triangles all = {.faces = resize(NULL, (n + 1) * sizeof(uint32_t))};
    for (int axis = 0; split == KD_SPLIT_SAH && axis < 3; axis++)
        all.events[axis] = resize(NULL, (2 * n + 1) * sizeof(struct event));
    /* The pad; the triangles as the test wants them; the padded boxes of the faces that go into the
     * tree (all but the slivers), their union, and for the SAH their bounds on each axis, sorted. */
    struct aabb bounds = aabb_empty(), root = aabb_empty();
    for (size_t f = 0; f < n; f++)
        for (int c = 0; c < 3; c++)
            bounds = aabb_grow(bounds, m->vertices[m->faces[f].v[c]]);
    vec3 extent = vec3_sub(bounds.max, bounds.min);
    double pad = n > 0 ? KD_BOX_PAD * fmax(extent.x, fmax(extent.y, extent.z)) : 0.0;
    for (uint32_t f = 0; f < n; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
        k->triangles[f] = (struct kd_triangle){a, b, c};
        vec3 e1 = vec3_sub(b, a), e2 = vec3_sub(c, a);
        double sine = vec3_length(vec3_cross(e1, e2)) / (vec3_length(e1) * vec3_length(e2));
        if (sine > 0.0 && sine < KD_SLIVER_SINE) {
            k->slivers[k->info.slivers++] = f;
            continue;
        }
        all.faces[all.count++] = f;
        boxes[f] = padded_box(a, b, c, pad);
        root = aabb_union(root, boxes[f]);
        for (int axis = 0; split == KD_SPLIT_SAH && axis < 3; axis++) {
            float lo = (float)vec3_axis(boxes[f].min, axis), hi = (float)vec3_axis(boxes[f].max, axis);
            if (lo < hi)
                all.events[axis][all.event_count[axis]++] = (struct event){hi, f, EVENT_END};
            all.events[axis][all.event_count[axis]++] = (struct event){lo, f, lo < hi ? EVENT_START : EVENT_PLANAR};
        }
    }
    for (int axis = 0; split == KD_SPLIT_SAH && axis < 3; axis++)
        qsort(all.events[axis], all.event_count[axis], sizeof(struct event), by_position);
    k->root = all.count > 0 ? root : (struct aabb){vec3_make(0, 0, 0), vec3_make(0, 0, 0)};
    k->centre = vec3_scale(vec3_add(k->root.min, k->root.max), 0.5);
    k->size = vec3_length(vec3_sub(k->root.max, k->root.min));
    bd.root_area = aabb_surface_area(k->root);
    double levels = log2((double)(all.count > 1 ? all.count : 1));
    bd.depth_limit = split == KD_SPLIT_SEED ? (size_t)ceil(levels) + KD_SEED_EXTRA_DEPTH
                                            : (size_t)(KD_MAX_DEPTH_BASE + KD_MAX_DEPTH_PER_LEVEL * levels);
    /* within 32 bits (the references' numbers) with room for the nodes under way, on any size_t */
    bd.reference_limit = all.count < UINT32_MAX / 2 / KD_MAX_REFERENCES_PER_TRIANGLE
                             ? KD_MAX_REFERENCES_PER_TRIANGLE * (all.count > 0 ? all.count : 1)
                             : UINT32_MAX / 2;
    build(&bd, split, &all, k->root, 0); /* frees all */
    k->info.sah_cost += KD_COST_TRIANGLE * (double)k->info.slivers;
    free(boxes);
    free(bd.sides);
    free(bd.centres);
    return k;
}

void kdtree_free(struct kdtree *k) {
    if (k == NULL)
        return;
    free(k->nodes);
    free(k->refs);
    free(k->triangles);
    free(k->slivers);
    free(k);
}

void kdtree_get_info(const struct kdtree *k, struct kdtree_info *info) { *info = k->info; }

/* ==== walking =================================================================================== */

/* One query: what it asks, its window, the ray made ready for the triangle test, what it found. */
struct query {
    enum { QUERY_CLOSEST, QUERY_ANY, QUERY_ALL } kind; /* the nearest hit, any hit, every hit */
    double t_min, t_max;
    struct triangle_ray ray;
    bool found;
    double t; /* QUERY_CLOSEST: the best hit so far (t_max until one is found) */
    uint32_t face;
    bool (*visit)(void *ctx, double t, uint32_t face); /* QUERY_ALL */
    void *ctx;
    /* QUERY_ALL: the faces reported so far, a set: `slots` entries (0, or a power of two at least twice
     * `count`), each a face or KD_NO_FACE, a face in the first free entry from its hash on. */
    uint32_t *reported;
    size_t reported_count, reported_slots;
};

/* An entry of the reported set that holds no face (no face has this number: there are fewer). */
#define KD_NO_FACE UINT32_MAX
/* The reported set's first size. */
#define KD_REPORTED_FIRST_SLOTS 16

/* Where the reported set of `slots` entries starts looking for face: Knuth's multiplicative hash, so
 * that neighbouring faces spread out. */
static size_t reported_start(uint32_t face, size_t slots) {
    return (size_t)(face * 2654435761u) & (slots - 1);
}

/* Puts face into the reported set unless it is there; returns whether it was new. */
static bool reported_add(struct query *q, uint32_t face) {
    size_t at = reported_start(face, q->reported_slots);
    while (q->reported[at] != KD_NO_FACE) {
        if (q->reported[at] == face)
            return false;
        at = (at + 1) & (q->reported_slots - 1);
    }
    q->reported[at] = face;
    q->reported_count++;
    return true;
}

/* Doubles the reported set (or makes its first), putting back the faces it held. */
static void reported_grow(struct query *q) {
    uint32_t *old = q->reported;
    size_t old_slots = q->reported_slots;
    q->reported_slots = old_slots == 0 ? KD_REPORTED_FIRST_SLOTS : 2 * old_slots;
    q->reported = resize(NULL, q->reported_slots * sizeof *q->reported);
    for (size_t k = 0; k < q->reported_slots; k++)
        q->reported[k] = KD_NO_FACE;
    q->reported_count = 0;
    for (size_t k = 0; k < old_slots; k++)
        if (old[k] != KD_NO_FACE)
            reported_add(q, old[k]);
    free(old);
}

/* QUERY_ALL: reports face unless it already was (a face may lie in many leaves); returns false when the
 * walk should stop. The faces reported are a hash set, so that a ray crossing n faces costs about n
 * steps: a list searched from its start cost n², and a stack of 100,000 coplanar glass triangles took
 * chapter 9 75 s for a 32 x 24 picture. */
static bool report_once(struct query *q, double t, uint32_t face) {
    if (2 * (q->reported_count + 1) > q->reported_slots)
        reported_grow(q);
    if (!reported_add(q, face))
        return true;
    return q->visit(q->ctx, t, face);
}

/* Tests faces[0..count) for hits with q->t_min < t < t_max, skipping and recording faces in the mailbox if
 * one is given. Returns false when the walk should stop: any hit found, or the visitor said so. */
static bool test_faces(const struct kdtree *k, struct query *q, const uint32_t *faces, size_t count, double t_max,
                       uint32_t *mailbox) {
    for (size_t i = 0; i < count; i++) {
        uint32_t face = faces[i];
        if (mailbox != NULL) {
            uint32_t *slot = &mailbox[face % KD_MAILBOX_SIZE];
            if (*slot == face)
                continue; /* tested already on this ray */
            *slot = face;
        }
        stats_thread.triangle_tests++;
        const struct kd_triangle *tri = &k->triangles[face];
        double t, u, v;
        if (!triangle_crossing_prepared(tri->a, tri->b, tri->c, &q->ray, &t, &u, &v) || !(t > q->t_min && t < t_max))
            continue;
        bool nearest = !q->found || t < q->t || (t == q->t && face < q->face); /* ties: the lowest face */
        q->found = true;
        if (q->kind == QUERY_ANY || (q->kind == QUERY_ALL && !report_once(q, t, face)))
            return false; /* any hit will do, or the visitor said stop */
        if (q->kind == QUERY_CLOSEST && nearest) {
            q->t = t;
            q->face = face;
        }
    }
    return true;
}

/* Walks the tree for query q along r, after testing the slivers. Returns q->found. */
/* TASK 9.3: front-to-back traversal */
static bool traverse(const struct kdtree *k, const ray *r, struct query *q) {
    q->t = q->t_max;
    double length = vec3_length(r->direction);
    if (k->face_count == 0 || length == 0.0)
        return false; /* a zero direction hits nothing: the triangle test's shear is NaN */
    q->ray = triangle_ray_make(r);
    if (!test_faces(k, q, k->slivers, k->info.slivers, q->t_max, NULL))
        return q->found;

    /* The ray's stretch inside the root box (chapter 5's slab test; infinite ends made finite, so that
     * a ray parallel to a slab and outside it misses). */
    double t_near = fmax(q->t_min, -DBL_MAX), t_far = fmin(q->t_max, DBL_MAX);
    vec3 inverse_direction = aabb_inverse_direction(r->direction);
    stats_thread.box_tests++;
    if (!aabb_clip(&k->root, r->origin, inverse_direction, &t_near, &t_far))
        return q->found;

    double reach = vec3_length(vec3_sub(r->origin, k->centre)) + k->size;
    double tolerance = fmin(KD_T_TOLERANCE * reach / length, INFINITY); /* NaN (a box reaching infinity): INFINITY */
    uint32_t mailbox[KD_MAILBOX_SIZE];
    memset(mailbox, 0xff, sizeof mailbox); /* UINT32_MAX: no face */
    struct postponed {
        uint32_t node;
        double t_near, t_far; /* the ray's stretch in it */
    } stack[KD_STACK_SIZE];
    int top = 0;
    uint32_t index = 0;
    for (;;) {
        const struct kd_node *n = &k->nodes[index];
        stats_thread.node_visits++;
        if (n->axis != KD_LEAF) {
            /* The children in the order the ray meets them: going up the axis, the one below first. */
            double inverse = vec3_axis(inverse_direction, n->axis);
            double t_split = ((double)n->split - vec3_axis(r->origin, n->axis)) * inverse;
            bool from_above = inverse < 0.0;
            uint32_t first = from_above ? n->above : index + 1, second = from_above ? index + 1 : n->above;
            if (isnan(t_split)) {
                /* the ray runs inside the plane (origin on it, direction 0 on this axis): both sides */
                stack[top++] = (struct postponed){second, t_near, t_far};
                index = first;
            } else if (t_split > t_far + tolerance) {
                index = first; /* the plane lies beyond the ray's stretch in this node */
            } else if (t_split < t_near - tolerance) {
                index = second; /* the ray crossed the plane before entering this node */
            } else {
                double t_cross = t_split < t_near ? t_near : t_split > t_far ? t_far : t_split;
                stack[top++] = (struct postponed){second, t_cross, t_far};
                index = first;
                t_far = t_cross;
            }
            continue;
        }
        if (!test_faces(k, q, &k->refs[n->first], n->count, q->t_max, mailbox))
            return q->found;
        /* Next: the last postponed subtree that starts no later than the best hit (give or take the
         * tolerance): one starting beyond it holds nothing nearer. (q->t stays t_max for the others.) */
        do {
            if (top == 0)
                return q->found;
        } while (!(stack[--top].t_near <= q->t + tolerance));
        index = stack[top].node;
        t_near = stack[top].t_near;
        t_far = stack[top].t_far;
    }
}

bool kdtree_closest(const struct kdtree *k, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    struct query q = {.kind = QUERY_CLOSEST, .t_min = t_min, .t_max = t_max};
    if (!traverse(k, r, &q))
        return false;
    *t = q.t;
    *face = q.face;
    return true;
}

bool kdtree_occluded(const struct kdtree *k, const ray *r, double t_min, double t_max) {
    struct query q = {.kind = QUERY_ANY, .t_min = t_min, .t_max = t_max};
    return traverse(k, r, &q);
}

void kdtree_for_each_hit(const struct kdtree *k, const ray *r, double t_min, double t_max,
                         bool (*visit)(void *ctx, double t, uint32_t face), void *ctx) {
    struct query q = {.kind = QUERY_ALL, .t_min = t_min, .t_max = t_max, .visit = visit, .ctx = ctx};
    traverse(k, r, &q);
    free(q.reported);
}
