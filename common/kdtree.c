/* kdtree.c: kd-tree, the dissertation's rule and the SAH build, stack traversal with mailboxes (chapter 9).
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
 *    at the depth limit. As in their O(N log N) algorithm the bound planes ("events") are sorted once at
 *    the root (a radix sort), and each split passes its children the events in order, so no node sorts
 *    again.
 *    Triangles are not clipped to the node (their "perfect splits"): a straddling triangle keeps its
 *    whole box in both children, which costs some tree quality and keeps the build simple.
 *
 * The SAH's depth limit is KD_MAX_DEPTH_BASE + KD_MAX_DEPTH_PER_LEVEL * log2(triangles), 8 + 1.3 log2 N
 * as in pbrt and Havran's thesis; the dissertation's rule stops at log2 N + KD_SEED_EXTRA_DEPTH.
 *
 * Traversal: front to back with a stack, the walk the dissertation quotes (its figure 19; Havran's
 * thesis compares the family): at each node the ray's interval [t_near, t_far] is split at the plane's
 * t, the child the ray meets first is visited and the other pushed with its interval. The textbook accepts a hit in a
 * leaf only when it lies inside the leaf's interval, because a straddling triangle's hit may lie in a
 * later leaf, behind something nearer there. Combined with mailboxes (below) that rule loses hits: the
 * triangle rejected in the first leaf is not tested again in the leaf where its hit really is. So here
 * every hit is kept whatever leaf finds it, and a postponed subtree is skipped when it starts after the
 * best hit so far: the first leaf whose interval contains the best hit is still where the search ends,
 * for the same reason.
 *
 * Mailboxes (Amanatides and Woo 1987, per ray as in Havran's thesis): a small direct-mapped array of
 * the last KD_MAILBOX_SIZE faces tested on this ray, so a triangle referenced from several leaves along
 * the ray is mostly tested once. A face evicted from it is tested again at worst, giving the same t
 * and changing nothing for the nearest hit; kdtree_for_each_hit also keeps a list of the faces it has
 * reported, so it reports each once.
 *
 * Exact agreement with the brute-force loop, as in bvh.c: triangles are tested with triangle_intersect's
 * arithmetic on the very corners the mesh holds (same t to the last bit); every triangle's
 * box is grown by KD_BOX_PAD times the mesh's size, so that a ray that Moller-Trumbore's rounding
 * calls a hit is always in a leaf holding the triangle; needle-thin triangles (KD_SLIVER_SINE) stay out
 * of the tree and are tested by every ray; and the t comparisons that prune the walk allow a tolerance
 * of KD_T_TOLERANCE (relative to the distances involved) for the rounding of the planes' t. Ties go to
 * the lowest face index, as in the brute-force loop.
 *
 * Tuning constants: KD_COST_TRAVERSAL 2, KD_COST_TRIANGLE 1, KD_EMPTY_BONUS 0.2, KD_MIN_SPLIT_COUNT
 * 2, KD_SEED_LEAF_SIZE 2, KD_SEED_MAX_STRADDLING 0.5, KD_SEED_EXTRA_DEPTH 2, depth 8 + 1.3 log2 N (SAH),
 * KD_BOX_PAD 2^-20, KD_T_TOLERANCE 1e-9, KD_MAILBOX_SIZE 32, KD_SLIVER_SINE 1e-6.
 *
 * Layout: nodes are 8 bytes (pbrt's): the plane as a float, or a leaf's first reference, and one word
 * holding the axis (3 for a leaf) in its low two bits and, above them, the index of the far ("above")
 * child or a leaf's triangle count. The near ("below") child always follows its parent. */
#include "kdtree.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

#include "stats.h"
#include "triangle.h"

/* Relative costs of one node step and one triangle test, as the heuristic sees them. A node step is
 * fewer operations than a triangle test, but each one waits for a node from memory; on the bench
 * models (bench_accel, 1:1.5 to 2:1 tried) frame times hardly moved while 2:1 built the smallest trees
 * fastest: without clipping, cheap steps let the heuristic cut below the size of the triangles and
 * copy each into many leaves. */
#define KD_COST_TRAVERSAL 2.0
#define KD_COST_TRIANGLE 1.0

/* A split leaving one side empty costs this fraction less: empty space is cut off cheaply and lets
 * rays leave the tree early. Wald and Havran use 0.2 (their lambda = 0.8). */
