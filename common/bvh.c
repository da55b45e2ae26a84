/* bvh.c: bounding volume hierarchy: median and binned-SAH builds, ordered traversal (chapter 10).
 *
 * The build sorts the triangles into a binary tree of boxes. Each node has the box around its
 * triangles; an interior node has two children, a leaf a run of triangles. BVH_SPLIT_MEDIAN is the
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
 * its box. At an interior node it tests both children's boxes and visits the nearer first; a node that
 * starts beyond the best hit so far is skipped. A shadow ray stops at its first hit.
 *
 * Exact agreement with the brute-force loop. A query must return the very face and t that testing
 * every face with triangle_intersect would. Four things make sure of it:
 *  - Triangles are tested with triangle_crossing_prepared (triangle.h), the very arithmetic
 *    triangle_intersect uses (the ray made ready once per query), on the very corners the mesh holds,
 *    so t is the same double to the last bit.
 *  - A box may only be skipped when no triangle inside can be reported hit. The triangle test rounds:
 *    it may call a ray that passes a hair outside a triangle a hit. So every triangle's box is grown by
 *    BVH_BOX_PAD times the mesh's size, far more than any such rounding error (about 1e-16 of the
 *    distance from the ray's origin) and far too little to cost anything measurable.
 *  - Needle-thin triangles (BVH_SLIVER_SINE), whose rounding errors no pad covers, are kept out of the
 *    tree and tested by every ray.
 *  - Ties: a box is skipped only when it starts strictly after the best hit so far, and a triangle at
 *    the same t as the best replaces it only with a lower face index.
 * What is left: a ray starting more than about a thousand mesh sizes away, or one meeting a triangle's
 * plane at a grazing angle below about 1e-8 radians, has rounding errors the pad may not cover. Neither
 * occurs in tests/test_accel.c's hundreds of thousands of chosen rays nor, as far as we know, in a scene.
 *
 * Everything here is plain double-precision C, written to be read. Chapter 11 (fast_bvh.c) makes the
 * same tree fast: four children per node, float boxes, vector instructions, prefetching. */
#include "bvh.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stats.h"
#include "triangle.h"

/* Centroid slots per axis for the SAH build. Wald (2007) found 16 within a few percent of testing
 * every plane; more bins build slower and help little (exercise 1). */
#define BVH_BINS 16

/* An SAH node with more triangles than this is always split, even when the heuristic would rather
 * not: a long leaf is costly for every ray that reaches it, which the heuristic's averages hide. */
#define BVH_MAX_LEAF_SIZE 8

/* The dissertation's median build stops at one or two triangles per node. */
#define BVH_MEDIAN_LEAF_SIZE 2

/* Relative costs of visiting a node (testing both children's boxes) and of one triangle test, as the
 * heuristic sees them. Measured on this code they are about equal (each is some twenty floating point
 * operations and a few branches); the program prints the predicted cost next to the measured. */
#define BVH_COST_TRAVERSAL 1.0
#define BVH_COST_TRIANGLE 1.0

/* Below this depth the SAH chooses freely; deeper nodes are halved by count, so the depth stays
 * bounded (at most BVH_MAX_DEPTH + 31 levels for 2^31 triangles), and with it the traversal stack,
 * which holds at most one node per level plus one. */
#define BVH_MAX_DEPTH 64
#define BVH_STACK_SIZE (BVH_MAX_DEPTH + 33)

/* Every triangle's box is grown by this fraction of the mesh's largest extent (see the file comment):
 * 2^-20, about 1e-6, is ten orders of magnitude above the triangle test's rounding for rays starting
 * within a thousand mesh sizes, and invisible in the statistics. */
#define BVH_BOX_PAD (1.0 / 1048576.0)

/* A triangle whose edges b - a and c - a are this close to parallel (the sine of the angle between
 * them is below it, yet not zero) is kept out of the tree and tested by every ray. For such a sliver
 * a triangle test divides by a value that is mostly rounding noise, and can report a "hit" far
 * outside the triangle (measured: 2.6e-4 away, for a triangle whose middle corner is the midpoint of
 * its long edge): no box can be trusted to hold it. Above 1e-6 the error stays below 1e-9 of the ray's
 * distance, well inside BVH_BOX_PAD. Edges with an exactly zero cross product are never hit at all
 * (triangle_intersect rejects them), so those stay in the tree. Real meshes have few slivers or none. */
#define BVH_SLIVER_SINE 1e-6

/* Faces are numbered with uint32_t, and a tree of n faces has up to 2n - 1 nodes. */
#define BVH_MAX_FACES ((size_t)1 << 31)

struct bvh_box {
    double lo[3], hi[3];
};

