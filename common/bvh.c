/* bvh.c: bounding volume hierarchy, median and binned-SAH builds, stack traversal (chapter 10).
 *
 * The build sorts triangles into a binary tree of axis-aligned boxes. BVH_SPLIT_MEDIAN is the
 * dissertation's rule (halve the triangles by centroid along the longest axis). BVH_SPLIT_SAH is the
 * binned surface area heuristic of Wald, "On fast construction of SAH-based bounding volume
 * hierarchies" (IEEE RT 2007): the centroids are dropped into BVH_BINS slots per axis, and of the
 * BVH_BINS - 1 planes between slots the one minimising
 *     BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * (area(L) * count(L) + area(R) * count(R)) / area(node)
 * is taken, unless a leaf (BVH_COST_TRIANGLE * count) is cheaper. The ratio of a child's area to its
 * parent's is the chance that a random ray through the parent also crosses the child (MacDonald and
 * Booth 1990), so the sum is the expected cost of a ray that reaches the node.
 *
 * Tuning constants (values below): BVH_BINS 16, BVH_MAX_LEAF_SIZE 8, BVH_MEDIAN_LEAF_SIZE 2,
 * BVH_COST_TRAVERSAL 1.0, BVH_COST_TRIANGLE 1.0, BVH_MAX_DEPTH 64, BVH_BOX_PAD 2^-20.
 *
 * Exact agreement with the brute-force loop. A query must return the very face and t that testing
 * every face with triangle_intersect would. Three things make sure of it:
 *  - Triangles are tested with a copy of triangle_intersect's arithmetic (same operations, same
 *    order, edges b - a and c - a computed once at build time with the same subtraction), so t is the
 *    same double to the last bit.
 *  - A box may only be skipped when no triangle inside can be reported hit. Moller-Trumbore rounds:
 *    it may call a ray that passes a hair outside a triangle a hit. So every triangle's box is grown by
 *    BVH_BOX_PAD times the mesh's size before it is rounded outward to float, far more than any such
 *    rounding error (about 1e-16 of the distance from the ray's origin) and far too little to cost
 *    anything measurable.
 *  - Ties: a box is skipped only when it starts strictly after the best hit so far, and a triangle at
 *    the same t as the best replaces it only with a lower face index.
 *
 * Layout. A node is 32 bytes: its box as floats, and either the index of its first child (the second
 * follows it) or the first triangle and count of a leaf. Children are allocated in pairs from index 2
 * (index 1 is left empty), so with a 64-byte aligned array each pair shares one cache line. Triangles
 * are stored in leaf order as (a, b - a, c - a) in doubles, with their face numbers beside them. */
#include "bvh.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stats.h"

/* Centroid slots per axis for the SAH build. Wald (2007) found 16 within a few percent of testing
 * every plane; more bins build slower and help little. */
#define BVH_BINS 16

/* An SAH node with more triangles than this is always split, even when the heuristic would rather
 * not: a long leaf is costly for every ray that reaches it, which the heuristic's averages hide. */
#define BVH_MAX_LEAF_SIZE 8

/* The dissertation's median build stops at one or two triangles per node. */
#define BVH_MEDIAN_LEAF_SIZE 2

/* Relative costs of visiting an interior node (testing both children's boxes) and of one triangle
 * test, as the heuristic sees them. Measured on this code they are about equal (each is ~20 floating
 * point operations and a few branches); bench_accel prints the predicted cost next to the measured. */
#define BVH_COST_TRAVERSAL 1.0
#define BVH_COST_TRIANGLE 1.0

/* Below this depth the SAH chooses freely; deeper nodes are halved by count, so the depth, and the
 * traversal stack, stay bounded (at most BVH_MAX_DEPTH + 32 levels for 2^32 triangles). */
#define BVH_MAX_DEPTH 64
#define BVH_STACK_SIZE 128

/* Every triangle's box is grown by this fraction of the mesh's largest extent (see the file comment):
 * 2^-20, about 1e-6, is ten orders of magnitude above Moller-Trumbore's rounding for rays starting
 * within a thousand mesh sizes, and invisible in the statistics. */
#define BVH_BOX_PAD (1.0 / 1048576.0)

/* Faces are numbered with uint32_t and nodes number at most twice the faces. */
#define BVH_MAX_FACES ((size_t)1 << 30)

struct bvh_node {
    float lo[3];
    uint32_t first; /* interior: index of the first child (the second is first + 1); leaf: first triangle */
    float hi[3];
    uint32_t count; /* 0 for an interior node; the number of triangles of a leaf */
};

