/* kdtree_events.c: the SAH kd-tree built fast, by the sorted-event sweep of Wald and Havran (chapter 9).
 *
 * kdtree.c builds the SAH tree plainly: at every node, every bound of every triangle box is a candidate
 * plane, and each candidate counts the triangles on its two sides by looking at all of them, O(N^2) per
 * node. This file builds the very same tree (same planes, same leaves, same order of faces in each leaf;
 * the tests compare the two node by node) in O(N log N), as in Wald and Havran, "On building fast
 * kd-trees for ray tracing, and on doing that in O(N log N)" (IEEE RT 2006), section 4:
 *
 *  - Each triangle box gives, per axis, an "event" at each of its two bounds: a start at lo, an end at
 *    hi, or one planar event when lo = hi. Sorted by position (and, at one position, ends before planar
 *    events before starts), one sweep over a node's events counts, for every candidate plane at once,
 *    the triangles on each side: the counts change only at events.
 *  - The events are sorted once, at the root (a radix sort), and each split hands its children the
 *    events of their own faces, filtered in order, so no node sorts again.
 *
 * Ties: the sweep prices candidates in the order axis, then position, and keeps a new plane only when
 * it is strictly cheaper: the first cheapest, as in kdtree.c's plain search. A leaf lists its faces in
 * the order of their start (or planar) events on axis 0, which kdtree.c's plain build reproduces by
 * sorting its root list the same way. */
#include "kdtree_private.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

/* ==== memory ================================================================================== */

/* Arrays of 2 MB or more are aligned to 2 MB and the kernel is asked for 2 MB pages: first-touch page
 * faults dominated the build on a virtual machine, and the event lists of the top levels are made
 * afresh at every level. NULL when memory runs out; release with free(). */
#define KD_HUGE_PAGE ((size_t)1 << 21)

void *kd_alloc_big(size_t bytes) {
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

/* ==== events ================================================================================== */

/* A bound plane of one triangle box, for the SAH sweep. Sorted by position, and at one position ends
 * before flat boxes before starts: the order in which the sweep must count them. */
enum event_type { EVENT_END = 0, EVENT_PLANAR = 1, EVENT_START = 2 };

struct kd_event {
    float position;
    uint32_t key; /* face << 2 | event_type */
};

/* The bits of a position: equal for equal positions (never -0, see event_order), and for a NaN too. */
static inline uint32_t position_bits(float position) {
    uint32_t bits;
    memcpy(&bits, &position, sizeof bits);
    return bits;
}

/* The order the sweep needs, as one unsigned 64-bit number: the position's bits made to sort like the
 * floats they are (negative numbers flipped, the sign bit set on the others), then the type, then the
 * face (below 2^30, KD_MAX_FACES). Positions are never -0 (kd_build_sah_events adds +0 to each). */
static uint64_t event_order(const struct kd_event *e) {
    uint32_t bits = position_bits(e->position);
    bits = bits & 0x80000000u ? ~bits : bits | 0x80000000u;
    return (uint64_t)bits << 32 | (uint64_t)(e->key & 3u) << 30 | e->key >> 2;
}

/* Sorts events[0..n) by event_order: a least-significant-digit radix sort, four passes of 16 bits,
 * each a counting sort (stable) into the other buffer; O(n), where qsort was a quarter of the build.
 * False when memory runs out (the events are then unsorted). */
static bool sort_events(struct kd_event *events, size_t n) {
    struct kd_event *other = kd_alloc_big(n * sizeof *other);
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

/* ==== the sweep ================================================================================ */

/* Builds the subtree of a node holding `count` triangles whose sorted events per axis are
 * events[a][0..event_count[a]); takes ownership of (frees) the event arrays. False on out of memory. */
static bool build_sah(struct kd_builder *bd, struct kd_event *events[3], size_t event_count[3], size_t count,
                      struct fbox box, size_t depth) {
    uint32_t index = kd_new_node(bd);
    bool ok = index != UINT32_MAX;
    double best_cost = kd_leaf_cost(count);
    int best_axis = -1;
    float best_split = 0.0f;
    if (ok && kd_sah_may_split(bd, count, depth, &box)) {
        double area = kd_fbox_area(&box);
        for (int a = 0; a < 3; a++) {
            const struct kd_event *e = events[a];
            size_t n = event_count[a], left = 0, right = count;
            for (size_t i = 0; i < n;) {
                /* The events at position p: ends, then flat boxes, then starts. Positions are compared
                 * by their bits, so e[i] itself is always taken by one of the three loops (whatever its
                 * type) and the sweep advances even past a NaN, which == would never match. */
                float p = e[i].position;
                uint32_t at = position_bits(p);
                size_t ends = 0, planars = 0, starts = 0;
                for (; i < n && position_bits(e[i].position) == at && (e[i].key & 3u) == EVENT_END; i++)
                    ends++;
                for (; i < n && position_bits(e[i].position) == at && (e[i].key & 3u) == EVENT_PLANAR; i++)
                    planars++;
                for (; i < n && position_bits(e[i].position) == at && (e[i].key & 3u) == EVENT_START; i++)
                    starts++;
                right -= ends + planars;
                if (p > box.lo[a] && p < box.hi[a]) {
                    /* flat boxes in the plane go both ways (kd_classify) */
                    double cost = kd_sah_cost(&box, area, a, p, left + planars, right + planars);
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
            kd_count_node(bd, &box, count, true, depth);
            ok = kd_make_leaf(bd, index, faces, count);
        }
        free(faces);
        return ok;
    }

    size_t left_count, right_count;
    kd_mark_sides(bd, faces, count, best_axis, best_split, &left_count, &right_count);
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
        left_events[a] = kd_alloc_big(to_left * sizeof **left_events);
        right_events[a] = kd_alloc_big(to_right * sizeof **right_events);
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

    kd_count_node(bd, &box, count, false, depth);
    struct fbox left_box = box, right_box = box;
    left_box.hi[best_axis] = best_split;
    right_box.lo[best_axis] = best_split;
    if (!build_sah(bd, left_events, left_n, left_count, left_box, depth + 1)) {
        for (int a = 0; a < 3; a++)
            free(right_events[a]);
        return false;
    }
    kd_make_interior(bd, index, best_axis, best_split, (uint32_t)bd->node_count);
    return build_sah(bd, right_events, right_n, right_count, right_box, depth + 1);
}

bool kd_build_sah_events(struct kd_builder *bd, const uint32_t *faces, size_t count, const struct fbox *root) {
    /* Every face's events along every axis, sorted once. */
    struct kd_event *events[3];
    size_t event_count[3];
    bool ok = true;
    for (int a = 0; a < 3; a++) {
        events[a] = kd_alloc_big((2 * count + 1) * sizeof **events);
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


bool kd_sort_like_events(const struct fbox *boxes, uint32_t *faces, size_t count) {
    struct kd_event *events = kd_alloc_big((count ? count : 1) * sizeof *events);
    if (events == NULL)
        return false;
    for (size_t i = 0; i < count; i++) {
        const struct fbox *b = &boxes[faces[i]];
        float lo = b->lo[0] + 0.0f, hi = b->hi[0] + 0.0f;
        events[i] = (struct kd_event){lo, faces[i] << 2 | (lo == hi ? EVENT_PLANAR : EVENT_START)};
    }
    bool ok = sort_events(events, count);
    for (size_t i = 0; ok && i < count; i++)
        faces[i] = events[i].key >> 2;
    free(events);
    return ok;
}
