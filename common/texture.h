/* texture.h: pigments drawn, the colour of a surface that varies from point to point (chapter 14;
 * docs/14-textures.md). The scene's pigment lines are read by every chapter (pigment.h); this module
 * evaluates them as POV-Ray 3.7 does: the point is carried back through the pigment's texture transform,
 * the pattern gives a number there, and the number picks or blends the pigment's colours. */
#ifndef WHITTED_TEXTURE_H
#define WHITTED_TEXTURE_H

#include "box.h"
#include "mesh.h"
#include "scene.h"

/* The colour of a pigment at one point: red, green, blue and the share of light it lets through
 * untinted (an image's alpha: transmit = 1 - alpha; 0 for the patterns). */
struct texture_colour {
    vec3 colour;
    double transmit;
};

/* Returns `point` carried back through p's texture transform: translate undone, then the rotations
 * about z, y and x, then the scale. The pattern is evaluated at the point this returns. */
vec3 texture_space(const struct pigment *p, vec3 point);

/* Returns POV-Ray's pattern value of p's procedural pattern at the texture-space point q: checker and
 * brick 0 or 1 (brick: 0 in the mortar), gradient and radial in [0, 1] after POV-Ray's ramp wave.
 * Not for image maps. */
double texture_pattern_value(const struct pigment *p, vec3 q);

/* Returns the colour of pigment p at the world-space point `point`. An image map must have been read
 * (texture_load_images). */
struct texture_colour texture_pigment_at(const struct pigment *p, vec3 point);

/* Returns the (u, v) that POV-Ray 3.7's uv_mapping gives the point `point` of box b on the face whose
 * outward normal is `normal` (Box::UVCoord): the box unfolded into a cross on the unit square, each face
 * a quarter wide and a third high, seen from outside without mirroring. With P = (point - min) /
 * (max - min) in [0, 1]^3:
 *
 *     face   u              v                   the cross, v up:      +y
 *     -x     Pz / 4         1/3 + Py / 3                         -x  +z  +x  -z
 *     +z     1/4 + Px / 4   1/3 + Py / 3                              -y
 *     +x     3/4 - Pz / 4   1/3 + Py / 3
 *     -z     1 - Px / 4     1/3 + Py / 3        (the +y face above the +z face, the -y face below it)
 *     +y     1/4 + Px / 4   1 - Pz / 3
 *     -y     1/4 + Px / 4   Pz / 3 */
struct mesh_uv texture_box_uv(const struct box *b, vec3 point, vec3 normal);

/* The scene's paint hook (scene_paint_fn; set run.scene.paint = texture_paint). On a mesh with normals,
 * replaces h->normal by the blended normal at `point` (mesh_surface.h). For a material with a pigment,
 * fills *painted from it with the pigment's colour at `point` (or, for `map uv`, at (u, v, 0): a mesh's
 * blended texture coordinates, a box's texture_box_uv; (0, 0, 0) on another surface) and its transmit added to the
 * material's (at most 1 - filter) and returns painted; otherwise returns the scene's material. */
const struct material *texture_paint(const struct scene *s, struct hit *h, vec3 point, struct material *painted);

/* The scene's shadow_paint hook (set run.scene.shadow_paint = texture_paint_shadow): the material a
 * shadow ray crossing the hit *h at `point` is filtered by. texture_paint's, except for POV-Ray 3.7's
 * test of what is opaque: a surface whose pigment is a `map uv` image map, not `wrap once`, of a
 * picture whose every alpha is 1, casts a full shadow, whatever its material's filter and transmit
 * (then *painted is the material with filter and transmit 0). POV-Ray decides before rendering whether
 * an object can let light through to a shadow, from its pigment. The twin's `filter all` and `transmit
 * all` mark an image map's own pigment as letting light through, but for uv_mapping the test looks at
 * the pigment round it, which asks the picture alone: no alpha, not once, so opaque. The camera still
 * sees through the surface. */
const struct material *texture_paint_shadow(const struct scene *s, struct hit *h, vec3 point,
                                            struct material *painted);

/* Reads the image of every image_map pigment of s (image_map.h), once a file: pigments naming a file an
 * earlier one has read borrow its pixels. Returns false at the first that fails, or that takes the
 * images over their share of memory (memory_budget.h), with "scene:line: pigment 'name': what is
 * wrong" in err. */
bool texture_load_images(struct scene *s, char *err, size_t err_size);

#endif