struct bvh_node {
    struct bvh_box box;    /* holds every triangle below the node */
    uint32_t left, right;  /* an interior node's children (indices into the nodes) */
    uint32_t first, count; /* a leaf's triangles: count > 0 of them from triangles[first]; 0 for interior */
};

/* A triangle as the intersection test wants it: its three corners, copied from the mesh. */
struct bvh_triangle {
    vec3 a, b, c;
};

struct bvh {
    struct bvh_node *nodes;         /* node_count entries; the root is nodes[0] */
    size_t node_count;
    struct bvh_triangle *triangles; /* triangle_count entries: tree_count in leaf order, then the slivers */
    uint32_t *faces;                /* faces[k] = index into the mesh's faces of triangles[k] */
    size_t triangle_count, tree_count;
    struct bvh_info info;
};

/* ==== boxes =================================================================================== */

static const struct bvh_box box_empty = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};

/* Grows *b to hold c. A NaN bound of c (a corner beyond double's range) compares false and changes
 * nothing. (Written as comparisons rather than fmin and fmax, which GCC calls as library functions:
 * that made the whole build five times slower.) */
static void box_grow(struct bvh_box *b, const struct bvh_box *c) {
    for (int a = 0; a < 3; a++) {
        b->lo[a] = c->lo[a] < b->lo[a] ? c->lo[a] : b->lo[a];
        b->hi[a] = c->hi[a] > b->hi[a] ? c->hi[a] : b->hi[a];
    }
}

/* Surface area; 0 for an empty box. */
static double box_area(const struct bvh_box *b) {
    double x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    if (!(x >= 0.0 && y >= 0.0 && z >= 0.0))
        return 0.0;
    return 2.0 * (x * y + y * z + z * x);
}

/* ==== building ================================================================================ */

