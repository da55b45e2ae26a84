/* scene_scale.c: the warning for scenes too small for the fixed distance margins (chapter 1). */
#include "scene_scale.h"

#include <math.h>

#include "ray.h"

/* The box around everything seen so far. */
struct extent {
    vec3 min, max;
};

static void grow(struct extent *e, vec3 p) {
    e->min = vec3_make(fmin(e->min.x, p.x), fmin(e->min.y, p.y), fmin(e->min.z, p.z));
    e->max = vec3_make(fmax(e->max.x, p.x), fmax(e->max.y, p.y), fmax(e->max.z, p.z));
}

double scene_extent(const struct scene *s) {
    struct extent e = {s->eye, s->eye};
    for (size_t k = 0; k < s->sphere_count; k++) {
        vec3 c = s->spheres[k].centre;
        double r = s->spheres[k].radius;
        grow(&e, vec3_make(c.x - r, c.y - r, c.z - r));
        grow(&e, vec3_make(c.x + r, c.y + r, c.z + r));
    }
    for (size_t k = 0; k < s->box_count; k++) {
        grow(&e, s->boxes[k].min);
        grow(&e, s->boxes[k].max);
    }
    for (size_t k = 0; k < s->triangle_count; k++) {
        grow(&e, s->triangles[k].a);
        grow(&e, s->triangles[k].b);
        grow(&e, s->triangles[k].c);
    }
    for (size_t k = 0; k < s->mesh_count; k++)
        for (size_t v = 0; v < s->meshes[k].mesh.vertex_count; v++)
            grow(&e, s->meshes[k].mesh.vertices[v]);
    return fmax(e.max.x - e.min.x, fmax(e.max.y - e.min.y, e.max.z - e.min.z));
}

bool scene_scale_warn(const struct scene *s, FILE *out) {
    if (s->sphere_count + s->box_count + s->triangle_count + s->mesh_count == 0)
        return false; /* nothing finite to measure (chapter 1 draws no shapes at all) */
    double extent = scene_extent(s);
    double smallest = SCENE_SCALE_MIN_MARGINS * SHADOW_T_MIN;
    if (extent >= smallest)
        return false;
    double factor = pow(10.0, ceil(log10(smallest / fmax(extent, 1e-300))));
    fprintf(out,
            "%s: warning: the scene is %g units across, only %g times the shadow-ray margin %g (and %g times "
            "the ray margin %g); surfaces that close are missed and the picture will differ from POV-Ray's: "
            "scale the scene up %g times or more\n",
            s->path, extent, extent / SHADOW_T_MIN, SHADOW_T_MIN, extent / RAY_T_MIN, RAY_T_MIN, factor);
    return true;
}
