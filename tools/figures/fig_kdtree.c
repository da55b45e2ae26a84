/* fig_kdtree.c: chapter 9's figure, a kd-tree's cells and the front-to-back order in which a ray visits
 * them, with the early exit. */
#include "aabb.h"
#include "figures.h"
#include "svg.h"

/* A small tree in the plane, drawn by hand: inner nodes hold a plane, leaves a cell. */
struct node {
    int axis;        /* 0 = x, 1 = y; -1 for a leaf */
    double split;    /* the plane's position */
    int below, above; /* children's indices */
};
static const struct node tree[] = {
    {0, 3.5, 1, 2}, {1, 2.2, 3, 4}, {0, 6.0, 5, 6}, {-1, 0, 0, 0}, {-1, 0, 0, 0}, {-1, 0, 0, 0}, {1, 3.0, 7, 8},
    {-1, 0, 0, 0}, {-1, 0, 0, 0},
};
#define NODES (int)(sizeof tree / sizeof tree[0])
static const svg_point root_min = {0, 0}, root_max = {8, 5};

static const svg_point triangles[][3] = {
    {{0.6, 0.5}, {1.8, 0.4}, {1.1, 1.5}}, {{0.7, 3.2}, {2.2, 2.8}, {1.5, 4.3}}, {{2.8, 3.7}, {4.3, 4.0}, {3.4, 4.6}},
    {{4.2, 0.8}, {5.4, 1.4}, {4.6, 2.2}}, {{6.6, 0.6}, {7.6, 1.2}, {6.9, 2.0}}, {{6.5, 3.3}, {7.5, 3.5}, {7.1, 4.2}},
    {{4.5, 3.1}, {5.6, 2.75}, {5.3, 3.7}},
};
#define TRIANGLES (int)(sizeof triangles / sizeof triangles[0])

/* Where a ray in the plane first crosses the triangle's outline (edges as segments p + s (q - p),
 * 0 <= s <= 1), or INFINITY. A figure-only helper: the chapter's triangles are tested in 3D. */
static double first_crossing(svg_point o, svg_point d, const svg_point *corner) {
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
        svg_point p = corner[k], e = svg_minus(corner[(k + 1) % 3], p), w = svg_minus(p, o);
        double det = e.x * d.y - e.y * d.x;
        if (det == 0)
            continue;
        double t = (e.x * w.y - e.y * w.x) / det, s = (d.x * w.y - d.y * w.x) / det;
        if (t > 0 && s >= 0 && s <= 1 && t < best)
            best = t;
    }
    return best;
}

/* The cell of every node, from the root down. */
static void cells(svg_point lo[], svg_point hi[]) {
    lo[0] = root_min;
    hi[0] = root_max;
    for (int k = 0; k < NODES; k++)
        if (tree[k].axis >= 0) {
            lo[tree[k].below] = lo[tree[k].above] = lo[k];
            hi[tree[k].below] = hi[tree[k].above] = hi[k];
            if (tree[k].axis == 0)
                hi[tree[k].below].x = lo[tree[k].above].x = tree[k].split;
            else
                hi[tree[k].below].y = lo[tree[k].above].y = tree[k].split;
        }
}