#define KD_EMPTY_BONUS 0.2

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
 * stay out of the tree and are tested by every ray: their Moller-Trumbore "hits" may lie far outside
 * them (see BVH_SLIVER_SINE in bvh.c, the same value and reasons). */
#define KD_SLIVER_SINE 1e-6

/* Tolerance of the t comparisons that prune the walk, relative to the ray's distance from the mesh
 * plus the mesh's size: far above the ~1e-16 rounding of a plane's t, far below any real gap. */
#define KD_T_TOLERANCE 1e-9

/* Faces remembered per ray (a power of two). Most rays test fewer distinct faces than this. */
#define KD_MAILBOX_SIZE 32

/* The walk's stack holds at most one entry per level: 64 > 8 + 1.3 * 30, the depth limit for the
 * largest mesh accepted (KD_MAX_FACES). */
#define KD_STACK_SIZE 64
#define KD_MAX_FACES ((size_t)1 << 30)
#define KD_MAX_NODES ((size_t)1 << 30) /* node indices share a word with the axis */

/* kdtree_for_each_hit remembers this many reported faces without calling malloc. */
#define KD_HITS_ON_STACK 64

#define KD_LEAF 3u /* the axis field of a leaf */

struct kd_node {
    union {
        float split;    /* interior: the plane's position on its axis */
        uint32_t first; /* leaf: index of its first entry in refs */
    };
    uint32_t bits; /* low 2 bits: axis 0-2, or KD_LEAF; the rest: the above child's index, or a leaf's count */
};

_Static_assert(sizeof(struct kd_node) == 8, "kd-tree nodes are meant to be 8 bytes");

/* A triangle as the intersection test wants it (see bvh.c). */
struct kd_triangle {
    vec3 a, b, c;
};

struct kdtree {
    struct kd_node *nodes;          /* [0] is the root */
    uint32_t *refs;                 /* leaves' face numbers, leaf after leaf */
    struct kd_triangle *triangles;  /* indexed by face number */
    size_t face_count;
    uint32_t *slivers;              /* faces kept out of the tree (KD_SLIVER_SINE), sliver_count of them */
    size_t sliver_count;
    float root_lo[3], root_hi[3];   /* box of all padded triangle boxes */
    vec3 centre;                    /* of the root box */
    double size;                    /* length of the root box's diagonal */
    struct kdtree_info info;
};

/* ==== memory ================================================================================== */

/* Arrays of 2 MB or more are aligned to 2 MB and the kernel is asked for 2 MB pages (see alloc_big in
 * bvh.c: first-touch page faults dominated the build on a virtual machine; here the event lists of
 * the top levels are made afresh at every level). NULL when memory runs out; release with free(). */
#define KD_HUGE_PAGE ((size_t)1 << 21)

static void *alloc_big(size_t bytes) {
    if (bytes < KD_HUGE_PAGE)
        return malloc(bytes ? bytes : 1);
    size_t rounded = (bytes + KD_HUGE_PAGE - 1) / KD_HUGE_PAGE * KD_HUGE_PAGE;
    void *p = aligned_alloc(KD_HUGE_PAGE, rounded);
#if defined(MADV_HUGEPAGE)
    if (p != NULL)
        madvise(p, rounded, MADV_HUGEPAGE); /* only a hint: failure changes nothing */
#endif
    return p;
}

/* ==== building ================================================================================ */

struct fbox {
    float lo[3], hi[3];
};

static double fbox_area(const struct fbox *b) {
    double ex = (double)b->hi[0] - b->lo[0], ey = (double)b->hi[1] - b->lo[1], ez = (double)b->hi[2] - b->lo[2];
    if (!(ex >= 0.0 && ey >= 0.0 && ez >= 0.0))
        return 0.0;
    return 2.0 * (ex * ey + ey * ez + ez * ex);
}