_Static_assert(sizeof(struct bvh_node) == 32, "two sibling nodes should fill one 64-byte cache line");

/* A triangle as the intersection test wants it: corner a and the two edges leaving it. */
struct bvh_triangle {
    vec3 a, edge1, edge2;
};

struct bvh {
    struct bvh_node *nodes;          /* node_slots entries, 64-byte aligned; [0] is the root, [1] unused */
    size_t node_slots;               /* highest index used + 1 */
    struct bvh_triangle *triangles;  /* triangle_count entries, in leaf order */
    uint32_t *faces;                 /* faces[k] = index into the mesh's faces of triangles[k] */
    size_t triangle_count;
    struct bvh_info info;
};

/* ==== building ================================================================================ */

/* A box in float, bounds rounded outward. */
struct fbox {
    float lo[3], hi[3];
};

/* One triangle while building: its padded box and its face number. 32 bytes, moved as a whole by the
 * partitions so each pass reads memory in order. */
struct build_prim {
    float lo[3], hi[3];
    uint32_t face;
    uint32_t unused;
};

struct builder {
    struct build_prim *prims;
    struct bvh_node *nodes;
    size_t node_slots;
    enum bvh_split split;
    size_t leaves, max_depth;
};

static struct fbox fbox_empty(void) {
    return (struct fbox){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

static void fbox_grow(struct fbox *b, const float lo[3], const float hi[3]) {
    for (int a = 0; a < 3; a++) {
        b->lo[a] = lo[a] < b->lo[a] ? lo[a] : b->lo[a];
        b->hi[a] = hi[a] > b->hi[a] ? hi[a] : b->hi[a];
    }
}

/* Surface area; 0 for an empty box. Computed in double: only the heuristic uses it. */
static double fbox_area(const struct fbox *b) {
    double ex = (double)b->hi[0] - b->lo[0], ey = (double)b->hi[1] - b->lo[1], ez = (double)b->hi[2] - b->lo[2];
    if (!(ex >= 0.0 && ey >= 0.0 && ez >= 0.0))
        return 0.0;
    return 2.0 * (ex * ey + ey * ez + ez * ex);
}

/* The largest float <= x and the smallest float >= x: a float box built from these holds the double
 * box exactly. */
static float float_below(double x) {
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float float_above(double x) {
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* Twice the centre of a primitive's box along axis: the key the splits sort by. */
static float prim_centroid(const struct build_prim *p, int axis) { return p->lo[axis] + p->hi[axis]; }

static void swap_prims(struct build_prim *a, struct build_prim *b) {
    struct build_prim t = *a;
    *a = *b;
    *b = t;
}

/* Box of prims[begin, end) and box of their centroids. */
static void bounds_of(const struct build_prim *prims, uint32_t begin, uint32_t end, struct fbox *box,
                      struct fbox *centroids) {
    *box = fbox_empty();
    *centroids = fbox_empty();
    for (uint32_t k = begin; k < end; k++) {
        fbox_grow(box, prims[k].lo, prims[k].hi);
        float c[3] = {prim_centroid(&prims[k], 0), prim_centroid(&prims[k], 1), prim_centroid(&prims[k], 2)};
        fbox_grow(centroids, c, c);
    }
}

/* Reorders prims[begin, end) so that prims[nth] has the centroid it would have if sorted along axis,
 * with no larger centroid before it and no smaller after (quickselect, Hoare's FIND, with a
 * three-way partition so that many equal centroids cost nothing extra). */
static void select_nth(struct build_prim *prims, uint32_t begin, uint32_t end, uint32_t nth, int axis) {
    while (end - begin > 1) {
        float a = prim_centroid(&prims[begin], axis);
        float b = prim_centroid(&prims[begin + (end - begin) / 2], axis);
        float c = prim_centroid(&prims[end - 1], axis);
        float pivot = a < b ? (b < c ? b : (a < c ? c : a)) : (a < c ? a : (b < c ? c : b)); /* median */
        uint32_t less = begin, i = begin, greater = end; /* [begin,less) < pivot, [greater,end) > pivot */
        while (i < greater) {
            float key = prim_centroid(&prims[i], axis);
            if (key < pivot)
                swap_prims(&prims[less++], &prims[i++]);
            else if (key > pivot)
                swap_prims(&prims[i], &prims[--greater]);
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

/* Halves prims[begin, end) by count along the longest axis of their centroids' box. */
static uint32_t split_median(struct build_prim *prims, uint32_t begin, uint32_t end, const struct fbox *centroids) {
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (centroids->hi[a] - centroids->lo[a] > centroids->hi[axis] - centroids->lo[axis])
            axis = a;
    uint32_t mid = begin + (end - begin) / 2;
    select_nth(prims, begin, end, mid, axis);
    return mid;
}

struct bin {
    struct fbox box;
    uint32_t count;
};

/* The slot of a centroid: the same expression in binning and partitioning, so both agree. */
static int bin_of(const struct build_prim *p, int axis, float origin, float scale) {
    int k = (int)((prim_centroid(p, axis) - origin) * scale);
    return k < BVH_BINS ? k : BVH_BINS - 1;
}

/* Chooses an SAH split of prims[begin, end), whose box is *box and centroid box *centroids. Returns
 * the index where the right half starts after partitioning, or `begin` when a leaf is cheaper (the
 * prims are then untouched) or when no plane separates the centroids. */
static uint32_t split_sah(struct build_prim *prims, uint32_t begin, uint32_t end, const struct fbox *box,
                          const struct fbox *centroids) {
    struct bin bins[3][BVH_BINS];
    float scale[3];
    for (int a = 0; a < 3; a++) {
        float extent = centroids->hi[a] - centroids->lo[a];
        scale[a] = extent > 0.0f ? (float)BVH_BINS / extent : 0.0f;
        for (int k = 0; k < BVH_BINS; k++)
            bins[a][k] = (struct bin){fbox_empty(), 0};
    }
    for (uint32_t i = begin; i < end; i++) {
        for (int a = 0; a < 3; a++) {
            struct bin *slot = &bins[a][bin_of(&prims[i], a, centroids->lo[a], scale[a])];
            slot->count++;
            fbox_grow(&slot->box, prims[i].lo, prims[i].hi);
        }
    }

    /* For each axis, sweep from the right to get the area and count right of every plane, then from the
     * left to price each plane. Cost is in units of "triangle tests per ray reaching this node". */
    double best_cost = INFINITY;
    int best_axis = -1, best_plane = 0;
    for (int a = 0; a < 3; a++) {
        if (scale[a] == 0.0f)
            continue; /* all centroids in one plane: this axis cannot separate them */
        double right_area[BVH_BINS];
        uint32_t right_count[BVH_BINS];
        struct fbox acc = fbox_empty();
        uint32_t count = 0;
        for (int k = BVH_BINS - 1; k > 0; k--) {
            fbox_grow(&acc, bins[a][k].box.lo, bins[a][k].box.hi);
            count += bins[a][k].count;
            right_area[k] = fbox_area(&acc); /* plane between slot k - 1 and slot k */
            right_count[k] = count;
        }
        acc = fbox_empty();
        count = 0;
        for (int k = 1; k < BVH_BINS; k++) {
            fbox_grow(&acc, bins[a][k - 1].box.lo, bins[a][k - 1].box.hi);
            count += bins[a][k - 1].count;
            if (count == 0 || right_count[k] == 0)
                continue;
            double cost = fbox_area(&acc) * count + right_area[k] * right_count[k];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = a;
                best_plane = k;
            }
        }
    }
    if (best_axis < 0)
        return begin;

    uint32_t count = end - begin;
    double area = fbox_area(box);
    double split_cost = area > 0.0 ? BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * best_cost / area : INFINITY;
    if (count <= BVH_MAX_LEAF_SIZE && BVH_COST_TRIANGLE * count <= split_cost)
        return begin;

    uint32_t left = begin, right = end; /* [begin,left) go left, [right,end) go right */
    while (left < right) {
        if (bin_of(&prims[left], best_axis, centroids->lo[best_axis], scale[best_axis]) < best_plane)
            left++;
        else
            swap_prims(&prims[left], &prims[--right]);
    }
    return left;
}

/* Turns nodes[index] into the root of a subtree over prims[begin, end), whose box is *box. */
static void build_node(struct builder *bd, uint32_t index, uint32_t begin, uint32_t end, const struct fbox *box,
                       size_t depth) {
    struct bvh_node *node = &bd->nodes[index];
    memcpy(node->lo, box->lo, sizeof node->lo);
    memcpy(node->hi, box->hi, sizeof node->hi);
    uint32_t count = end - begin;

    uint32_t mid = begin; /* begin: make a leaf */
    struct fbox unused, centroids;
    if (count > 1)
        bounds_of(bd->prims, begin, end, &unused, &centroids);
    if (bd->split == BVH_SPLIT_MEDIAN) {
        if (count > BVH_MEDIAN_LEAF_SIZE)
            mid = split_median(bd->prims, begin, end, &centroids);
    } else if (count > 1) {
        mid = depth < BVH_MAX_DEPTH ? split_sah(bd->prims, begin, end, box, &centroids) : begin;
        /* Too deep, or every centroid at one point: still too many for a leaf, so halve by count. */
        if (mid == begin && (count > BVH_MAX_LEAF_SIZE || depth >= BVH_MAX_DEPTH) && count > BVH_MEDIAN_LEAF_SIZE)
            mid = split_median(bd->prims, begin, end, &centroids);
    }

    if (mid == begin || mid == end) {
        node->first = begin;
        node->count = count;
        bd->leaves++;
        if (depth > bd->max_depth)
            bd->max_depth = depth;
        return;
    }
    uint32_t pair = (uint32_t)bd->node_slots;
    bd->node_slots += 2;
    node->first = pair;
    node->count = 0;
    struct fbox left_box, right_box;
    bounds_of(bd->prims, begin, mid, &left_box, &unused);
    bounds_of(bd->prims, mid, end, &right_box, &unused);
    build_node(bd, pair, begin, mid, &left_box, depth + 1);
    build_node(bd, pair + 1, mid, end, &right_box, depth + 1);
}

/* Expected cost of a ray through the tree's root, by the surface area heuristic. */
static double tree_sah_cost(const struct bvh *b) {
    double root_area = fbox_area(&(struct fbox){{b->nodes[0].lo[0], b->nodes[0].lo[1], b->nodes[0].lo[2]},
                                                {b->nodes[0].hi[0], b->nodes[0].hi[1], b->nodes[0].hi[2]}});
    if (!(root_area > 0.0))
        return BVH_COST_TRIANGLE * (double)b->triangle_count;
    double cost = 0.0;
    for (size_t i = 0; i < b->node_slots; i++) {
        if (i == 1)
            continue; /* the unused slot */
        const struct bvh_node *n = &b->nodes[i];
        struct fbox box = {{n->lo[0], n->lo[1], n->lo[2]}, {n->hi[0], n->hi[1], n->hi[2]}};
        double share = fbox_area(&box) / root_area;
        cost += n->count == 0 ? BVH_COST_TRAVERSAL * share : BVH_COST_TRIANGLE * n->count * share;
    }
    return cost;
}

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

struct bvh *bvh_build(const struct mesh *m, enum bvh_split split) {
    double start = now_ms();
    size_t n = m->face_count;
    if (n > BVH_MAX_FACES)
        return NULL;
    struct bvh *b = calloc(1, sizeof *b);
    if (b == NULL)
        return NULL;
    struct build_prim *prims = NULL;
    b->triangle_count = n;
    /* Slots: 2n - 1 nodes at most, plus the unused slot 1; rounded up to whole cache lines. */
    size_t slots = 2 * n + 2;
    b->nodes = aligned_alloc(64, (slots * sizeof *b->nodes + 63) / 64 * 64);
    b->triangles = malloc((n ? n : 1) * sizeof *b->triangles);
    b->faces = malloc((n ? n : 1) * sizeof *b->faces);
    prims = malloc((n ? n : 1) * sizeof *prims);
    if (b->nodes == NULL || b->triangles == NULL || b->faces == NULL || prims == NULL)
        goto fail;
    if (n == 0) {
        b->info.build_ms = now_ms() - start;
        free(prims);
        return b;
    }

    /* The pad: BVH_BOX_PAD times the largest extent of the vertices the faces use. */
    struct aabb_d {
        vec3 lo, hi;
    } all = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (size_t f = 0; f < n; f++)
        for (int k = 0; k < 3; k++) {
            vec3 p = m->vertices[m->faces[f].v[k]];
            all.lo = vec3_min(all.lo, p);
            all.hi = vec3_max(all.hi, p);
        }
    vec3 extent = vec3_sub(all.hi, all.lo);
    double pad = BVH_BOX_PAD * fmax(extent.x, fmax(extent.y, extent.z));

    for (size_t f = 0; f < n; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], bb = m->vertices[v[1]], c = m->vertices[v[2]];
        vec3 lo = vec3_min(a, vec3_min(bb, c)), hi = vec3_max(a, vec3_max(bb, c));
        for (int axis = 0; axis < 3; axis++) {
            prims[f].lo[axis] = float_below(vec3_axis(lo, axis) - pad);
            prims[f].hi[axis] = float_above(vec3_axis(hi, axis) + pad);
        }
        prims[f].face = (uint32_t)f;
        prims[f].unused = 0;
    }

    struct builder bd = {prims, b->nodes, 2, split, 0, 0};
    struct fbox root_box, centroids;
    bounds_of(prims, 0, (uint32_t)n, &root_box, &centroids);
    memset(&b->nodes[1], 0, sizeof b->nodes[1]);
    build_node(&bd, 0, 0, (uint32_t)n, &root_box, 0);
    b->node_slots = bd.node_slots;
    assert(bd.max_depth < BVH_STACK_SIZE);

    for (size_t k = 0; k < n; k++) {
        uint32_t f = prims[k].face;
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]];
        b->triangles[k] = (struct bvh_triangle){a, vec3_sub(m->vertices[v[1]], a), vec3_sub(m->vertices[v[2]], a)};
        b->faces[k] = f;
    }
    free(prims);

    b->info.nodes = b->node_slots - 1; /* all but the unused slot */
    b->info.leaves = bd.leaves;
    b->info.max_depth = bd.max_depth;
    b->info.sah_cost = tree_sah_cost(b);
    b->info.build_ms = now_ms() - start;
    return b;

fail:
    free(prims);
    bvh_free(b);
    return NULL;
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

/* What every box test of one ray shares: computed once per ray. */
struct ray_setup {
    double origin[3];
    double inverse[3];  /* 1 / direction; a zero component gives an infinity of the zero's sign */
    bool negative[3];   /* direction < 0 (or -0): the ray enters through the box's high face */
};

static struct ray_setup ray_setup_make(const ray *r) {
    struct ray_setup s;
    for (int a = 0; a < 3; a++) {
        s.origin[a] = vec3_axis(r->origin, a);
        s.inverse[a] = 1.0 / vec3_axis(r->direction, a);
        s.negative[a] = s.inverse[a] < 0.0;
    }
    return s;
}

/* The slab test (aabb.c) on a float node box, in double. Returns true when the ray is inside the box
 * for some t in [t_near, t_far], and stores the entry distance in *t_entry. An origin exactly on a face
 * plane with a zero direction component gives 0 * infinity = NaN, which compares false and so leaves
 * the interval alone: a ray running in a face's plane is inside. Plain comparisons rather than
 * fmin/fmax: they compile to single instructions and handle that NaN the way we want. */
static inline bool box_hit(const struct bvh_node *n, const struct ray_setup *s, double t_near, double t_far,
                           double *t_entry) {
    for (int a = 0; a < 3; a++) {
        double near_plane = s->negative[a] ? n->hi[a] : n->lo[a];
        double far_plane = s->negative[a] ? n->lo[a] : n->hi[a];
        double t0 = (near_plane - s->origin[a]) * s->inverse[a];
        double t1 = (far_plane - s->origin[a]) * s->inverse[a];
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    *t_entry = t_near;
    return t_near <= t_far;
}

/* Moller-Trumbore with exactly triangle_intersect's arithmetic (the same vec3 operations in the same
 * order on the same values), so t is bit-identical. Returns true and stores t when the ray's line
 * crosses the triangle; the caller checks t against its window. Does not count the test. */
static inline bool triangle_hit(const struct bvh_triangle *tri, const ray *r, double *t) {
    vec3 p = vec3_cross(r->direction, tri->edge2);
    double det = vec3_dot(tri->edge1, p);
    if (det == 0.0)
        return false;
    double inv_det = 1.0 / det;
    vec3 to_origin = vec3_sub(r->origin, tri->a);
    double u = vec3_dot(to_origin, p) * inv_det;
    if (u < 0.0 || u > 1.0)
        return false;
    vec3 q = vec3_cross(to_origin, tri->edge1);
    double v = vec3_dot(r->direction, q) * inv_det;
    if (v < 0.0 || u + v > 1.0)
        return false;
    *t = vec3_dot(tri->edge2, q) * inv_det;
    return true;
}

/* The three questions one traversal answers; the code is specialised for each at compile time. */
enum query {
    QUERY_CLOSEST,  /* nearest hit: near child first, boxes beyond the best hit skipped */
    QUERY_ANY,      /* any hit: stop at the first */
    QUERY_ALL,      /* every hit: visit everything the ray crosses */
};

struct query_state {
    double t;      /* QUERY_CLOSEST: best t so far (t_max until something is found) */
    uint32_t face; /* QUERY_CLOSEST: its face */
    bool found;
    bool (*visit)(void *ctx, double t, uint32_t face); /* QUERY_ALL */
    void *ctx;
};

/* Walks the tree for one query. Counters are kept in locals and added to the thread's once at the end
 * (one thread-local update per ray instead of one per node). Returns q->found. */
static inline __attribute__((always_inline)) bool traverse(const struct bvh *b, const ray *r, double t_min,
                                                           double t_max, enum query kind, struct query_state *q) {
    q->found = false;
    q->t = t_max;
    if (b->triangle_count == 0)
        return false;
    struct ray_setup s = ray_setup_make(r);
    /* The box tests' window: infinite ends replaced by the largest finite doubles, so that a ray
     * parallel to a slab and outside it (entry and exit both +infinity) is a miss. */
    double box_min = t_min > -DBL_MAX ? t_min : -DBL_MAX;
    double box_max = t_max < DBL_MAX ? t_max : DBL_MAX;
    uint64_t visits = 0, boxes = 1, tests = 0;
    uint32_t stack_node[BVH_STACK_SIZE];
    double stack_entry[BVH_STACK_SIZE];
    int top = 0;
    double entry;
    uint32_t index = 0;
    bool running = box_hit(&b->nodes[0], &s, box_min, box_max, &entry);
    while (running) {
        const struct bvh_node *n = &b->nodes[index];
        visits++;
        if (n->count == 0) {
            const struct bvh_node *child = &b->nodes[n->first];
            double entry0, entry1;
            bool hit0 = box_hit(&child[0], &s, box_min, box_max, &entry0);
            bool hit1 = box_hit(&child[1], &s, box_min, box_max, &entry1);
            boxes += 2;
            if (hit0 && hit1) {
                /* Go to the nearer child, and keep the farther one for later with its entry distance. */
                bool second_first = kind == QUERY_CLOSEST && entry1 < entry0;
                index = n->first + (second_first ? 1u : 0u);
                stack_node[top] = n->first + (second_first ? 0u : 1u);
                stack_entry[top] = second_first ? entry0 : entry1;
                top++;
                continue;
            }
            if (hit0 || hit1) {
                index = n->first + (hit0 ? 0u : 1u);
                continue;
            }
        } else {
            for (uint32_t k = n->first; k < n->first + n->count; k++) {
                double t;
                tests++;
                if (!triangle_hit(&b->triangles[k], r, &t) || !(t > t_min && t < t_max))
                    continue;
                uint32_t face = b->faces[k];
                if (kind == QUERY_ANY) {
                    q->found = true;
                    running = false;
                    break;
                }
                if (kind == QUERY_ALL) {
                    q->found = true;
                    if (!q->visit(q->ctx, t, face)) {
                        running = false;
                        break;
                    }
                    continue;
                }
                if (!q->found || t < q->t || (t == q->t && face < q->face)) {
                    q->found = true;
                    q->t = t;
                    q->face = face;
                    box_max = t; /* from now on only boxes starting at or before t matter */
                }
            }
            if (!running)
                break;
        }
        /* Next: the most recently postponed child that can still hold something at or before box_max. */
        running = false;
        while (top > 0) {
            top--;
            if (stack_entry[top] <= box_max) {
                index = stack_node[top];
                running = true;
                break;
            }
        }
    }
    stats_thread.node_visits += visits;
    stats_thread.box_tests += boxes;
    stats_thread.triangle_tests += tests;
    return q->found;
}

bool bvh_closest(const struct bvh *b, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    struct query_state q = {0};
    if (!traverse(b, r, t_min, t_max, QUERY_CLOSEST, &q))
        return false;
    *t = q.t;
    *face = q.face;
    return true;
}

bool bvh_occluded(const struct bvh *b, const ray *r, double t_min, double t_max) {
    struct query_state q = {0};
    return traverse(b, r, t_min, t_max, QUERY_ANY, &q);
}

void bvh_for_each_hit(const struct bvh *b, const ray *r, double t_min, double t_max,
                      bool (*visit)(void *ctx, double t, uint32_t face), void *ctx) {
    struct query_state q = {0};
    q.visit = visit;
    q.ctx = ctx;
    traverse(b, r, t_min, t_max, QUERY_ALL, &q);
}