/* A triangle while building: its padded box, the centre of that box, and its face number. */
struct bvh_prim {
    struct bvh_box box;
    double centroid[3];
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
static void range_boxes(const struct bvh_prim *p, uint32_t begin, uint32_t end, struct bvh_box *box,
                        struct bvh_box *centroids) {
    *box = box_empty;
    *centroids = box_empty;
    for (uint32_t k = begin; k < end; k++) {
        box_grow(box, &p[k].box);
        struct bvh_box c = {{p[k].centroid[0], p[k].centroid[1], p[k].centroid[2]},
                            {p[k].centroid[0], p[k].centroid[1], p[k].centroid[2]}};
        box_grow(centroids, &c);
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
        double pivot = p[begin + (end - begin) / 2].centroid[axis];
        uint32_t less = begin, i = begin, greater = end; /* [begin,less) < pivot, [greater,end) > pivot */
        while (i < greater) {
            double key = p[i].centroid[axis];
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
static uint32_t split_median(struct builder *bd, uint32_t begin, uint32_t end, const struct bvh_box *centroids) {
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (centroids->hi[a] - centroids->lo[a] > centroids->hi[axis] - centroids->lo[axis])
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
static bool split_sah(struct builder *bd, uint32_t begin, uint32_t end, const struct bvh_box *box,
                      const struct bvh_box *centroids, uint32_t *mid) {
    struct bvh_prim *p = bd->prims;
    uint32_t n = end - begin;
    double best_cost = INFINITY; /* area(L) * count(L) + area(R) * count(R) of the best plane */
    int best_axis = -1, best_plane = 0;
    for (int a = 0; a < 3; a++) {
        double lo = centroids->lo[a], extent = centroids->hi[a] - lo;
        if (!(extent > 0.0))
            continue; /* all centroids in one plane: this axis cannot separate them */
        struct {
            struct bvh_box box;
            uint32_t count;
        } bins[BVH_BINS];
        for (int k = 0; k < BVH_BINS; k++) {
            bins[k].box = box_empty;
            bins[k].count = 0;
        }
        for (uint32_t i = begin; i < end; i++) {
            int k = bin_of(p[i].centroid[a], lo, extent);
            box_grow(&bins[k].box, &p[i].box);
            bins[k].count++;
        }
        /* Sweep from the right: the area and count of everything right of the plane before slot k. */
        double right_area[BVH_BINS];
        uint32_t right_count[BVH_BINS];
        struct bvh_box side = box_empty;
        uint32_t count = 0;
        for (int k = BVH_BINS - 1; k > 0; k--) {
            box_grow(&side, &bins[k].box);
            count += bins[k].count;
            right_area[k] = box_area(&side);
            right_count[k] = count;
        }
        /* Sweep from the left, pricing each plane on the way. */
        side = box_empty;
        count = 0;
        for (int k = 1; k < BVH_BINS; k++) {
            box_grow(&side, &bins[k - 1].box);
            count += bins[k - 1].count;
            if (count == 0 || right_count[k] == 0)
                continue; /* everything on one side: not a split */
            double cost = box_area(&side) * count + right_area[k] * right_count[k];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = a;
                best_plane = k;
            }
        }
    }
    if (best_axis < 0)
        return false;
    double split_cost = BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * best_cost / box_area(box);
    if (n <= BVH_MAX_LEAF_SIZE && BVH_COST_TRIANGLE * n <= split_cost)
        return false;
    uint32_t i = begin, j = end; /* [begin, i) go left, [j, end) go right */
    double lo = centroids->lo[best_axis], extent = centroids->hi[best_axis] - lo;
    while (i < j) {
        if (bin_of(p[i].centroid[best_axis], lo, extent) < best_plane)
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
    struct bvh_box centroids;
    range_boxes(bd->prims, begin, end, &node->box, &centroids);
    double area_ratio = bd->root_area > 0.0 ? box_area(&node->box) / bd->root_area : 1.0;
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

bool bvh_is_sliver(const struct mesh *m, size_t face) {
    const uint32_t *v = m->faces[face].v;
    vec3 a = m->vertices[v[0]], e1 = vec3_sub(m->vertices[v[1]], a), e2 = vec3_sub(m->vertices[v[2]], a);
    double cross = vec3_length(vec3_cross(e1, e2));
    return cross > 0.0 && cross < BVH_SLIVER_SINE * vec3_length(e1) * vec3_length(e2);
}

double bvh_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

struct bvh *bvh_build(const struct mesh *m, enum bvh_split split) {
    double start = bvh_now_ms();
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
    /* The pad: BVH_BOX_PAD times the largest extent of the mesh's corners. */
    struct bvh_box all = box_empty;
    for (size_t f = 0; f < n; f++)
        for (int c = 0; c < 3; c++) {
            vec3 p = m->vertices[m->faces[f].v[c]];
            box_grow(&all, &(struct bvh_box){{p.x, p.y, p.z}, {p.x, p.y, p.z}});
        }
    double pad = 0.0;
    for (int a = 0; a < 3 && n > 0; a++)
        pad = fmax(pad, BVH_BOX_PAD * (all.hi[a] - all.lo[a]));
    /* One prim per face, slivers to the end of faces[]. */
    size_t tree = 0, slivers = 0;
    for (size_t f = 0; f < n; f++) {
        if (bvh_is_sliver(m, f)) {
            b->faces[n - ++slivers] = (uint32_t)f;
            continue;
        }
        struct bvh_prim *p = &prims[tree++];
        p->box = box_empty;
        for (int c = 0; c < 3; c++) {
            vec3 v = m->vertices[m->faces[f].v[c]];
            box_grow(&p->box, &(struct bvh_box){{v.x - pad, v.y - pad, v.z - pad}, {v.x + pad, v.y + pad, v.z + pad}});
        }
        for (int a = 0; a < 3; a++)
            p->centroid[a] = 0.5 * (p->box.lo[a] + p->box.hi[a]);
        p->face = (uint32_t)f;
    }
    b->tree_count = tree;
    struct builder bd = {prims, b, split, 0.0, 0, 0, 0.0};
    if (tree > 0) {
        struct bvh_box root, centroids;
        range_boxes(prims, 0, (uint32_t)tree, &root, &centroids);
        bd.root_area = box_area(&root);
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
    for (size_t k = 0; k < n; k++) {
        const uint32_t *v = m->faces[b->faces[k]].v;
        b->triangles[k] = (struct bvh_triangle){m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]]};
    }
    b->info = (struct bvh_info){b->node_count, bd.leaves, bd.max_depth, 0.0,
                                bd.sah_cost + BVH_COST_TRIANGLE * slivers, slivers};
    b->info.build_ms = bvh_now_ms() - start;
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

/* The slab test (chapter 5) of box against the ray with origin o and inverse direction inv (1 / D,
 * infinite where D has a zero), within [t_near, t_far]. Returns whether the ray is inside the box for
 * some t there, and where it enters in *entry. On each axis the ray enters through the low face when
 * it moves towards larger values and through the high face otherwise. An origin exactly on a face
 * plane with a zero direction component gives 0 * infinity = NaN, which compares false and so leaves
 * the window alone: a ray running in a face's plane is inside. */
static bool box_hit(const struct bvh_box *box, const double o[3], const double inv[3], double t_near,
                    double t_far, double *entry) {
    for (int a = 0; a < 3; a++) {
        double t0 = ((inv[a] < 0.0 ? box->hi[a] : box->lo[a]) - o[a]) * inv[a];
        double t1 = ((inv[a] < 0.0 ? box->lo[a] : box->hi[a]) - o[a]) * inv[a];
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    *entry = t_near;
    return t_near <= t_far;
}

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
        } else if (!q->found || t < q->t || (t == q->t && face < q->face)) {
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
    double o[3] = {r->origin.x, r->origin.y, r->origin.z};
    double inv[3] = {1.0 / r->direction.x, 1.0 / r->direction.y, 1.0 / r->direction.z};
    struct stack_entry stack[BVH_STACK_SIZE];
    int top = 0;
    double entry;
    stats_thread.box_tests++;
    if (box_hit(&b->nodes[0].box, o, inv, box_min, box_max, &entry))
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
        double enter_left, enter_right;
        bool left = box_hit(&b->nodes[n->left].box, o, inv, box_min, box_max, &enter_left);
        bool right = box_hit(&b->nodes[n->right].box, o, inv, box_min, box_max, &enter_right);
        stats_thread.box_tests += 2;
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

/* True when box b holds box c (a NaN bound, from a corner beyond double's range, holds anything). */
static bool box_holds(const struct bvh_box *b, const struct bvh_box *c) {
    for (int a = 0; a < 3; a++)
        if (b->lo[a] > c->lo[a] || b->hi[a] < c->hi[a])
            return false;
    return true;
}

/* Checks the subtree at node `index`, at the given depth. */
static bool check_node(struct check *c, uint32_t index, size_t depth) {
    if (depth + 1 >= BVH_STACK_SIZE)
        return check_fail(c, "deeper than the traversal stack", depth);
    if (index >= c->b->node_count || c->seen_node[index]++)
        return check_fail(c, "node index out of range or reached twice", index);
    const struct bvh_node *n = &c->b->nodes[index];
    if (n->count == 0) {
        if (n->left >= c->b->node_count || n->right >= c->b->node_count)
            return check_fail(c, "child index out of range", index);
        if (!box_holds(&n->box, &c->b->nodes[n->left].box) || !box_holds(&n->box, &c->b->nodes[n->right].box))
            return check_fail(c, "child box sticks out of its parent's", index);
        return check_node(c, n->left, depth + 1) && check_node(c, n->right, depth + 1);
    }
    if ((size_t)n->first + n->count > c->b->tree_count)
        return check_fail(c, "leaf runs past the triangles", index);
    for (uint32_t k = n->first; k < n->first + n->count; k++) {
        if (c->seen_triangle[k]++)
            return check_fail(c, "triangle in two leaves", k);
        const uint32_t *v = c->m->faces[c->b->faces[k]].v;
        for (int corner = 0; corner < 3; corner++) {
            vec3 p = c->m->vertices[v[corner]];
            if (!box_holds(&n->box, &(struct bvh_box){{p.x, p.y, p.z}, {p.x, p.y, p.z}}))
                return check_fail(c, "leaf box does not hold its triangle", k);
        }
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
        const struct bvh_triangle *t = &b->triangles[k];
        if (memcmp(&t->a, &m->vertices[v[0]], sizeof t->a) != 0 || memcmp(&t->b, &m->vertices[v[1]], sizeof t->b) != 0 ||
            memcmp(&t->c, &m->vertices[v[2]], sizeof t->c) != 0)
            ok = check_fail(&c, "stored triangle differs from its face", k);
    }
    if (ok && b->tree_count > 0)
        ok = check_node(&c, 0, 0);
    if (ok)
        ok = bvh_check_faces(m, b->faces, b->triangle_count, b->tree_count, c.seen_triangle, why, why_size);
    free(c.seen_triangle);
    free(c.seen_node);
    return ok;
}

bool bvh_check_faces(const struct mesh *m, const uint32_t *faces, size_t triangle_count, size_t tree_count,
                     unsigned char *seen, char *why, size_t why_size) {
    const char *what = NULL;
    size_t where = 0;
    for (size_t k = 0; what == NULL && k < tree_count; k++)
        if (!seen[k])
            what = "triangle in no leaf", where = k;
    for (size_t k = 0; what == NULL && k < triangle_count; k++)
        if (bvh_is_sliver(m, faces[k]) != (k >= tree_count))
            what = "sliver in the tree, or other triangle among the slivers", where = k;
    if (what == NULL) { /* every face once: no face number repeats */
        memset(seen, 0, triangle_count + 1);
        for (size_t k = 0; what == NULL && k < triangle_count; k++)
            if (seen[faces[k]]++)
                what = "face stored twice", where = faces[k];
    }
    if (what != NULL)
        snprintf(why, why_size, "%s (at %zu)", what, where);
    return what == NULL;
}
