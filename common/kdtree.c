/* kdtree.c: kd-tree, the dissertation's rule and the SAH, stack traversal with mailboxes (chapter 9).
 *
 * Build. Every node is cut by one axis-aligned plane; a triangle goes to each side its (padded) box
 * reaches, so triangles that straddle the plane are referenced from both halves. Two rules choose the
 * plane:
 *
 *  - KD_SPLIT_SEED, the dissertation's (its section 3.1): bound the objects, cut along the axis that
 *    holds the most objects, send straddling objects both ways, stop at a fixed depth or below a
 *    primitive count. It says neither where on that axis the plane goes nor how an axis holds objects.
 *    We read it as its BVH chapter does the same job: the plane goes through the median of the
 *    triangles' centres (of their boxes clipped to the node), and an axis holds the objects that its
 *    median plane leaves whole on one side; the axis holding the most wins (ties to
 *    x, then y). Leaves at KD_SEED_LEAF_SIZE triangles or the depth limit, and (our addition) where
 *    more than KD_SEED_MAX_STRADDLING of the triangles would straddle the plane.
 *
 *  - KD_SPLIT_SAH, the surface area heuristic as in Wald and Havran (IEEE RT 2006), section 4: the
 *    candidate planes are the faces of the triangles' boxes, the cost of cutting at p is
 *        KD_COST_TRAVERSAL + KD_COST_TRIANGLE * (area(L) * count(L) + area(R) * count(R)) / area(node),
 *    lowered by KD_EMPTY_BONUS when one side is empty, and a node becomes a leaf when no plane beats
 *    KD_COST_TRIANGLE * count ("no benefit"), when it holds fewer than KD_MIN_SPLIT_COUNT triangles, or
 *    at the depth limit. sah_plane below tries every candidate plainly, O(N^2) per node; kdtree_build
 *    uses kdtree_events.c, their O(N log N) sweep over sorted bounds, which finds the same planes and
 *    builds the same tree (KD_SPLIT_SAH_PLAIN builds it plainly, for the tests).
 *    Triangles are not clipped to the node (their "perfect splits"): a straddling triangle keeps its
 *    whole box in both children, which costs some tree quality and keeps the build simple.
 *
 * The SAH's depth limit is KD_MAX_DEPTH_BASE + KD_MAX_DEPTH_PER_LEVEL * log2(triangles), 8 + 1.3 log2 N
 * as in pbrt and Havran's thesis; the dissertation's rule stops at log2 N + KD_SEED_EXTRA_DEPTH.
 *
 * Traversal: front to back with a stack, the walk the dissertation quotes (its figure 19; Havran's
 * thesis compares the family): at each node the ray's interval [t_near, t_far] is split at the plane's
 * t, the child the ray meets first is visited and the other pushed with its interval. The textbook
 * accepts a hit in a leaf only when it lies inside the leaf's interval, because a straddling triangle's
 * hit may lie in a later leaf, behind something nearer there. Combined with mailboxes (below) that rule
 * loses hits: the triangle rejected in the first leaf is not tested again in the leaf where its hit
 * really is. So here every hit is kept whatever leaf finds it, and a postponed subtree is skipped when
 * it starts after the best hit so far: the first leaf whose interval contains the best hit is still
 * where the search ends, for the same reason.
 *
 * Mailboxes (Amanatides and Woo 1987, per ray as in Havran's thesis): a small direct-mapped array of
 * the last KD_MAILBOX_SIZE faces tested on this ray, so a triangle referenced from several leaves along
 * the ray is mostly tested once. A face evicted from it is tested again at worst, giving the same t
 * and changing nothing for the nearest hit; kdtree_for_each_hit also keeps a list of the faces it has
 * reported, so it reports each once.
 *
 * Exact agreement with the brute-force loop, as in bvh.c: triangles are tested with triangle_intersect's
 * arithmetic (triangle_crossing) on the very corners the mesh holds (same t to the last bit); every
 * triangle's box is grown by KD_BOX_PAD times the mesh's size and rounded outward to float, so that a
 * ray that the test's rounding calls a hit is always in a leaf holding the triangle; needle-thin
 * triangles (KD_SLIVER_SINE) stay out of the tree and are tested by every ray; and the t comparisons
 * that prune the walk allow a tolerance of KD_T_TOLERANCE (relative to the distances involved) for the
 * rounding of the planes' t. Ties go to the lowest face index, as in the brute-force loop. The pad
 * outweighs the test's rounding while the ray starts within about 2^30 mesh sizes of the mesh (the pad
 * is 2^-20 of the size, the rounding about 2^-52 of the distance); a mesh shrunk far below its camera's
 * distance (scale 1e-40 seen from 10 units away) is beyond that, and there a grazing "hit" is rounding
 * noise the tree may not reproduce.
 *
 * Degenerate input: a box bound that overflows float becomes infinite, a NaN bound (a corner at
 * infinity or NaN) becomes the infinite one, and the walk prunes nothing when the root box reaches
 * infinity; the SAH then finds no plane worth its price (costs over an infinite area are NaN) and
 * the seed's rule skips axes without a finite median, so such a mesh gets a shallow tree that is
 * slow but exact. The event sweep advances even past NaN positions (kdtree_events.c).
 *
 * Files: this one is the algorithm; kdtree_sah.h prices a plane and sorts triangles to its sides;
 * kdtree_events.c builds the SAH tree fast; kdtree_check.c checks a tree's invariants for the tests;
 * kdtree_private.h holds what they share, among it the node layout: nodes are 8
 * bytes (pbrt's), the plane as a float, or a leaf's first reference, and one word holding the axis (3
 * for a leaf) in its low two bits and, above them, the index of the far ("above") child or a leaf's
 * triangle count. The near ("below") child always follows its parent. */