void figure_kdtree(FILE *out) {
    svg_point lo[NODES], hi[NODES];
    cells(lo, hi);
    svg_point o = {-0.3, 1.6}, d = svg_unit((svg_point){1, 0.3});
    double hit = INFINITY;
    int hit_triangle = -1;
    for (int k = 0; k < TRIANGLES; k++) {
        double t = first_crossing(o, d, triangles[k]);
        if (t < hit) {
            hit = t;
            hit_triangle = k;
        }
    }
    /* each leaf's stretch of the ray, by the slab test; leaves visited in order of entry, until one
     * starts beyond the hit */
    double enter[NODES], leave[NODES];
    int order[NODES] = {0};
    bool crossed[NODES] = {false};
    for (int k = 0; k < NODES; k++) {
        struct aabb box = {vec3_make(lo[k].x, lo[k].y, -1), vec3_make(hi[k].x, hi[k].y, 1)};
        enter[k] = -INFINITY;
        leave[k] = INFINITY;
        crossed[k] = tree[k].axis < 0 &&
                     aabb_clip(&box, vec3_make(o.x, o.y, 0), aabb_inverse_direction(vec3_make(d.x, d.y, 0)), &enter[k],
                               &leave[k]);
    }
    for (int k = 0; k < NODES; k++)
        if (crossed[k] && enter[k] <= hit) {
            order[k] = 1;
            for (int m = 0; m < NODES; m++)
                order[k] += crossed[m] && enter[m] < enter[k];
        }

    struct svg s;
    svg_begin(&s, out, 900, 440, "Chapter 9: a kd-tree's cells, visited front to back");
    svg_view(&s, 0, 0, 40, 380, 64);
    svg_text_px(&s, 40, 28, "start", SVG_INK, "the cells, and the order in which the ray visits them");
    for (int k = 0; k < NODES; k++)
        if (tree[k].axis < 0)
            svg_rect(&s, lo[k], hi[k], order[k] ? SVG_ACCENT : SVG_MUTED, SVG_THIN, order[k] ? 0.12 : 0);
    for (int k = 0; k < NODES; k++)
        if (tree[k].axis >= 0) {
            svg_point a = lo[k], b = hi[k];
            if (tree[k].axis == 0)
                a.x = b.x = tree[k].split;
            else
                a.y = b.y = tree[k].split;
            svg_line(&s, a, b, SVG_INK, SVG_SOLID);
            svg_text(&s, tree[k].axis == 0 ? b : a, tree[k].axis == 0 ? 0 : 4, tree[k].axis == 0 ? -6 : -6,
                     tree[k].axis == 0 ? "middle" : "start", SVG_INK, "%s = %g", tree[k].axis == 0 ? "x" : "y",
                     tree[k].split);
        }
    svg_rect(&s, root_min, root_max, SVG_INK, SVG_SOLID, 0);
    for (int k = 0; k < TRIANGLES; k++)
        svg_polygon(&s, triangles[k], 3, true, SVG_SURFACE, SVG_THIN, k == hit_triangle ? 0.6 : 0.3);
    svg_line(&s, o, svg_along(o, d, 9.2), SVG_RAY, SVG_ARROW);
    svg_dot(&s, svg_along(o, d, hit), SVG_HIT);
    svg_text(&s, svg_along(o, d, hit), -6, -12, "end", SVG_HIT, "hit, t = %.2f", hit);
    for (int k = 0; k < NODES; k++) {
        if (!crossed[k])
            continue;
        svg_point corner = {lo[k].x, hi[k].y};
        if (order[k]) {
            svg_text(&s, corner, 6, 18, "start", SVG_ACCENT, "visit %d", order[k]);
            svg_text(&s, corner, 6, 38, "start", SVG_ACCENT, "t %.2f to %.2f", enter[k], leave[k]);
        } else {
            svg_text(&s, corner, 6, 18, "start", SVG_MUTED, "skipped:");
            svg_text(&s, corner, 6, 38, "start", SVG_MUTED, "from t %.2f", enter[k]);
        }
    }

    /* Right: the tree itself. */
    svg_view(&s, 0, 0, 0, 0, 1);
    const svg_point at[NODES] = {{710, -70}, {630, -150}, {790, -150}, {590, -230}, {670, -230}, {750, -230},
                                 {830, -230}, {790, -310}, {865, -310}};
    svg_text_px(&s, 730, 28, "middle", SVG_INK, "the tree");
    for (int k = 0; k < NODES; k++)
        if (tree[k].axis >= 0) {
            svg_line(&s, at[k], at[tree[k].below], SVG_MUTED, SVG_THIN);
            svg_line(&s, at[k], at[tree[k].above], SVG_MUTED, SVG_THIN);
        }
    for (int k = 0; k < NODES; k++) {
        if (tree[k].axis >= 0)
            svg_text(&s, at[k], 0, 5, "middle", SVG_INK, "%s = %g", tree[k].axis == 0 ? "x" : "y", tree[k].split);
        else if (order[k])
            svg_text(&s, at[k], 0, 5, "middle", SVG_ACCENT, "visit %d", order[k]);
        else
            svg_text(&s, at[k], 0, 5, "middle", SVG_MUTED, crossed[k] ? "skipped" : "missed");
    }
    svg_text_px(&s, 740, 360, "middle", SVG_INK, "left branches: below the plane");
    svg_text_px(&s, 740, 385, "middle", SVG_INK, "the near child first, the far");
    svg_text_px(&s, 740, 405, "middle", SVG_INK, "one kept on a stack for later");
    svg_end(&s);
}
