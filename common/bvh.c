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
 *    anything measurable. The slab test itself runs in double on these float bounds.
 *  - Ties: a box is skipped only when it starts strictly after the best hit so far, and a triangle at
 *    the same t as the best replaces it only with a lower face index.
 *
 * Layout, chosen for speed. A node stores the boxes of its two children side by side (64 bytes, one
 * cache line), so a ray visiting it tests both children with 2-wide vector arithmetic and decides which
 * to enter first without touching the children themselves. A child is either another node or a leaf:
 * a run of triangles, stored in leaf order as (a, b - a, c - a) in doubles with their face numbers
 * beside them. The root's box is kept in struct bvh. */
#include "bvh.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "stats.h"

/* Centroid slots per axis for the SAH build. Wald (2007) found 16 within a few percent of testing
 * every plane; more bins build slower and help little. */
#define BVH_BINS 16

/* An SAH node with more triangles than this is always split, even when the heuristic would rather
 * not: a long leaf is costly for every ray that reaches it, which the heuristic's averages hide. */
#define BVH_MAX_LEAF_SIZE 8

/* The dissertation's median build stops at one or two triangles per node. */
#define BVH_MEDIAN_LEAF_SIZE 2

/* Relative costs of visiting a node (testing both children's boxes) and of one triangle test, as the
 * heuristic sees them. Measured on this code they are about equal (each is some twenty floating point
 * operations and a few branches); bench_accel prints the predicted cost next to the measured. */
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

/* Faces are numbered with uint32_t. */
#define BVH_MAX_FACES ((size_t)1 << 31)

struct bvh_node {
    float bounds[3][2][2]; /* [axis][0 = low, 1 = high][child]: both children's boxes, side by side */
    uint32_t child[2];     /* an interior child's node index, or a leaf child's first triangle */
    uint32_t count[2];     /* 0 when the child is a node; otherwise the leaf's number of triangles */
};

_Static_assert(sizeof(struct bvh_node) == 64, "a node should fill exactly one 64-byte cache line");

/* A triangle as the intersection test wants it: corner a and the two edges leaving it. */
struct bvh_triangle {
    vec3 a, edge1, edge2;
};