#include "kdtree.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "kdtree_private.h"
#include "stats.h"
#include "triangle.h"

/* Depth limit 8 + 1.3 log2(N): deep enough for the heuristic to isolate small triangles, bounded so a
 * degenerate input cannot run away. */
#define KD_MAX_DEPTH_BASE 8.0
#define KD_MAX_DEPTH_PER_LEVEL 1.3

/* SAH nodes with fewer triangles than this are leaves without asking the heuristic. */
#define KD_MIN_SPLIT_COUNT 2

/* The dissertation's rule stops at this many triangles (its BVH stops at one or two). */
#define KD_SEED_LEAF_SIZE 2

/* The dissertation's rule stops at a "pre-defined depth" without giving it. Median planes halve the
 * count, so leaves of one or two triangles are reached at depth log2(N); below that, cuts mostly copy
 * the triangles that straddle them (at 8 + 1.3 log2 N, the SAH's limit, the teapot's 350,000 triangles
 * had 31 references each). We stop at log2(N) + 2. */
#define KD_SEED_EXTRA_DEPTH 2

/* Our addition to the dissertation's rule: a node whose plane would send more than this share of its
 * triangles to both sides becomes a leaf. Without it, large triangles are copied into every leaf below
 * them: 5,000 random triangles gave 608 million references (2.4 GB) at the depth limit. 0.5: the two
 * children then hold at most 1.5 times the parent's references. */
#define KD_SEED_MAX_STRADDLING 0.5

/* Triangle boxes grow by this fraction of the mesh's largest extent: 2^-20, as BVH_BOX_PAD in bvh.c. */
#define KD_BOX_PAD (1.0 / 1048576.0)

/* Needle-thin triangles (the sine of the angle between edges b - a and c - a below this, yet not zero)
 * stay out of the tree and are tested by every ray (see BVH_SLIVER_SINE in bvh.c, the same value). The
 * reason was Moller-Trumbore, whose "hits" on them may lie far outside them; the watertight test that
 * replaced it keeps every hit within rounding of the triangle (triangle.c), so this is now a margin of
 * safety that costs the few slivers of real meshes a test per ray. */
#define KD_SLIVER_SINE 1e-6

/* Tolerance of the t comparisons that prune the walk, relative to the ray's distance from the mesh
 * plus the mesh's size: far above the ~1e-16 rounding of a plane's t, far below any real gap. */
#define KD_T_TOLERANCE 1e-9

/* Faces remembered per ray (a power of two). Most rays test fewer distinct faces than this. */
#define KD_MAILBOX_SIZE 32

/* kdtree_for_each_hit remembers this many reported faces without calling malloc. */
#define KD_HITS_ON_STACK 64

/* ==== the SAH rule, plainly ===================================================================== */

