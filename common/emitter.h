/* emitter.h: the surfaces that give off light, gathered for next-event estimation: a shadow ray aimed
 * at a point chosen on them (chapter 15; docs/15-paths.md).
 *
 * Any surface whose material has `emission` is an emitter, seen from both faces. A path finds it in two
 * ways: by scattering into it, or by choosing a point on it and testing whether that point is in view
 * (next-event estimation). For the second, every emitter is a list of pieces with an area: the
 * triangles (triangle lines and mesh faces) and spheres of emissive materials, and a box's six faces as
 * two triangles each. A piece is chosen with probability proportional to its power, area times the mean
 * of its radiance's channels, and a point on it uniformly, so the density of a point over the area of
 * all emitters is power(radiance) / total power: it depends only on the radiance there, which is what
 * emitter_density needs to weigh a path that scattered into an emitter (multiple importance sampling).
 * An infinite plane cannot be chosen that way; a plane of an emissive material is refused.
 *
 * Chapter 13's area lights become emitters too (emitter_add_area_lights): each rectangle a surface of
 * two triangles giving off the light's colour as radiance. Point lights have no area; paths never see
 * them. */
#ifndef WHITTED_EMITTER_H
#define WHITTED_EMITTER_H

#include <stdbool.h>
#include <stddef.h>

#include "accel.h"
#include "scene.h"

enum emitter_shape { EMITTER_TRIANGLE, EMITTER_SPHERE };

/* One piece of an emitting surface. */
struct emitter {
    enum emitter_shape shape;
    vec3 a, e1, e2;   /* TRIANGLE: the corner a and the sides e1 = b - a, e2 = c - a */
    vec3 centre;      /* SPHERE */
    double radius;
    double area;
    vec3 radiance;
};

struct emitter_list {
    struct emitter *items; /* owned */
    double *cumulative;    /* owned: cumulative[k] = power of items[0..k], the last being total_power */
    size_t count;
    double total_power;    /* sum of area * emitter_power(radiance); 0 when there are no emitters */
};

/* A point chosen on the emitters. */
struct emitter_sample {
    vec3 point;
    vec3 normal;      /* unit normal of the surface there (either face emits) */
    vec3 radiance;
    double density;   /* per unit area: emitter_density(list, radiance) */
};

/* Returns the power of a radiance per unit area, as chosen by: the mean of its channels. */
double emitter_power(vec3 radiance);

/* Turns every area light of s into an emitting rectangle: a material "area light N" (black, emission the
 * light's colour) and two triangle lines over the parallelogram of its axes, added to s before its world
 * is built. Returns the number of point lights left, which paths do not see; -1 with "out of memory" in
 * err on failure. */
int emitter_add_area_lights(struct scene *s, char *err, size_t err_size);

/* Gathers the emitters of the world w (triangles from its gathered mesh, spheres and boxes from its
 * scene). Returns false with the reason in err: "out of memory", or "scene: plane N has the emissive
 * material 'x': ..." for an emissive plane, "scene: the emitters' total power ..." when the sum of
 * emission times area overflows. Free with emitter_list_free. */
bool emitter_list_build(struct emitter_list *list, const struct accel_world *w, char *err, size_t err_size);

/* Frees what emitter_list_build allocated. Safe on a zeroed list. */
void emitter_list_free(struct emitter_list *list);

/* Chooses a piece by power with u_pick and a point on it uniformly with (u1, u2). Returns false when
 * there are no emitters. */
bool emitter_sample(const struct emitter_list *list, double u_pick, double u1, double u2, struct emitter_sample *out);

/* Returns the density per unit area with which emitter_sample chooses a point of radiance `radiance`:
 * emitter_power(radiance) / total power, 0 without emitters. */
double emitter_density(const struct emitter_list *list, vec3 radiance);

#endif