struct bvh {
    struct bvh_node *nodes;          /* node_count entries, 64-byte aligned */
    size_t node_count;
    float root_lo[3], root_hi[3];    /* the root's box */
    uint32_t root_child, root_count; /* the root, as a child is referred to in a node */
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

/* A run of prims, with the box of their boxes and the box of their centroids. */
struct build_range {
    uint32_t begin, end;
    struct fbox box, centroids;
};

struct builder {
    struct build_prim *prims;
    struct bvh_node *nodes;
    size_t node_count;
    enum bvh_split split;
    double root_area;
    size_t leaves, max_depth;
    double sah_cost;
};

static struct fbox fbox_empty(void) {
    return (struct fbox){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

static inline void fbox_grow(struct fbox *b, const float lo[3], const float hi[3]) {
    for (int a = 0; a < 3; a++) {
        b->lo[a] = lo[a] < b->lo[a] ? lo[a] : b->lo[a];
        b->hi[a] = hi[a] > b->hi[a] ? hi[a] : b->hi[a];
    }
}

/* Surface area; 0 for an empty box. In double: only the heuristic uses it. */
static inline double fbox_area(const struct fbox *b) {
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

/* Twice the centre of a prim's box along axis: the key the splits sort by. */
static inline float prim_centroid(const struct build_prim *p, int axis) { return p->lo[axis] + p->hi[axis]; }

static inline void swap_prims(struct build_prim *a, struct build_prim *b) {
    struct build_prim t = *a;
    *a = *b;
    *b = t;
}

/* Fills r->box and r->centroids from prims[r->begin, r->end). */
static void range_bounds(const struct build_prim *prims, struct build_range *r) {
    r->box = fbox_empty();
    r->centroids = fbox_empty();
    for (uint32_t k = r->begin; k < r->end; k++) {
        fbox_grow(&r->box, prims[k].lo, prims[k].hi);
        float c[3] = {prim_centroid(&prims[k], 0), prim_centroid(&prims[k], 1), prim_centroid(&prims[k], 2)};
        fbox_grow(&r->centroids, c, c);
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

/* Halves r by count along the longest axis of its centroids' box (the dissertation's split; also the
 * fallback when the SAH finds no plane). */
static void split_median(struct build_prim *prims, const struct build_range *r, struct build_range *left,
                         struct build_range *right) {
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (r->centroids.hi[a] - r->centroids.lo[a] > r->centroids.hi[axis] - r->centroids.lo[axis])
            axis = a;
    uint32_t mid = r->begin + (r->end - r->begin) / 2;
    select_nth(prims, r->begin, r->end, mid, axis);
    left->begin = r->begin;
    left->end = mid;
    right->begin = mid;
    right->end = r->end;
    range_bounds(prims, left);
    range_bounds(prims, right);
}

struct bin {
    struct fbox box, centroids;
    uint32_t count;
};

/* The slot of a centroid: the same expression in binning and partitioning, so both agree. */
static inline int bin_of(const struct build_prim *p, int axis, float origin, float scale) {
    int k = (int)((prim_centroid(p, axis) - origin) * scale);
    return k < BVH_BINS ? k : BVH_BINS - 1;
}

/* Looks for the cheapest SAH split of r. Returns false, leaving the prims alone, when a leaf is
 * cheaper or no plane separates the centroids; otherwise partitions r into *left and *right. */
static bool split_sah(struct build_prim *prims, const struct build_range *r, struct build_range *left,
                      struct build_range *right) {
    struct bin bins[3][BVH_BINS];
    float scale[3];
    for (int a = 0; a < 3; a++) {
        float extent = r->centroids.hi[a] - r->centroids.lo[a];
        scale[a] = extent > 0.0f ? (float)BVH_BINS / extent : 0.0f;
        for (int k = 0; k < BVH_BINS; k++)
            bins[a][k] = (struct bin){fbox_empty(), fbox_empty(), 0};
    }
    for (uint32_t i = r->begin; i < r->end; i++) {
        const struct build_prim *p = &prims[i];
        float c[3] = {prim_centroid(p, 0), prim_centroid(p, 1), prim_centroid(p, 2)};
        for (int a = 0; a < 3; a++) {
            struct bin *slot = &bins[a][bin_of(p, a, r->centroids.lo[a], scale[a])];
            slot->count++;
            fbox_grow(&slot->box, p->lo, p->hi);
            fbox_grow(&slot->centroids, c, c);
        }
    }

    /* For each axis, sweep from the right to get the area and count right of every plane, then from the
     * left to price each plane. Cost: the sum of area * count over both sides. */
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
            right_area[k] = fbox_area(&acc); /* the plane between slot k - 1 and slot k */
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
        return false;

    uint32_t count = r->end - r->begin;
    double area = fbox_area(&r->box);
    double split_cost = area > 0.0 ? BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * best_cost / area : INFINITY;
    if (count <= BVH_MAX_LEAF_SIZE && BVH_COST_TRIANGLE * count <= split_cost)
        return false;

    uint32_t mid = r->begin, back = r->end; /* [begin,mid) go left, [back,end) go right */
    while (mid < back) {
        if (bin_of(&prims[mid], best_axis, r->centroids.lo[best_axis], scale[best_axis]) < best_plane)
            mid++;
        else
            swap_prims(&prims[mid], &prims[--back]);
    }
    /* The children's boxes are the unions of their slots': no further pass over the prims. */
    *left = (struct build_range){r->begin, mid, fbox_empty(), fbox_empty()};
    *right = (struct build_range){mid, r->end, fbox_empty(), fbox_empty()};
    for (int k = 0; k < BVH_BINS; k++) {
        struct build_range *side = k < best_plane ? left : right;
        fbox_grow(&side->box, bins[best_axis][k].box.lo, bins[best_axis][k].box.hi);
        fbox_grow(&side->centroids, bins[best_axis][k].centroids.lo, bins[best_axis][k].centroids.hi);
    }
    return true;
}

/* Builds the subtree over r and stores how its parent refers to it in *child and *count (see struct
 * bvh_node). */
static void build_subtree(struct builder *bd, const struct build_range *r, size_t depth, uint32_t *child,
                          uint32_t *count) {
    uint32_t n = r->end - r->begin;
    struct build_range left, right;
    bool split = false;
    if (bd->split == BVH_SPLIT_MEDIAN) {
        if (n > BVH_MEDIAN_LEAF_SIZE) {
            split_median(bd->prims, r, &left, &right);
            split = true;
        }
    } else if (n > 1) {
        if (depth < BVH_MAX_DEPTH)
            split = split_sah(bd->prims, r, &left, &right);
        /* Too deep for the heuristic, or every centroid at one point: still too many for a leaf, so
         * halve by count. */
        if (!split && n > BVH_MAX_LEAF_SIZE) {
            split_median(bd->prims, r, &left, &right);
            split = true;
        }
    }

    double share = bd->root_area > 0.0 ? fbox_area(&r->box) / bd->root_area : 1.0;
    if (!split) {
        *child = r->begin;
        *count = n;
        bd->leaves++;
        bd->sah_cost += BVH_COST_TRIANGLE * n * share;
        if (depth > bd->max_depth)
            bd->max_depth = depth;
        return;
    }
    bd->sah_cost += BVH_COST_TRAVERSAL * share;
    uint32_t index = (uint32_t)bd->node_count++;
    struct bvh_node *node = &bd->nodes[index];
    for (int a = 0; a < 3; a++) {
        node->bounds[a][0][0] = left.box.lo[a];
        node->bounds[a][1][0] = left.box.hi[a];
        node->bounds[a][0][1] = right.box.lo[a];
        node->bounds[a][1][1] = right.box.hi[a];
    }
    build_subtree(bd, &left, depth + 1, &node->child[0], &node->count[0]);
    build_subtree(bd, &right, depth + 1, &node->child[1], &node->count[1]);
    *child = index;
    *count = 0;
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
    struct build_prim *prims = malloc((n ? n : 1) * sizeof *prims);
    b->triangle_count = n;
    /* A binary tree whose leaves hold at least one triangle each has at most n - 1 interior nodes. */
    b->nodes = aligned_alloc(64, (n > 1 ? n - 1 : 1) * sizeof *b->nodes);
    b->triangles = malloc((n ? n : 1) * sizeof *b->triangles);
    b->faces = malloc((n ? n : 1) * sizeof *b->faces);
    if (b->nodes == NULL || b->triangles == NULL || b->faces == NULL || prims == NULL) {
        free(prims);
        bvh_free(b);
        return NULL;
    }

    /* The pad: BVH_BOX_PAD times the largest extent of the vertices the faces use. */
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t f = 0; f < n; f++)
        for (int c = 0; c < 3; c++) {
            lo = vec3_min(lo, m->vertices[m->faces[f].v[c]]);
            hi = vec3_max(hi, m->vertices[m->faces[f].v[c]]);
        }
    vec3 extent = vec3_sub(hi, lo);
    double pad = n > 0 ? BVH_BOX_PAD * fmax(extent.x, fmax(extent.y, extent.z)) : 0.0;
    for (size_t f = 0; f < n; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], bb = m->vertices[v[1]], c = m->vertices[v[2]];
        vec3 tlo = vec3_min(a, vec3_min(bb, c)), thi = vec3_max(a, vec3_max(bb, c));
        for (int axis = 0; axis < 3; axis++) {
            prims[f].lo[axis] = float_below(vec3_axis(tlo, axis) - pad);
            prims[f].hi[axis] = float_above(vec3_axis(thi, axis) + pad);
        }
        prims[f].face = (uint32_t)f;
        prims[f].unused = 0;
    }

    struct build_range root = {0, (uint32_t)n, fbox_empty(), fbox_empty()};
    range_bounds(prims, &root);
    if (n == 0)
        root.box = (struct fbox){{0, 0, 0}, {0, 0, 0}};
    memcpy(b->root_lo, root.box.lo, sizeof root.box.lo);
    memcpy(b->root_hi, root.box.hi, sizeof root.box.hi);
    struct builder bd = {prims, b->nodes, 0, split, fbox_area(&root.box), 0, 0, 0.0};
    if (n > 0)
        build_subtree(&bd, &root, 0, &b->root_child, &b->root_count);
    b->node_count = bd.node_count;
    assert(bd.max_depth < BVH_STACK_SIZE);

    for (size_t k = 0; k < n; k++) {
        uint32_t f = prims[k].face;
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]];
        b->triangles[k] = (struct bvh_triangle){a, vec3_sub(m->vertices[v[1]], a), vec3_sub(m->vertices[v[2]], a)};
        b->faces[k] = f;
    }
    free(prims);

    b->info.nodes = bd.node_count + bd.leaves;
    b->info.leaves = bd.leaves;
    b->info.max_depth = bd.max_depth;
    b->info.sah_cost = bd.sah_cost;
    b->info.build_ms = now_ms() - start;
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

/* ==== checking ================================================================================ */

struct check {
    const struct bvh *b;
    const struct mesh *m;
    unsigned char *seen_triangle, *seen_node;
    char *why;
    size_t why_size;
};

static bool check_fail(struct check *c, const char *message, size_t where) {
    snprintf(c->why, c->why_size, "%s (at %zu)", message, where);
    return false;
}

/* Checks the subtree referred to by (child, count) whose box is [lo, hi]. */
static bool check_subtree(struct check *c, uint32_t child, uint32_t count, const float lo[3], const float hi[3],
                          size_t depth) {
    if (depth >= BVH_STACK_SIZE)
        return check_fail(c, "deeper than the traversal stack", depth);
    if (count > 0) {
        if ((size_t)child + count > c->b->triangle_count)
            return check_fail(c, "leaf runs past the triangles", child);
        for (uint32_t k = child; k < child + count; k++) {
            if (c->seen_triangle[k]++)
                return check_fail(c, "triangle in two leaves", k);
            const uint32_t *v = c->m->faces[c->b->faces[k]].v;
            for (int corner = 0; corner < 3; corner++) {
                vec3 p = c->m->vertices[v[corner]];
                for (int a = 0; a < 3; a++)
                    if (!(vec3_axis(p, a) >= lo[a] && vec3_axis(p, a) <= hi[a]))
                        return check_fail(c, "leaf box does not hold its triangle", k);
            }
        }
        return true;
    }
    if (child >= c->b->node_count || c->seen_node[child]++)
        return check_fail(c, "node index out of range or reached twice", child);
    const struct bvh_node *n = &c->b->nodes[child];
    for (int k = 0; k < 2; k++) {
        float child_lo[3], child_hi[3];
        for (int a = 0; a < 3; a++) {
            child_lo[a] = n->bounds[a][0][k];
            child_hi[a] = n->bounds[a][1][k];
            if (!(child_lo[a] >= lo[a] && child_hi[a] <= hi[a]))
                return check_fail(c, "child box sticks out of its parent's", child);
        }
        if (!check_subtree(c, n->child[k], n->count[k], child_lo, child_hi, depth + 1))
            return false;
    }
    return true;
}

bool bvh_is_valid(const struct bvh *b, const struct mesh *m, char *why, size_t why_size) {
    struct check c = {b, m, calloc(b->triangle_count + 1, 1), calloc(b->node_count + 1, 1), why, why_size};
    bool ok = c.seen_triangle != NULL && c.seen_node != NULL;
    if (!ok)
        snprintf(why, why_size, "out of memory");
    if (ok && b->triangle_count != m->face_count)
        ok = check_fail(&c, "triangle count differs from the mesh's face count", b->triangle_count);
    for (size_t k = 0; ok && k < b->triangle_count; k++) {
        uint32_t f = b->faces[k];
        if (f >= m->face_count) {
            ok = check_fail(&c, "face number out of range", k);
            break;
        }
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], e1 = vec3_sub(m->vertices[v[1]], a), e2 = vec3_sub(m->vertices[v[2]], a);
        const struct bvh_triangle *t = &b->triangles[k];
        if (memcmp(&t->a, &a, sizeof a) != 0 || memcmp(&t->edge1, &e1, sizeof e1) != 0 ||
            memcmp(&t->edge2, &e2, sizeof e2) != 0)
            ok = check_fail(&c, "stored triangle differs from its face", k);
    }
    if (ok && b->triangle_count > 0)
        ok = check_subtree(&c, b->root_child, b->root_count, b->root_lo, b->root_hi, 0);
    for (size_t k = 0; ok && k < b->triangle_count; k++)
        if (!c.seen_triangle[k])
            ok = check_fail(&c, "triangle in no leaf", k);
    /* Every face once: triangles hold each face exactly once when no face number repeats. */
    if (ok) {
        memset(c.seen_triangle, 0, b->triangle_count + 1);
        for (size_t k = 0; ok && k < b->triangle_count; k++)
            if (c.seen_triangle[b->faces[k]]++)
                ok = check_fail(&c, "face stored twice", b->faces[k]);
    }
    free(c.seen_triangle);
    free(c.seen_node);
    return ok;
}

/* ==== traversal =============================================================================== */

/* Two doubles processed as one: lane k belongs to child k of a node. GCC's vector extension; on
 * x86-64 each operation is one SSE2 instruction. */
typedef double double2 __attribute__((vector_size(16)));
typedef int64_t long2 __attribute__((vector_size(16)));

/* Lane by lane, a > b ? a : b and a < b ? a : b. A NaN in a compares false and gives b: that is how
 * the slab test ignores 0 * infinity (see box_hit). SSE2 has these as single instructions. */
static inline double2 max2(double2 a, double2 b) {
#if defined(__SSE2__)
    return _mm_max_pd(a, b);
#else
    long2 pick_a = a > b;
    return (double2)(((long2)a & pick_a) | ((long2)b & ~pick_a));
#endif
}

static inline double2 min2(double2 a, double2 b) {
#if defined(__SSE2__)
    return _mm_min_pd(a, b);
#else
    long2 pick_a = a < b;
    return (double2)(((long2)a & pick_a) | ((long2)b & ~pick_a));
#endif
}

/* What every box test of one ray shares: computed once per ray. */
struct ray_setup {
    double origin[3];
    double inverse[3];  /* 1 / direction; a zero component gives an infinity of the zero's sign */
    int near[3];        /* 0 when the ray enters a box through its low face on this axis, 1 for the high */
    double2 origin2[3]; /* origin and inverse again, each component in both lanes */
    double2 inverse2[3];
};

static inline struct ray_setup ray_setup_make(const ray *r) {
    struct ray_setup s;
    for (int a = 0; a < 3; a++) {
        s.origin[a] = vec3_axis(r->origin, a);
        s.inverse[a] = 1.0 / vec3_axis(r->direction, a);
        s.near[a] = s.inverse[a] < 0.0;
        s.origin2[a] = (double2){s.origin[a], s.origin[a]};
        s.inverse2[a] = (double2){s.inverse[a], s.inverse[a]};
    }
    return s;
}

/* The slab test (aabb.c) on the root box, in double: true when the ray is inside it for some t in
 * [t_near, t_far]. An origin exactly on a face plane with a zero direction component gives
 * 0 * infinity = NaN, which compares false and so leaves the interval alone: a ray running in a face's
 * plane is inside. */
static inline bool root_hit(const struct bvh *b, const struct ray_setup *s, double t_near, double t_far) {
    for (int a = 0; a < 3; a++) {
        double near_plane = s->near[a] ? b->root_hi[a] : b->root_lo[a];
        double far_plane = s->near[a] ? b->root_lo[a] : b->root_hi[a];
        double t0 = (near_plane - s->origin[a]) * s->inverse[a];
        double t1 = (far_plane - s->origin[a]) * s->inverse[a];
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    return t_near <= t_far;
}

/* One axis of the slab test on both children of n at once: narrows each lane's [enter, leave]. */
static inline void slab_pair(const struct bvh_node *n, const struct ray_setup *s, int axis, double2 *enter,
                             double2 *leave) {
    const float *near_planes = n->bounds[axis][s->near[axis]], *far_planes = n->bounds[axis][1 - s->near[axis]];
    double2 t0 = ((double2){near_planes[0], near_planes[1]} - s->origin2[axis]) * s->inverse2[axis];
    double2 t1 = ((double2){far_planes[0], far_planes[1]} - s->origin2[axis]) * s->inverse2[axis];
    *enter = max2(t0, *enter);
    *leave = min2(t1, *leave);
}

/* The slab test on both children of n at once. Returns a bit mask (bit k: child k is hit in
 * [t_near, t_far]) and each child's entry distance in *entry. */
static inline int children_hit(const struct bvh_node *n, const struct ray_setup *s, double t_near, double t_far,
                               double2 *entry) {
    double2 enter = {t_near, t_near}, leave = {t_far, t_far};
    slab_pair(n, s, 0, &enter, &leave);
    slab_pair(n, s, 1, &enter, &leave);
    slab_pair(n, s, 2, &enter, &leave);
    *entry = enter;
    long2 hit = enter <= leave;
    return (int)(hit[0] & 1) | (int)(hit[1] & 2);
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
    QUERY_CLOSEST, /* nearest hit: near child first, boxes beyond the best hit skipped */
    QUERY_ANY,     /* any hit: stop at the first */
    QUERY_ALL,     /* every hit: visit everything the ray crosses */
};

struct query_state {
    double t;      /* QUERY_CLOSEST: best t so far (t_max until something is found) */
    uint32_t face; /* QUERY_CLOSEST: its face */
    bool found;
    bool (*visit)(void *ctx, double t, uint32_t face); /* QUERY_ALL */
    void *ctx;
};

/* A subtree put aside for later, with the distance at which the ray enters its box. */
struct stack_entry {
    uint32_t child, count;
    double entry;
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
    struct stack_entry stack[BVH_STACK_SIZE];
    int top = 0;
    uint32_t child = b->root_child, count = b->root_count;
    bool running = root_hit(b, &s, box_min, box_max);
    while (running) {
        visits++;
        if (count == 0) {
            const struct bvh_node *n = &b->nodes[child];
            double2 entry;
            int hit = children_hit(n, &s, box_min, box_max, &entry);
            boxes += 2;
            if (hit == 3) {
                /* Both: enter the nearer now, put the farther aside with its entry distance. */
                int near = kind == QUERY_CLOSEST && entry[1] < entry[0];
                stack[top++] = (struct stack_entry){n->child[1 - near], n->count[1 - near], entry[1 - near]};
                child = n->child[near];
                count = n->count[near];
                continue;
            }
            if (hit != 0) {
                int k = hit >> 1; /* bit 0 set: child 0; bit 1 set: child 1 */
                child = n->child[k];
                count = n->count[k];
                continue;
            }
        } else {
            for (uint32_t k = child; k < child + count; k++) {
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
        /* Next: the most recently put aside subtree that can still hold something at or before box_max
         * (at: a lower face at the same t would win the tie). */
        running = false;
        while (top > 0) {
            const struct stack_entry *e = &stack[--top];
            if (e->entry <= box_max) {
                child = e->child;
                count = e->count;
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