bool kd_sah_may_split(const struct kd_builder *bd, size_t count, size_t depth, const struct fbox *box) {
    return count >= KD_MIN_SPLIT_COUNT && depth < bd->depth_limit && kd_fbox_area(box) > 0.0;
}

/* The SAH's plane for a node over faces[0..count) with region `box`: every bound of every triangle box
 * that lies strictly inside the region is a candidate (between two bounds the counts stay fixed and
 * the cost changes linearly, so the cheapest plane is at a bound), priced with the counts kd_classify
 * gives. The cheapest wins if it beats the leaf; among equal costs the lowest axis, then the lowest
 * position. Returns false for a leaf. O(count^2): kdtree_events.c finds the same plane in one sweep. */
/* TASK 9.2: the surface area heuristic, plainly */
static bool sah_plane(const struct kd_builder *bd, const uint32_t *faces, size_t count, const struct fbox *box,
                      size_t depth, int *best_axis, float *best_split) {
    double best_cost = kd_leaf_cost(count);
    *best_axis = -1;
    if (!kd_sah_may_split(bd, count, depth, box))
        return false;
    double area = kd_fbox_area(box);
    for (int axis = 0; axis < 3; axis++)
        for (size_t k = 0; k < 2 * count; k++) {
            const struct fbox *candidate = &bd->boxes[faces[k / 2]];
            float p = (k % 2 == 0 ? candidate->lo[axis] : candidate->hi[axis]) + 0.0f; /* + 0: no -0 planes */
            if (!(p > box->lo[axis] && p < box->hi[axis]))
                continue;
            size_t left = 0, right = 0;
            for (size_t j = 0; j < count; j++) {
                enum side s = kd_classify(&bd->boxes[faces[j]], axis, p);
                left += (s & SIDE_LEFT) != 0;
                right += (s & SIDE_RIGHT) != 0;
            }
            double cost = kd_sah_cost(box, area, axis, p, left, right);
            if (cost < best_cost || (cost == best_cost && axis == *best_axis && p < *best_split)) {
                best_cost = cost;
                *best_axis = axis;
                *best_split = p;
            }
        }
    return *best_axis >= 0;
}

/* ==== the dissertation's rule =================================================================== */

/* Reorders values[0..n) so that values[nth] is what sorting would put there (quickselect). */
static float select_nth(float *values, size_t n, size_t nth) {
    size_t begin = 0, end = n;
    while (end - begin > 1) {
        float a = values[begin], b = values[begin + (end - begin) / 2], c = values[end - 1];
        float pivot = a < b ? (b < c ? b : (a < c ? c : a)) : (a < c ? a : (b < c ? c : b));
        size_t less = begin, i = begin, greater = end;
        while (i < greater) {
            float v = values[i];
            if (v < pivot) {
                values[i++] = values[less];
                values[less++] = v;
            } else if (v > pivot) {
                values[i] = values[--greater];
                values[greater] = v;
            } else {
                i++;
            }
        }
        if (nth < less)
            end = less;
        else if (nth >= greater)
            begin = greater;
        else
            return pivot;
    }
    return values[nth];
}

/* The seed's plane for a node over faces[0..count) with region `box`: on each axis the median of the
 * triangles' centres (of their boxes clipped to the region); the axis whose plane leaves the most
 * triangles whole wins (ties to x, then y). Returns false for a leaf: at KD_SEED_LEAF_SIZE triangles, at
 * the depth limit, or when more than KD_SEED_MAX_STRADDLING of them would straddle the plane. */
/* TASK 9.1: the dissertation's split rule */
static bool seed_plane(struct kd_builder *bd, const uint32_t *faces, size_t count, const struct fbox *box,
                       size_t depth, int *best_axis, float *best_split) {
    *best_axis = -1;
    size_t best_whole = 0;
    if (count <= KD_SEED_LEAF_SIZE || depth >= bd->depth_limit)
        return false;
    for (int a = 0; a < 3; a++) {
        bool finite = true;
        for (size_t k = 0; k < count; k++) {
            const struct fbox *b = &bd->boxes[faces[k]];
            float lo = b->lo[a] > box->lo[a] ? b->lo[a] : box->lo[a];
            float hi = b->hi[a] < box->hi[a] ? b->hi[a] : box->hi[a];
            bd->centres[k] = 0.5f * lo + 0.5f * hi;
            finite = finite && isfinite(bd->centres[k]);
        }
        if (!finite)
            continue; /* boxes reaching infinity (coordinates beyond float): no median on this axis */
        float split = select_nth(bd->centres, count, count / 2);
        size_t whole = 0;
        for (size_t k = 0; k < count; k++)
            whole += kd_classify(&bd->boxes[faces[k]], a, split) != SIDE_BOTH;
        if (*best_axis < 0 || whole > best_whole) {
            *best_axis = a;
            *best_split = split;
            best_whole = whole;
        }
    }
    /* Too many straddle: cutting would mostly copy them. */
    return !((double)(count - best_whole) > KD_SEED_MAX_STRADDLING * (double)count);
}

