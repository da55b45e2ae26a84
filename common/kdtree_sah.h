/* kdtree_sah.h: the two questions every kd-tree build asks of a plane, which side a triangle goes and
 * what the cut costs by the surface area heuristic (chapter 9). Shared by the plain build (kdtree.c)
 * and the fast one (kdtree_events.c), and inline because the fast build prices tens of millions of
 * planes on a large mesh (out of line, and with the area recomputed for each plane, the build of
 * chapter 10's 350,000 triangles took about 15 % longer). */
#ifndef WHITTED_KDTREE_SAH_H
#define WHITTED_KDTREE_SAH_H

#include <stdbool.h>
#include <stddef.h>

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

/* A box in floats: a padded triangle box, or a node's region. */
struct fbox {
    float lo[3], hi[3];
};

/* Which sides of a plane a triangle box goes to. */
enum side { SIDE_LEFT = 1, SIDE_RIGHT = 2, SIDE_BOTH = 3 };

/* Left when the box starts before the plane `split` on `axis`, right when it reaches past it, both
 * when it lies flat in the plane: every triangle goes somewhere (never 0 for a box without NaN).
 * (Padded boxes are never flat; only a mesh of zero size, whose pad is 0, has flat boxes.) */
static inline enum side kd_classify(const struct fbox *b, int axis, float split) {
    bool flat_in_plane = b->lo[axis] == split && b->hi[axis] == split;
    bool left = b->lo[axis] < split || flat_in_plane;
    bool right = b->hi[axis] > split || flat_in_plane;
    return (left ? SIDE_LEFT : 0) | (right ? SIDE_RIGHT : 0);
}

/* Surface area of b; 0 for an empty box. */
static inline double kd_fbox_area(const struct fbox *b) {
    double ex = (double)b->hi[0] - b->lo[0], ey = (double)b->hi[1] - b->lo[1], ez = (double)b->hi[2] - b->lo[2];
    if (!(ex >= 0.0 && ey >= 0.0 && ez >= 0.0))
        return 0.0;
    return 2.0 * (ex * ey + ey * ez + ez * ex);
}

/* What a leaf of `count` triangles costs a ray that crosses it. */
static inline double kd_leaf_cost(size_t count) { return KD_COST_TRIANGLE * (double)count; }

/* What cutting the node `box` (of surface area `area`, computed once per node) at `split` on `axis`
 * costs a ray that crosses the node, with n_left and n_right triangles on the two sides: one step,
 * then each side's triangles weighted by the chance that the ray crosses that side, the ratio of the
 * areas. The halves' areas need no box arithmetic: with the node's extents e_b, e_c across the axis,
 * a half of length l along it has area 2 (e_b e_c + l (e_b + e_c)). */
static inline double kd_sah_cost(const struct fbox *box, double area, int axis, float split, size_t n_left,
                                 size_t n_right) {
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    double extent_b = (double)box->hi[b] - box->lo[b], extent_c = (double)box->hi[c] - box->lo[c];
    double below = (double)split - box->lo[axis], above = (double)box->hi[axis] - split;
    double cross = extent_b * extent_c, side = extent_b + extent_c;
    double area_left = 2.0 * (cross + below * side), area_right = 2.0 * (cross + above * side);
    double bonus = n_left == 0 || n_right == 0 ? 1.0 - KD_EMPTY_BONUS : 1.0;
    return KD_COST_TRAVERSAL + KD_COST_TRIANGLE * bonus * (area_left * n_left + area_right * n_right) / area;
}

#endif
