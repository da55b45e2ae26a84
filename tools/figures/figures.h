/* figures.h: the walkthroughs' figures, one function per figure (tools/figures; not part of any chapter).
 *
 * Each function draws one SVG into `out`. The geometry comes from the numbers the walkthrough uses
 * and is computed with the chapters' own functions (camera_ray, sphere_intersect, triangle_intersect,
 * aabb_clip, ...), so a figure cannot disagree with its text or its code. */
#ifndef WHITTED_FIGURES_H
#define WHITTED_FIGURES_H

#include <stdio.h>

void figure_camera(FILE *out);     /* 01-camera.svg: the pixel grid, and the camera's basis seen from the side */
void figure_sphere(FILE *out);     /* 02-sphere.svg: the quadratic's two roots, and a ray starting inside */
void figure_triangle(FILE *out);   /* 03-triangle.svg: Moller-Trumbore's barycentric coordinates */
void figure_plane(FILE *out);      /* 04-plane.svg: the distance to a plane along a ray */
void figure_slabs(FILE *out);      /* 05-slabs.svg: the slab test's entry and exit intervals */
void figure_phong(FILE *out);      /* 06-phong.svg: the vectors N, L, D, R of the Phong highlight */
void figure_shadow(FILE *out);     /* 07-shadow.svg: the shadow ray's window, and acne */
void figure_recursion(FILE *out);  /* 08-recursion.svg: reflection, refraction, total internal reflection */
void figure_kdtree(FILE *out);     /* 09-kdtree.svg: a kd-tree's cells in front-to-back order */
void figure_bvh(FILE *out);        /* 10-bvh.svg: a BVH's overlapping boxes and the SAH's areas */
void figure_antialias(FILE *out);  /* 12-antialias.svg: an edge over the pixel grid, and each method's rays */
void figure_penumbra(FILE *out);   /* 13-penumbra.svg: an area light's umbra and penumbra, and the share seen */
void figure_lens(FILE *out);       /* 13-lens.svg: the thin lens's rays, the focal plane, the circle of confusion */
void figure_textures(FILE *out);   /* 14-normals.svg: normals blended across a face, before and after renormalising */
void figure_sampling(FILE *out);   /* 15-sampling.svg: uniform and cosine-weighted directions over the hemisphere */
void figure_convergence(FILE *out); /* 15-convergence.svg: the path tracer's error against paths a pixel */
void figure_microfacets(FILE *out); /* 17-microfacets.svg: the half vector, the distribution D, masking G */

#endif