/* ==== building, for either rule ================================================================= */

void kd_mark_sides(struct kd_builder *bd, const uint32_t *faces, size_t count, int axis, float split, size_t *left,
                   size_t *right) {
    *left = *right = 0;
    for (size_t k = 0; k < count; k++) {
        enum side s = kd_classify(&bd->boxes[faces[k]], axis, split);
        bd->sides[faces[k]] = (unsigned char)s;
        *left += (s & SIDE_LEFT) != 0;
        *right += (s & SIDE_RIGHT) != 0;
    }
}

/* Builds the subtree of a node over faces[0..count) (owned: freed here) with region `box`, choosing its
 * plane by `rule` (KD_SPLIT_SEED or KD_SPLIT_SAH_PLAIN). Each child gets the faces whose boxes reach its
 * side, in the parent's order. False when memory runs out. */
static bool build(struct kd_builder *bd, enum kd_split rule, uint32_t *faces, size_t count, struct fbox box,
                  size_t depth) {
    uint32_t index = kd_new_node(bd);
    if (index == UINT32_MAX) {
        free(faces);
        return false;
    }
    int axis = -1;
    float split = 0.0f;
    bool cut = rule == KD_SPLIT_SEED ? seed_plane(bd, faces, count, &box, depth, &axis, &split)
                                     : sah_plane(bd, faces, count, &box, depth, &axis, &split);
    if (!cut) {
        kd_count_node(bd, &box, count, true, depth);
        bool ok = kd_make_leaf(bd, index, faces, count);
        free(faces);
        return ok;
    }
    size_t left_count, right_count;
    kd_mark_sides(bd, faces, count, axis, split, &left_count, &right_count);
    uint32_t *left = malloc((left_count ? left_count : 1) * sizeof *left);
    uint32_t *right = malloc((right_count ? right_count : 1) * sizeof *right);
    if (left == NULL || right == NULL) {
        free(left);
        free(right);
        free(faces);
        return false;
    }
    size_t nl = 0, nr = 0;
    for (size_t k = 0; k < count; k++) {
        unsigned char s = bd->sides[faces[k]];
        if (s & SIDE_LEFT)
            left[nl++] = faces[k];
        if (s & SIDE_RIGHT)
            right[nr++] = faces[k];
    }
    free(faces);
    kd_count_node(bd, &box, count, false, depth);
    struct fbox left_box = box, right_box = box;
    left_box.hi[axis] = split;
    right_box.lo[axis] = split;
    if (!build(bd, rule, left, nl, left_box, depth + 1)) {
        free(right);
        return false;
    }
    kd_make_interior(bd, index, axis, split, (uint32_t)bd->node_count);
    return build(bd, rule, right, nr, right_box, depth + 1);
}

/* ==== storing the tree while it is built ======================================================== */

uint32_t kd_new_node(struct kd_builder *bd) {
    if (bd->node_count >= KD_MAX_NODES)
        return UINT32_MAX; /* the index would not fit beside the axis */
    if (bd->node_count == bd->node_capacity) {
        size_t capacity = bd->node_capacity * 2;
        struct kd_node *grown = realloc(bd->nodes, capacity * sizeof *grown);
        if (grown == NULL)
            return UINT32_MAX;
        bd->nodes = grown;
        bd->node_capacity = capacity;
    }
    return (uint32_t)bd->node_count++;
}