static float float_below(double x) {
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float float_above(double x) {
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* Which sides of the plane `split` on `axis` a triangle box goes to. */
enum side { SIDE_LEFT = 1, SIDE_RIGHT = 2, SIDE_BOTH = 3 };

/* Left when the box starts before the plane, right when it reaches past it, both when it lies flat in
 * the plane: every triangle goes somewhere. (Padded boxes are never flat; only a mesh of zero size,
 * whose pad is 0, has flat boxes.) */
static enum side classify(const struct fbox *b, int axis, float split) {
    bool flat_in_plane = b->lo[axis] == split && b->hi[axis] == split;
    bool left = b->lo[axis] < split || flat_in_plane;
    bool right = b->hi[axis] > split || flat_in_plane;
    return (left ? SIDE_LEFT : 0) | (right ? SIDE_RIGHT : 0);
}

/* A bound plane of one triangle box, for the SAH sweep. Sorted by position, and at one position ends
 * before flat boxes before starts: the order in which the sweep must count them. */
enum event_type { EVENT_END = 0, EVENT_PLANAR = 1, EVENT_START = 2 };

struct kd_event {
    float position;
    uint32_t key; /* face << 2 | event_type */
};

/* The order the sweep needs, as one unsigned 64-bit number: the position's bits made to sort like the
 * floats they are (negative numbers flipped, the sign bit set on the others), then the type, then the
 * face (below 2^30, KD_MAX_FACES). Positions are never -0 (see push_events). */
static uint64_t event_order(const struct kd_event *e) {
    uint32_t bits;
    memcpy(&bits, &e->position, sizeof bits);
    bits = bits & 0x80000000u ? ~bits : bits | 0x80000000u;
    return (uint64_t)bits << 32 | (uint64_t)(e->key & 3u) << 30 | e->key >> 2;
}

/* Sorts events[0..n) by event_order: a least-significant-digit radix sort, four passes of 16 bits,
 * each a counting sort (stable) into the other buffer; O(n), where qsort was a quarter of the build.
 * False when memory runs out (the events are then unsorted). */
static bool sort_events(struct kd_event *events, size_t n) {
    struct kd_event *other = alloc_big(n * sizeof *other);
    size_t *count = malloc(((size_t)1 << 16) * sizeof *count);
    if (other == NULL || count == NULL) {
        free(other);
        free(count);
        return false;
    }
    struct kd_event *from = events, *to = other;
    for (int shift = 0; shift < 64; shift += 16) {
        memset(count, 0, ((size_t)1 << 16) * sizeof *count);
        for (size_t i = 0; i < n; i++)
            count[event_order(&from[i]) >> shift & 0xffffu]++;
        size_t start = 0;
        for (size_t d = 0; d < (size_t)1 << 16; d++) {
            size_t c = count[d];
            count[d] = start;
            start += c;
        }
        for (size_t i = 0; i < n; i++)
            to[count[event_order(&from[i]) >> shift & 0xffffu]++] = from[i];
        struct kd_event *swap = from;
        from = to;
        to = swap;
    }
    /* After an even number of passes the result is back in events. */
    free(other);
    free(count);
    return true;
}

struct kd_builder {
    const struct fbox *boxes; /* per face, padded */
    unsigned char *sides;     /* per face, scratch: enum side of the node being split */
    float *centres;           /* per face, scratch for the dissertation's rule */
    struct kd_node *nodes;
    size_t node_count, node_capacity;
    uint32_t *refs;
    size_t ref_count, ref_capacity;
    size_t depth_limit;
    double root_area;
    struct kdtree_info info; /* counted while building */
};

/* Appends an uninitialised node; returns its index, or UINT32_MAX when memory runs out. */
static uint32_t new_node(struct kd_builder *bd) {
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

/* Counts a node with box `box` into the tree's SAH cost and shape. */
static void count_node(struct kd_builder *bd, const struct fbox *box, size_t count, bool leaf, size_t depth) {
    double share = bd->root_area > 0.0 ? fbox_area(box) / bd->root_area : 1.0;
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

/* Makes nodes[index] a leaf over faces[0..count). */
static bool make_leaf(struct kd_builder *bd, uint32_t index, const uint32_t *faces, size_t count) {
    bd->nodes[index].first = (uint32_t)bd->ref_count;
    bd->nodes[index].bits = KD_LEAF | (uint32_t)count << 2;
    for (size_t k = 0; k < count; k++)
        if (!push_ref(bd, faces[k]))
            return false;
    return true;
}

/* Makes nodes[index] an interior node; its below child must be index + 1. */
static void make_interior(struct kd_builder *bd, uint32_t index, int axis, float split, uint32_t above) {
    bd->nodes[index].split = split;
    bd->nodes[index].bits = (uint32_t)axis | above << 2;
}

/* ---- the SAH rule ------------------------------------------------------------------------------ */

/* Builds the subtree of a node holding `count` triangles whose sorted events per axis are
 * events[a][0..event_count[a]); takes ownership of (frees) the event arrays. False on out of memory. */
static bool build_sah(struct kd_builder *bd, struct kd_event *events[3], size_t event_count[3], size_t count,
                      struct fbox box, size_t depth) {
    uint32_t index = new_node(bd);
    bool ok = index != UINT32_MAX;
    double area = fbox_area(&box);
    double best_cost = KD_COST_TRIANGLE * (double)count; /* the leaf's */
    int best_axis = -1;
    float best_split = 0.0f;
    if (ok && count >= KD_MIN_SPLIT_COUNT && depth < bd->depth_limit && area > 0.0) {
        for (int a = 0; a < 3; a++) {
            const struct kd_event *e = events[a];
            size_t n = event_count[a], left = 0, right = count;
            double extent[3] = {(double)box.hi[0] - box.lo[0], (double)box.hi[1] - box.lo[1],
                                (double)box.hi[2] - box.lo[2]};
            int b = (a + 1) % 3, c = (a + 2) % 3;
            for (size_t i = 0; i < n;) {
                float p = e[i].position;
                size_t ends = 0, planars = 0, starts = 0;
                for (; i < n && e[i].position == p && (e[i].key & 3u) == EVENT_END; i++)
                    ends++;
                for (; i < n && e[i].position == p && (e[i].key & 3u) == EVENT_PLANAR; i++)
                    planars++;
                for (; i < n && e[i].position == p && (e[i].key & 3u) == EVENT_START; i++)
                    starts++;
                right -= ends + planars;
                if (p > box.lo[a] && p < box.hi[a]) {
                    /* flat boxes in the plane go both ways (classify) */
                    size_t left_here = left + planars, right_here = right + planars;
                    double below = (double)p - box.lo[a], above = (double)box.hi[a] - p;
                    double cross = extent[b] * extent[c], side = extent[b] + extent[c];
                    double area_left = 2.0 * (cross + below * side), area_right = 2.0 * (cross + above * side);
                    double bonus = left_here == 0 || right_here == 0 ? 1.0 - KD_EMPTY_BONUS : 1.0;
                    double cost = KD_COST_TRAVERSAL + KD_COST_TRIANGLE * bonus *
                                                          (area_left * left_here + area_right * right_here) / area;
                    if (cost < best_cost) {
                        best_cost = cost;
                        best_axis = a;
                        best_split = p;
                    }
                }
                left += starts + planars;
            }
        }
    }

    /* The node's faces, once each: the start (or flat) events of axis 0. */
    uint32_t *faces = ok ? malloc((count ? count : 1) * sizeof *faces) : NULL;
    ok = ok && faces != NULL;
    size_t listed = 0;
    for (size_t i = 0; ok && i < event_count[0]; i++)
        if ((events[0][i].key & 3u) != EVENT_END)
            faces[listed++] = events[0][i].key >> 2;
    assert(!ok || listed == count);

    if (!ok || best_axis < 0) {
        for (int a = 0; a < 3; a++)
            free(events[a]);
        if (ok) {
            count_node(bd, &box, count, true, depth);
            ok = make_leaf(bd, index, faces, count);
        }
        free(faces);
        return ok;
    }

    size_t left_count = 0, right_count = 0;
    for (size_t k = 0; k < count; k++) {
        enum side s = classify(&bd->boxes[faces[k]], best_axis, best_split);
        bd->sides[faces[k]] = (unsigned char)s;
        left_count += (s & SIDE_LEFT) != 0;
        right_count += (s & SIDE_RIGHT) != 0;
    }
    free(faces);

    /* Each child gets, per axis, the events of its faces in the parent's (sorted) order. */
    struct kd_event *left_events[3] = {NULL, NULL, NULL}, *right_events[3] = {NULL, NULL, NULL};
    size_t left_n[3] = {0, 0, 0}, right_n[3] = {0, 0, 0};
    for (int a = 0; a < 3; a++) {
        size_t to_left = 0, to_right = 0;
        for (size_t i = 0; i < event_count[a]; i++) {
            unsigned char s = bd->sides[events[a][i].key >> 2];
            to_left += (s & SIDE_LEFT) != 0;
            to_right += (s & SIDE_RIGHT) != 0;
        }
        left_events[a] = alloc_big(to_left * sizeof **left_events);
        right_events[a] = alloc_big(to_right * sizeof **right_events);
        ok = ok && left_events[a] != NULL && right_events[a] != NULL;
        for (size_t i = 0; ok && i < event_count[a]; i++) {
            unsigned char s = bd->sides[events[a][i].key >> 2];
            if (s & SIDE_LEFT)
                left_events[a][left_n[a]++] = events[a][i];
            if (s & SIDE_RIGHT)
                right_events[a][right_n[a]++] = events[a][i];
        }
        free(events[a]);
    }
    if (!ok) {
        for (int a = 0; a < 3; a++) {
            free(left_events[a]);
            free(right_events[a]);
        }
        return false;
    }

    count_node(bd, &box, count, false, depth);
    struct fbox left_box = box, right_box = box;
    left_box.hi[best_axis] = best_split;
    right_box.lo[best_axis] = best_split;
    if (!build_sah(bd, left_events, left_n, left_count, left_box, depth + 1)) {
        for (int a = 0; a < 3; a++)
            free(right_events[a]);
        return false;
    }
    make_interior(bd, index, best_axis, best_split, (uint32_t)bd->node_count);
    return build_sah(bd, right_events, right_n, right_count, right_box, depth + 1);
}

/* Sorts the events of faces[0..count) along every axis and builds the SAH tree over them. */
static bool build_sah_root(struct kd_builder *bd, const uint32_t *faces, size_t count, const struct fbox *root) {
    struct kd_event *events[3];
    size_t event_count[3];
    bool ok = true;
    for (int a = 0; a < 3; a++) {
        events[a] = alloc_big((2 * count + 1) * sizeof **events);
        ok = ok && events[a] != NULL;
        event_count[a] = 0;
        for (size_t i = 0; ok && i < count; i++) {
            const struct fbox *b = &bd->boxes[faces[i]];
            uint32_t key = faces[i] << 2;
            float lo = b->lo[a] + 0.0f, hi = b->hi[a] + 0.0f; /* + 0: -0 becomes +0, for event_order */
            if (lo == hi) {
                events[a][event_count[a]++] = (struct kd_event){lo, key | EVENT_PLANAR};
            } else {
                events[a][event_count[a]++] = (struct kd_event){lo, key | EVENT_START};
                events[a][event_count[a]++] = (struct kd_event){hi, key | EVENT_END};
            }
        }
        ok = ok && sort_events(events[a], event_count[a]);
    }
    if (!ok) {
        for (int a = 0; a < 3; a++)
            free(events[a]);
        return false;
    }
    return build_sah(bd, events, event_count, count, *root, 0);
}

/* ---- the dissertation's rule ------------------------------------------------------------------- */

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

/* Builds the subtree of a node over faces[0..count) (owned: freed here) with box `box`. */
static bool build_seed(struct kd_builder *bd, uint32_t *faces, size_t count, struct fbox box, size_t depth) {
    uint32_t index = new_node(bd);
    if (index == UINT32_MAX) {
        free(faces);
        return false;
    }
    int best_axis = -1;
    float best_split = 0.0f;
    size_t best_whole = 0;
    if (count > KD_SEED_LEAF_SIZE && depth < bd->depth_limit) {
        for (int a = 0; a < 3; a++) {
            for (size_t k = 0; k < count; k++) {
                const struct fbox *b = &bd->boxes[faces[k]];
                float lo = b->lo[a] > box.lo[a] ? b->lo[a] : box.lo[a];
                float hi = b->hi[a] < box.hi[a] ? b->hi[a] : box.hi[a];
                bd->centres[k] = 0.5f * lo + 0.5f * hi;
            }
            float split = select_nth(bd->centres, count, count / 2);
            size_t whole = 0;
            for (size_t k = 0; k < count; k++)
                whole += classify(&bd->boxes[faces[k]], a, split) != SIDE_BOTH;
            if (best_axis < 0 || whole > best_whole) {
                best_axis = a;
                best_split = split;
                best_whole = whole;
            }
        }
    }
    size_t left_count = 0, right_count = 0;
    if (best_axis >= 0) {
        for (size_t k = 0; k < count; k++) {
            enum side s = classify(&bd->boxes[faces[k]], best_axis, best_split);
            bd->sides[faces[k]] = (unsigned char)s;
            left_count += (s & SIDE_LEFT) != 0;
            right_count += (s & SIDE_RIGHT) != 0;
        }
        if ((double)(left_count + right_count - count) > KD_SEED_MAX_STRADDLING * (double)count)
            best_axis = -1; /* too many straddle: cutting would mostly copy them */
    }
    if (best_axis < 0) {
        count_node(bd, &box, count, true, depth);
        bool ok = make_leaf(bd, index, faces, count);
        free(faces);
        return ok;
    }
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
    count_node(bd, &box, count, false, depth);
    struct fbox left_box = box, right_box = box;
    left_box.hi[best_axis] = best_split;
    right_box.lo[best_axis] = best_split;
    if (!build_seed(bd, left, nl, left_box, depth + 1)) {
        free(right);
        return false;
    }
    make_interior(bd, index, best_axis, best_split, (uint32_t)bd->node_count);
    return build_seed(bd, right, nr, right_box, depth + 1);
}

/* ---- kdtree_build -------------------------------------------------------------------------------- */

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* True for a face of m that KD_SLIVER_SINE keeps out of the tree. */
static bool is_sliver(const struct mesh *m, size_t face) {
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
    struct fbox *boxes = alloc_big(n * sizeof *boxes);
    uint32_t *tree_faces = malloc((n ? n : 1) * sizeof *tree_faces);
    bd.sides = malloc(n ? n : 1);
    bd.node_capacity = 64;
    bd.nodes = malloc(bd.node_capacity * sizeof *bd.nodes);
    bd.ref_capacity = n + 64;
    bd.refs = malloc(bd.ref_capacity * sizeof *bd.refs);
    if (k != NULL) {
        k->triangles = alloc_big(n * sizeof *k->triangles);
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
        if (is_sliver(m, f)) {
            k->slivers[k->sliver_count++] = (uint32_t)f;
            continue;
        }
        tree_faces[tree++] = (uint32_t)f;
        vec3 tlo = vec3_min(a, vec3_min(b, c)), thi = vec3_max(a, vec3_max(b, c));
        for (int axis = 0; axis < 3; axis++) {
            boxes[f].lo[axis] = float_below(vec3_axis(tlo, axis) - pad);
            boxes[f].hi[axis] = float_above(vec3_axis(thi, axis) + pad);
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

    bd.root_area = fbox_area(&root);
    double levels = log2((double)(tree > 1 ? tree : 1));
    bd.depth_limit = split == KD_SPLIT_SAH ? (size_t)(KD_MAX_DEPTH_BASE + KD_MAX_DEPTH_PER_LEVEL * levels)
                                           : (size_t)ceil(levels) + KD_SEED_EXTRA_DEPTH;
    assert(bd.depth_limit < KD_STACK_SIZE);
    bool ok;
    if (split == KD_SPLIT_SAH) {
        ok = build_sah_root(&bd, tree_faces, tree, &root);
        free(tree_faces);
    } else {
        ok = build_seed(&bd, tree_faces, tree, root, 0); /* takes tree_faces */
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

/* ==== checking ================================================================================ */

struct check {
    const struct kdtree *k;
    unsigned char *seen_node;
    char *why;
    size_t why_size;
};

static bool check_fail(struct check *c, const char *message, size_t where) {
    snprintf(c->why, c->why_size, "%s (at %zu)", message, where);
    return false;
}

/* Checks the shape of the subtree at index: indices in range, each node reached once. */
static bool check_shape(struct check *c, uint32_t index, size_t depth) {
    const struct kdtree *k = c->k;
    if (depth >= KD_STACK_SIZE)
        return check_fail(c, "deeper than the traversal stack", depth);
    if (index >= k->info.nodes || c->seen_node[index]++)
        return check_fail(c, "node index out of range or reached twice", index);
    const struct kd_node *n = &k->nodes[index];
    if ((n->bits & 3u) == KD_LEAF) {
        if ((size_t)n->first + (n->bits >> 2) > k->info.references)
            return check_fail(c, "leaf runs past the references", index);
        for (uint32_t i = 0; i < n->bits >> 2; i++)
            if (k->refs[n->first + i] >= k->face_count)
                return check_fail(c, "reference to a face that does not exist", index);
        return true;
    }
    if (!(n->bits >> 2 > index + 1))
        return check_fail(c, "above child not after the below child", index);
    return check_shape(c, index + 1, depth + 1) && check_shape(c, n->bits >> 2, depth + 1);
}

/* Checks that face is in every leaf under index whose region touches the box [lo, hi]. */
static bool check_face(struct check *c, uint32_t index, uint32_t face, const double lo[3], const double hi[3]) {
    const struct kd_node *n = &c->k->nodes[index];
    uint32_t axis = n->bits & 3u;
    if (axis == KD_LEAF) {
        for (uint32_t i = 0; i < n->bits >> 2; i++)
            if (c->k->refs[n->first + i] == face)
                return true;
        return check_fail(c, "face missing from a leaf its box touches", face);
    }
    if (lo[axis] <= n->split && !check_face(c, index + 1, face, lo, hi))
        return false;
    return !(hi[axis] >= n->split) || check_face(c, n->bits >> 2, face, lo, hi);
}

bool kdtree_is_valid(const struct kdtree *k, const struct mesh *m, char *why, size_t why_size) {
    struct check c = {k, calloc(k->info.nodes + 1, 1), why, why_size};
    if (c.seen_node == NULL) {
        snprintf(why, why_size, "out of memory");
        return false;
    }
    bool ok = true;
    if (k->face_count != m->face_count)
        ok = check_fail(&c, "face count differs from the mesh's", k->face_count);
    if (ok && k->face_count > 0) {
        ok = check_shape(&c, 0, 0);
        for (size_t i = 0; ok && i < k->info.nodes; i++)
            if (!c.seen_node[i])
                ok = check_fail(&c, "node not reachable from the root", i);
    }
    for (size_t i = 0; ok && i < k->sliver_count; i++)
        if (k->slivers[i] >= k->face_count || !is_sliver(m, k->slivers[i]) || (i > 0 && k->slivers[i] <= k->slivers[i - 1]))
            ok = check_fail(&c, "sliver list wrong", i);
    size_t slivers_seen = 0;
    for (uint32_t f = 0; ok && f < k->face_count; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], b1 = m->vertices[v[1]], c2 = m->vertices[v[2]];
        const struct kd_triangle *t = &k->triangles[f];
        if (memcmp(&t->a, &a, sizeof a) != 0 || memcmp(&t->b, &b1, sizeof b1) != 0 ||
            memcmp(&t->c, &c2, sizeof c2) != 0) {
            ok = check_fail(&c, "stored triangle differs from its face", f);
            break;
        }
        if (is_sliver(m, f)) {
            slivers_seen++;
            continue; /* not in the tree */
        }
        double lo[3], hi[3];
        for (int axis = 0; axis < 3; axis++) {
            double x0 = vec3_axis(a, axis), x1 = vec3_axis(m->vertices[v[1]], axis), x2 = vec3_axis(m->vertices[v[2]], axis);
            lo[axis] = fmin(x0, fmin(x1, x2));
            hi[axis] = fmax(x0, fmax(x1, x2));
            if (!(lo[axis] >= k->root_lo[axis] && hi[axis] <= k->root_hi[axis]))
                ok = check_fail(&c, "root box does not hold a triangle", f);
        }
        ok = ok && check_face(&c, 0, f, lo, hi);
    }
    if (ok && slivers_seen != k->sliver_count)
        ok = check_fail(&c, "sliver count wrong", slivers_seen);
    free(c.seen_node);
    return ok;
}

/* ==== traversal =============================================================================== */

/* Whether r's line crosses the triangle, and where: triangle_crossing (triangle.h), the arithmetic
 * triangle_intersect uses, so t is bit-identical to the brute-force loop's. Does not count. */
static inline bool triangle_hit(const struct kd_triangle *tri, const ray *r, double *t) {
    double u, v;
    return triangle_crossing(tri->a, tri->b, tri->c, r, t, &u, &v);
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
static inline __attribute__((always_inline)) bool test_faces(const struct kdtree *k, const ray *r,
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
static inline __attribute__((always_inline)) bool traverse(const struct kdtree *k, const ray *r, double t_min,
                                                           double t_max, enum query kind, struct query_state *q) {
    q->found = false;
    q->t = t_max;
    double length = vec3_length(r->direction);
    if (k->face_count == 0 || length == 0.0)
        return false; /* a zero direction hits nothing: Moller-Trumbore's determinant is 0 */
    uint64_t tests = 0;
    bool running = test_faces(k, r, k->slivers, (uint32_t)k->sliver_count, t_min, t_max, kind, q, NULL, &tests);
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

        if (!test_faces(k, r, &k->refs[n->first], n->bits >> 2, t_min, t_max, kind, q, mailbox, &tests))
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
