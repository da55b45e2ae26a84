/* fig_bvh.c: chapter 10's figure, the surface area heuristic pricing two ways to split one node, with
 * the worked example's numbers: a node of area 10 with 20 triangles; split A gives two boxes of area 6
 * with 10 triangles each, split B a box of area 2 with 5 and a box of area 9 with 15. */
#include "aabb.h"
#include "figures.h"
#include "svg.h"

/* Every triangle reaches from z = 0 to z = 1, so every box is 1 deep and its area is
 * 2 (w h + w + h): 2 x 1 gives 10, 1 x 1 gives 6, 1.75 x 1 gives 9, and a square of side sqrt 2 - 1
 * gives 2. */
#define SMALL_SIDE (M_SQRT2 - 1)

/* The costs in units of one triangle test, as in bvh.c: one node visit, one triangle test. */
#define COST_TRAVERSAL 1.0
#define COST_TRIANGLE 1.0

struct group {
    svg_point lo, hi; /* the box the group's triangles fill */
    int columns, rows, skip; /* a grid of cells, one triangle each, leaving out cell `skip` (-1: none) */
};

/* The triangles of one group, one per grid cell; the cells on the edges reach the box's sides, so the
 * group's bounding box is exactly lo..hi. Returns how many were written. */
static int group_triangles(const struct group *g, vec3 out[][3]) {
    int count = 0;
    double w = (g->hi.x - g->lo.x) / g->columns, h = (g->hi.y - g->lo.y) / g->rows;
    for (int row = 0; row < g->rows; row++)
        for (int column = 0; column < g->columns; column++) {
            if (row * g->columns + column == g->skip)
                continue;
            double x0 = g->lo.x + column * w, y0 = g->lo.y + row * h;
            double inset = 0.15; /* of a cell: room between neighbouring triangles */
            double left = column == 0 ? x0 : x0 + inset * w, right = column == g->columns - 1 ? x0 + w : x0 + (1 - inset) * w;
            double bottom = row == 0 ? y0 : y0 + inset * h, top = row == g->rows - 1 ? y0 + h : y0 + (1 - inset) * h;
            out[count][0] = vec3_make(left, bottom, 0);
            out[count][1] = vec3_make(right, (bottom + top) / 2, 1);
            out[count][2] = vec3_make((left + right) / 2, top, 0.5);
            count++;
        }
    return count;
}

static struct aabb bound(vec3 triangles[][3], int count) {
    struct aabb box = aabb_empty();
    for (int k = 0; k < count; k++)
        for (int corner = 0; corner < 3; corner++)
            box = aabb_grow(box, triangles[k][corner]);
    return box;
}

static svg_point lo2(struct aabb b) { return (svg_point){b.min.x, b.min.y}; }
static svg_point hi2(struct aabb b) { return (svg_point){b.max.x, b.max.y}; }

/* Draws one way of splitting the node: the triangles of each side and their boxes, with the SAH's price. */
static void draw_split(struct svg *s, const char *name, vec3 left[][3], int n_left, vec3 right[][3], int n_right,
                       double title_x) {
    struct aabb l = bound(left, n_left), r = bound(right, n_right), node = aabb_union(l, r);
    for (int k = 0; k < n_left; k++)
        svg_polygon(s, (svg_point[]){{left[k][0].x, left[k][0].y}, {left[k][1].x, left[k][1].y}, {left[k][2].x, left[k][2].y}},
                    3, true, SVG_LIGHT, SVG_THIN, 0.45);
    for (int k = 0; k < n_right; k++)
        svg_polygon(s, (svg_point[]){{right[k][0].x, right[k][0].y}, {right[k][1].x, right[k][1].y}, {right[k][2].x, right[k][2].y}},
                    3, true, SVG_SURFACE, SVG_THIN, 0.45);
    svg_rect(s, lo2(node), hi2(node), SVG_INK, SVG_DASHED, 0);
    svg_rect(s, lo2(l), hi2(l), SVG_LIGHT, SVG_SOLID, 0.08);
    svg_rect(s, lo2(r), hi2(r), SVG_SURFACE, SVG_SOLID, 0.08);
    double area_l = aabb_surface_area(l), area_r = aabb_surface_area(r), area = aabb_surface_area(node);
    double cost = COST_TRAVERSAL + COST_TRIANGLE * (area_l * n_left + area_r * n_right) / area;
    svg_text_px(s, title_x, 30, "middle", SVG_INK, "split %s", name);
    svg_text(s, lo2(node), 0, 28, "start", SVG_LIGHT, "area(L) = %g, N_L = %d", area_l, n_left);
    svg_text(s, lo2(node), 0, 50, "start", SVG_SURFACE, "area(R) = %g, N_R = %d", area_r, n_right);
    svg_text(s, lo2(node), 0, 72, "start", SVG_INK, "node: area %g, %d triangles", area, n_left + n_right);
    svg_text(s, lo2(node), 0, 98, "start", SVG_INK, "cost = %g + (%g·%d + %g·%d) / %g = %g", COST_TRAVERSAL, area_l,
             n_left, area_r, n_right, area, cost);
}

void figure_bvh(FILE *out) {
    /* the small group sits on the node's left edge; the big one's boxes meet at x = 1 */
    const struct group small = {{0, 0.45}, {SMALL_SIDE, 0.45 + SMALL_SIDE}, 3, 2, 1};
    const struct group big_left = {{0.25, 0}, {1, 1}, 2, 3, 2};
    const struct group big_right = {{1, 0}, {2, 1}, 5, 2, -1};
    vec3 a_left[20][3], a_right[20][3], b_left[20][3], b_right[20][3];
    /* split A: by x = 1; split B: the small group against the rest */
    int n_small = group_triangles(&small, a_left);
    int n_a_left = n_small + group_triangles(&big_left, a_left + n_small);
    int n_a_right = group_triangles(&big_right, a_right);
    int n_b_left = group_triangles(&small, b_left);
    int n_b_right = group_triangles(&big_left, b_right);
    n_b_right += group_triangles(&big_right, b_right + n_b_right);

    struct svg s;
    svg_begin(&s, out, 900, 400, "Chapter 10: the surface area heuristic prices two splits of one node");
    svg_view(&s, 0, 0, 30, 250, 200);
    draw_split(&s, "A: two boxes side by side", a_left, n_a_left, a_right, n_a_right, 230);
    svg_view(&s, 0, 0, 470, 250, 200);
    draw_split(&s, "B: a small box, and a big one that overlaps it", b_left, n_b_left, b_right, n_b_right, 670);
    svg_text_px(&s, 450, 385, "middle", SVG_MUTED, "every triangle reaches from z = 0 to z = 1: the boxes are 1 deep, area = 2 (wh + w + h)");
    svg_end(&s);
}