/* Appends one face number to refs; false when memory runs out. */
static bool push_ref(struct kd_builder *bd, uint32_t face) {
    if (bd->ref_count == bd->ref_capacity) {
        size_t capacity = bd->ref_capacity * 2;
        if (bd->ref_count >= UINT32_MAX)
            return false; /* leaves index refs with 32 bits */
        uint32_t *grown = realloc(bd->refs, capacity * sizeof *grown);
        if (grown == NULL)
            return false;
        bd->refs = grown;
        bd->ref_capacity = capacity;
    }
    bd->refs[bd->ref_count++] = face;
    return true;
}

/* Adds the node to the tree's shape and to its SAH cost: the cost formula unfolded over the tree. */
void kd_count_node(struct kd_builder *bd, const struct fbox *box, size_t count, bool leaf, size_t depth) {
    double share = bd->root_area > 0.0 ? kd_fbox_area(box) / bd->root_area : 1.0;
    bd->info.nodes++;
    if (!leaf) {
        bd->info.sah_cost += KD_COST_TRAVERSAL * share;
        return;
    }
    bd->info.sah_cost += KD_COST_TRIANGLE * (double)count * share;
    bd->info.leaves++;
    bd->info.empty_leaves += count == 0;
    bd->info.references += count;
    if (depth > bd->info.max_depth)
        bd->info.max_depth = depth;
}

bool kd_make_leaf(struct kd_builder *bd, uint32_t index, const uint32_t *faces, size_t count) {
    bd->nodes[index].first = (uint32_t)bd->ref_count;
    bd->nodes[index].bits = KD_LEAF | (uint32_t)count << 2;
    for (size_t k = 0; k < count; k++)
        if (!push_ref(bd, faces[k]))
            return false;
    return true;
}

void kd_make_interior(struct kd_builder *bd, uint32_t index, int axis, float split, uint32_t above) {
    bd->nodes[index].split = split;
    bd->nodes[index].bits = (uint32_t)axis | above << 2;
}

