/* fig_textures.c: chapter 14's figure, a smooth mesh seen edge-on: the corners' normals, the normal
 * blended across a face before and after it is made unit length, and the flat faces it pretends away. */
#include <math.h>

#include "figures.h"
#include "mesh_surface.h"
#include "svg.h"

#define FACES 3   /* facets of the arc drawn */
#define SAMPLES 5 /* blended normals drawn along the middle face, corners included */

void figure_textures(FILE *out) {
    struct svg s;
    svg_begin(&s, out, 900, 460, "Chapter 14: normals blended across a face, and made unit length again");
    svg_view(&s, 0, -0.2, 450, 250, 110);
    svg_text_px(&s, 450, 28, "middle", SVG_INK, "a curved surface as flat faces, seen edge-on");

    /* An arc of a circle of radius 2.5 cut into FACES flat faces; each vertex's normal is the
     * circle's, which is what averaging the faces' normals at the vertex gives on a regular arc. */
    double radius = 2.5, start = M_PI * 0.05, span = M_PI * 0.9, shift = 1.9;
    vec3 corners[FACES + 1], normals[FACES + 1];
    for (int k = 0; k <= FACES; k++) {
        double a = start + span * k / FACES;
        normals[k] = vec3_make(cos(a), sin(a), 0);
        corners[k] = vec3_scale(normals[k], radius);
        corners[k].y -= shift;
    }
    svg_circle(&s, (svg_point){0, -shift}, radius, SVG_MUTED, SVG_DASHED, 0.0);
    for (int k = 0; k < FACES; k++)
        svg_line(&s, (svg_point){corners[k].x, corners[k].y}, (svg_point){corners[k + 1].x, corners[k + 1].y},
                 SVG_SURFACE, SVG_SOLID);

    /* The middle face as a mesh of one triangle (its third corner off the page, below the arc, gives the
     * face a plane; its normal is the face's own), blended with the chapter's own function. */
    vec3 a = corners[1], b = corners[2], c = vec3_make((a.x + b.x) / 2, (a.y + b.y) / 2, -1);
    vec3 points[3] = {a, b, c}, face_normal = vec3_normalize(vec3_add(normals[1], normals[2]));
    vec3 corner_normals[3] = {normals[1], normals[2], face_normal};
    struct mesh_face face = {{0, 1, 2}};
    struct scene_mesh m = {.mesh = {.vertices = points, .vertex_count = 3, .faces = &face, .face_count = 1},
                           .corners = {.normals = corner_normals, .normal_count = 3, .normal_faces = &face}};
    double arrow = 0.9;
    for (int k = 0; k < SAMPLES; k++) {
        double t = (double)k / (SAMPLES - 1);
        vec3 p = vec3_add(vec3_scale(a, 1 - t), vec3_scale(b, t));
        vec3 n;
        if (!mesh_surface_normal(&m, 0, p, &n))
            continue;
        vec3 raw = vec3_add(vec3_scale(normals[1], 1 - t), vec3_scale(normals[2], t)); /* before: shorter */
        svg_point at = {p.x, p.y};
        svg_line(&s, at, svg_along(at, (svg_point){n.x, n.y}, arrow), SVG_NORMAL, SVG_ARROW);
        if (k > 0 && k < SAMPLES - 1)
            svg_line(&s, at, svg_along(at, (svg_point){raw.x, raw.y}, arrow), SVG_ACCENT, SVG_ARROW | SVG_THIN);
        svg_dot(&s, at, SVG_HIT);
    }
    /* The flat faces' own normals, for comparison: one direction over the whole face. */
    for (int k = 0; k < FACES; k += 2) {
        vec3 mid = vec3_scale(vec3_add(corners[k], corners[k + 1]), 0.5);
        vec3 n = vec3_normalize(vec3_add(normals[k], normals[k + 1]));
        svg_line(&s, (svg_point){mid.x, mid.y}, svg_along((svg_point){mid.x, mid.y}, (svg_point){n.x, n.y}, arrow),
                 SVG_MUTED, SVG_ARROW);
    }
    svg_text_px(&s, 450, 430, "middle", SVG_NORMAL, "blended, then made unit length: the middle face shades as if curved");
    svg_text_px(&s, 450, 447, "middle", SVG_ACCENT, "the plain blend (thin) is shorter between the corners; grey: a flat face's one normal");
    svg_end(&s);
}