/* ==== kdtree_build ============================================================================== */

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* The nearest floats below and above x: rounding a box outward keeps every point of it inside. */
static float float_below(double x) {
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float float_above(double x) {
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

bool kd_is_sliver(const struct mesh *m, size_t face) {
    const uint32_t *v = m->faces[face].v;
    vec3 a = m->vertices[v[0]], e1 = vec3_sub(m->vertices[v[1]], a), e2 = vec3_sub(m->vertices[v[2]], a);
    double cross = vec3_length(vec3_cross(e1, e2));
    return cross > 0.0 && cross < KD_SLIVER_SINE * vec3_length(e1) * vec3_length(e2);
}

struct kdtree *kdtree_build(const struct mesh *m, enum kd_split split) {
    double start = now_ms();
    size_t n = m->face_count;
    if (n > KD_MAX_FACES)
        return NULL;
    struct kdtree *k = calloc(1, sizeof *k);
    struct kd_builder bd = {0};
    struct fbox *boxes = kd_alloc_big(n * sizeof *boxes);
    uint32_t *tree_faces = malloc((n ? n : 1) * sizeof *tree_faces);
    bd.sides = malloc(n ? n : 1);
    bd.node_capacity = 64;
    bd.nodes = malloc(bd.node_capacity * sizeof *bd.nodes);
    bd.ref_capacity = n + 64;
    bd.refs = malloc(bd.ref_capacity * sizeof *bd.refs);
    if (k != NULL) {
        k->triangles = kd_alloc_big(n * sizeof *k->triangles);
        k->slivers = malloc((n ? n : 1) * sizeof *k->slivers);
    }
    if (split == KD_SPLIT_SEED)
        bd.centres = malloc((n ? n : 1) * sizeof *bd.centres);
    if (k == NULL || boxes == NULL || tree_faces == NULL || bd.sides == NULL || bd.nodes == NULL ||
        bd.refs == NULL || k->triangles == NULL || k->slivers == NULL || (split == KD_SPLIT_SEED && bd.centres == NULL))
        goto fail;
    bd.boxes = boxes;
    k->face_count = n;

    /* Padded float boxes and their union, the triangles in the form the test wants, and which faces
     * go into the tree (all but the slivers). */
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t f = 0; f < n; f++)
        for (int c = 0; c < 3; c++) {
            lo = vec3_min(lo, m->vertices[m->faces[f].v[c]]);
            hi = vec3_max(hi, m->vertices[m->faces[f].v[c]]);
        }
    vec3 extent = vec3_sub(hi, lo);
    double pad = n > 0 ? KD_BOX_PAD * fmax(extent.x, fmax(extent.y, extent.z)) : 0.0;
    struct fbox root = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    size_t tree = 0;
    for (size_t f = 0; f < n; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
        k->triangles[f] = (struct kd_triangle){a, b, c};
        if (kd_is_sliver(m, f)) {
            k->slivers[k->sliver_count++] = (uint32_t)f;
            continue;
        }
        tree_faces[tree++] = (uint32_t)f;
        vec3 tlo = vec3_min(a, vec3_min(b, c)), thi = vec3_max(a, vec3_max(b, c));
        for (int axis = 0; axis < 3; axis++) {
            /* Clamped both ways: a bound that is not a number (a corner at infinity or NaN, or one the
             * pad made infinite) becomes infinite, so the box still holds the triangle and no plane,
             * count or event made from it is NaN. Finite bounds that overflow float round to infinity. */
            float box_lo = float_below(vec3_axis(tlo, axis) - pad), box_hi = float_above(vec3_axis(thi, axis) + pad);
            boxes[f].lo[axis] = box_lo == box_lo ? box_lo : -INFINITY;
            boxes[f].hi[axis] = box_hi == box_hi ? box_hi : INFINITY;
            root.lo[axis] = boxes[f].lo[axis] < root.lo[axis] ? boxes[f].lo[axis] : root.lo[axis];
            root.hi[axis] = boxes[f].hi[axis] > root.hi[axis] ? boxes[f].hi[axis] : root.hi[axis];
        }
    }
    if (tree == 0)
        root = (struct fbox){{0, 0, 0}, {0, 0, 0}};
    memcpy(k->root_lo, root.lo, sizeof root.lo);
    memcpy(k->root_hi, root.hi, sizeof root.hi);
    k->centre = vec3_make(0.5 * ((double)root.lo[0] + root.hi[0]), 0.5 * ((double)root.lo[1] + root.hi[1]),
                          0.5 * ((double)root.lo[2] + root.hi[2]));
    k->size = vec3_length(vec3_make((double)root.hi[0] - root.lo[0], (double)root.hi[1] - root.lo[1],
                                    (double)root.hi[2] - root.lo[2]));

    bd.root_area = kd_fbox_area(&root);
    double levels = log2((double)(tree > 1 ? tree : 1));
    bool sah = split != KD_SPLIT_SEED;
    bd.depth_limit = sah ? (size_t)(KD_MAX_DEPTH_BASE + KD_MAX_DEPTH_PER_LEVEL * levels)
                         : (size_t)ceil(levels) + KD_SEED_EXTRA_DEPTH;
    assert(bd.depth_limit < KD_STACK_SIZE);
    /* KD_SPLIT_SAH takes the fast road (kdtree_events.c). The plain SAH build first puts its faces in
     * the order the fast one keeps them in, so that the two give the very same tree. */
    bool ok;
    if (split == KD_SPLIT_SAH) {
        ok = kd_build_sah_events(&bd, tree_faces, tree, &root);
        free(tree_faces);
    } else if (split == KD_SPLIT_SAH_PLAIN && !kd_sort_like_events(bd.boxes, tree_faces, tree)) {
        ok = false;
        free(tree_faces);
    } else {
        ok = build(&bd, split, tree_faces, tree, root, 0); /* takes tree_faces */
    }
    tree_faces = NULL;
    if (!ok)
        goto fail;

    k->nodes = bd.nodes;
    k->refs = bd.refs;
    k->info = bd.info;
    k->info.slivers = k->sliver_count;
    k->info.sah_cost += KD_COST_TRIANGLE * (double)k->sliver_count;
    free(boxes);
    free(bd.sides);
    free(bd.centres);
    k->info.build_ms = now_ms() - start;
    return k;

fail:
    free(boxes);
    free(tree_faces);
    free(bd.sides);
    free(bd.centres);
    free(bd.nodes);
    free(bd.refs);
    if (k != NULL) {
        free(k->triangles);
        free(k->slivers);
    }
    free(k);
    return NULL;
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

/* ==== traversal =============================================================================== */

/* Whether the ray's line crosses the triangle, and where: the watertight test (triangle.h) on the ray
 * made ready once per query, the arithmetic triangle_intersect uses, so t is bit-identical to the
 * brute-force loop's. Does not count. */
static inline bool triangle_hit(const struct kd_triangle *tri, const struct triangle_ray *r, double *t) {
    double u, v;
    return triangle_crossing_prepared(tri->a, tri->b, tri->c, r, t, &u, &v);
}

enum query {
    QUERY_CLOSEST, /* nearest hit */
    QUERY_ANY,     /* any hit: stop at the first */
    QUERY_ALL,     /* every hit, each face once */
};

struct query_state {
    double t;      /* QUERY_CLOSEST: best t so far (t_max until something is found) */
    uint32_t face;
    bool found;
    bool (*visit)(void *ctx, double t, uint32_t face); /* QUERY_ALL */
    void *ctx;
    uint32_t *reported; /* QUERY_ALL: faces reported so far */
    size_t reported_count, reported_capacity;
    uint32_t on_stack[KD_HITS_ON_STACK];
};

/* QUERY_ALL: reports face unless it already was; returns false when the walk should stop. */
static bool report_once(struct query_state *q, double t, uint32_t face) {
    for (size_t k = 0; k < q->reported_count; k++)
        if (q->reported[k] == face)
            return true;
    if (q->reported_count == q->reported_capacity) {
        size_t capacity = 2 * q->reported_capacity;
        uint32_t *grown = malloc(capacity * sizeof *grown);
        if (grown == NULL) {
            fprintf(stderr, "kdtree_for_each_hit: out of memory\n");
            abort();
        }
        memcpy(grown, q->reported, q->reported_count * sizeof *grown);
        if (q->reported != q->on_stack)
            free(q->reported);
        q->reported = grown;
        q->reported_capacity = capacity;
    }
    q->reported[q->reported_count++] = face;
    return q->visit(q->ctx, t, face);
}

/* Tests faces[0..count) for query q, skipping (and recording) those in the mailbox when one is
 * given. Returns false when the walk should stop (QUERY_ANY found one, or QUERY_ALL's visit said so). */
static inline __attribute__((always_inline)) bool test_faces(const struct kdtree *k, const struct triangle_ray *r,
                                                             const uint32_t *faces, uint32_t count, double t_min,
                                                             double t_max, enum query kind, struct query_state *q,
                                                             uint32_t *mailbox, uint64_t *tests) {
    for (uint32_t i = 0; i < count; i++) {
        uint32_t face = faces[i];
        if (mailbox != NULL) {
            uint32_t *slot = &mailbox[face & (KD_MAILBOX_SIZE - 1)];
            if (*slot == face)
                continue; /* tested already on this ray */
            *slot = face;
        }
        (*tests)++;
        double t;
        if (!triangle_hit(&k->triangles[face], r, &t) || !(t > t_min && t < t_max))
            continue;
        if (kind == QUERY_ANY) {
            q->found = true;
            return false;
        }
        if (kind == QUERY_ALL) {
            q->found = true;
            if (!report_once(q, t, face))
                return false;
            continue;
        }
        if (!q->found || t < q->t || (t == q->t && face < q->face)) {
            q->found = true;
            q->t = t;
            q->face = face;
        }
    }
    return true;
}

struct stack_entry {
    uint32_t node;
    double t_near, t_far;
};

/* Walks the tree for one query (specialised per kind at compile time), after the slivers. Returns
 * q->found. */
/* TASK 9.3: front-to-back traversal */
static inline __attribute__((always_inline)) bool traverse(const struct kdtree *k, const ray *r, double t_min,
                                                           double t_max, enum query kind, struct query_state *q) {
    q->found = false;
    q->t = t_max;
    double length = vec3_length(r->direction);
    if (k->face_count == 0 || length == 0.0)
        return false; /* a zero direction hits nothing: the triangle test's shear is NaN */
    uint64_t tests = 0;
    struct triangle_ray prepared = triangle_ray_make(r);
    bool running =
        test_faces(k, &prepared, k->slivers, (uint32_t)k->sliver_count, t_min, t_max, kind, q, NULL, &tests);
    stats_thread.triangle_tests += tests;
    if (!running)
        return q->found;
    double origin[3] = {r->origin.x, r->origin.y, r->origin.z};
    double inverse[3] = {1.0 / r->direction.x, 1.0 / r->direction.y, 1.0 / r->direction.z};

    /* Clip to the root box (the NaN-robust slab test of aabb.c, with infinite ends made finite so a ray
     * parallel to a slab and outside it misses). */
    double t_near = t_min > -DBL_MAX ? t_min : -DBL_MAX;
    double t_far = t_max < DBL_MAX ? t_max : DBL_MAX;
    for (int a = 0; a < 3; a++) {
        double t0 = ((double)k->root_lo[a] - origin[a]) * inverse[a];
        double t1 = ((double)k->root_hi[a] - origin[a]) * inverse[a];
        if (inverse[a] < 0.0) {
            double swap = t0;
            t0 = t1;
            t1 = swap;
        }
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    stats_thread.box_tests++;
    if (!(t_near <= t_far))
        return q->found;

    double tolerance = KD_T_TOLERANCE * (vec3_length(vec3_sub(r->origin, k->centre)) + k->size) / length;
    if (!(tolerance < INFINITY))
        tolerance = INFINITY; /* a root box reaching infinity (NaN centre): prune nothing */
    uint32_t mailbox[KD_MAILBOX_SIZE];
    memset(mailbox, 0xff, sizeof mailbox); /* UINT32_MAX: no face */
    struct stack_entry stack[KD_STACK_SIZE];
    int top = 0;
    uint64_t visits = 0;
    tests = 0;
    uint32_t index = 0;
    while (running) {
        const struct kd_node *n = &k->nodes[index];
        visits++;
        uint32_t axis = n->bits & 3u;
        if (axis != KD_LEAF) {
            /* Children in the order the ray meets them: coming from below the plane (direction > 0, or +0
             * with the origin below) it meets "below" (index + 1) first. */
            double t_split = ((double)n->split - origin[axis]) * inverse[axis];
            uint32_t below = index + 1, above = n->bits >> 2;
            bool from_above = inverse[axis] < 0.0;
            uint32_t first = from_above ? above : below, second = from_above ? below : above;
            if (t_split != t_split) {
                /* NaN: the ray runs inside the plane (origin on it, direction 0 on this axis): both sides. */
                stack[top++] = (struct stack_entry){second, t_near, t_far};
                index = first;
            } else if (t_split > t_far + tolerance) {
                index = first; /* the plane lies beyond the ray's stretch in this node */
            } else if (t_split < t_near - tolerance) {
                index = second; /* the ray crossed the plane before entering this node */
            } else {
                double t_cross = t_split < t_near ? t_near : t_split > t_far ? t_far : t_split;
                stack[top++] = (struct stack_entry){second, t_cross, t_far};
                index = first;
                t_far = t_cross;
            }
            continue;
        }

        if (!test_faces(k, &prepared, &k->refs[n->first], n->bits >> 2, t_min, t_max, kind, q, mailbox, &tests))
            break;
        /* Next: the most recently postponed subtree that starts no later than the best hit (give or take
         * the tolerance); those starting beyond it cannot hold anything nearer. */
        running = false;
        while (top > 0) {
            const struct stack_entry *e = &stack[--top];
            if (kind != QUERY_CLOSEST || e->t_near <= q->t + tolerance) {
                index = e->node;
                t_near = e->t_near;
                t_far = e->t_far;
                running = true;
                break;
            }
        }
    }
    stats_thread.node_visits += visits;
    stats_thread.triangle_tests += tests;
    return q->found;
}

bool kdtree_closest(const struct kdtree *k, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    struct query_state q;
    q.face = 0;
    if (!traverse(k, r, t_min, t_max, QUERY_CLOSEST, &q))
        return false;
    *t = q.t;
    *face = q.face;
    return true;
}

bool kdtree_occluded(const struct kdtree *k, const ray *r, double t_min, double t_max) {
    struct query_state q;
    return traverse(k, r, t_min, t_max, QUERY_ANY, &q);
}

void kdtree_for_each_hit(const struct kdtree *k, const ray *r, double t_min, double t_max,
                         bool (*visit)(void *ctx, double t, uint32_t face), void *ctx) {
    struct query_state q;
    q.visit = visit;
    q.ctx = ctx;
    q.reported = q.on_stack;
    q.reported_count = 0;
    q.reported_capacity = KD_HITS_ON_STACK;
    traverse(k, r, t_min, t_max, QUERY_ALL, &q);
    if (q.reported != q.on_stack)
        free(q.reported);
}
