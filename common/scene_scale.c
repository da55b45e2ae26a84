/* scene_scale.c: the warning for scenes too small for the distance margins, or too far from the origin
 * for their size (chapter 1). */
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

/* Grows e by the bounding box of every shape of `list` that has one. Returns true when one had. */
static bool grow_by_shapes(struct extent *e, const struct shape_list *list) {
    bool bounded = false;
    for (size_t k = 0; k < list->count; k++) {
        vec3 min, max;
        if (list->kind->bounds(shape_item(list->syntax, list->items, k), &min, &max)) {
            grow(e, min);
            grow(e, max);
            bounded = true;
        }
    }
    return bounded;
}

/* Grows e by every finite shape of s: the shapes with bounding boxes, the vertices of loaded meshes,
 * and chapter 16's instances, by their world boxes (s->instance_bounds). Returns true when s has one. */
static bool grow_by_scene(struct extent *e, const struct scene *s) {
    bool finite = s->mesh_count > 0;
    for (size_t k = 0; k < s->kind_count; k++)
        if (s->shapes[k].kind != NULL)
            finite |= grow_by_shapes(e, &s->shapes[k]);
    for (size_t k = 0; k < s->mesh_count; k++)
        for (size_t v = 0; v < s->meshes[k].mesh.vertex_count; v++)
            grow(e, s->meshes[k].mesh.vertices[v]);
    if (s->instance_bounds != NULL)
        finite |= s->instance_bounds(s->placed_instances, &e->min, &e->max);
    return finite;
}

static double longest_side(const struct extent *e) {
    return fmax(e->max.x - e->min.x, fmax(e->max.y - e->min.y, e->max.z - e->min.z));
}

double scene_extent(const struct scene *s) {
    struct extent e = {s->eye, s->eye};
    grow_by_scene(&e, s);
    return longest_side(&e);
}

/* The margin ray_t_min sets at the corner of e farthest from the origin: the largest of the scene. */
static double farthest_margin(const struct extent *e) {
    vec3 far = vec3_max(vec3_make(fabs(e->min.x), fabs(e->min.y), fabs(e->min.z)),
                        vec3_make(fabs(e->max.x), fabs(e->max.y), fabs(e->max.z)));
    return ray_t_min(far);
}

bool scene_scale_warn(const struct scene *s, FILE *out) {
    struct extent e = {s->eye, s->eye};
    if (!grow_by_scene(&e, s))
        return false; /* nothing finite to measure (chapter 1 draws no shapes at all) */
    double extent = longest_side(&e);
    double smallest = SCENE_SCALE_MIN_MARGINS * SHADOW_T_MIN;
    double margin = farthest_margin(&e);
    if (extent >= smallest && extent >= SCENE_SCALE_MIN_MARGINS * margin)
        return false;
    if (extent >= smallest) {
        fprintf(out,
                "%s: warning: the scene is %g units across and reaches %g from the origin, where a ray leaving a "
                "surface accepts hits only beyond %g (%g of that distance, for the rounding of its coordinates): "
                "reflections and refractions between surfaces that close are lost, and the path tracers' shadows "
                "too; move the scene towards the origin\n",
                s->path, extent, margin / RAY_T_MIN_RELATIVE, margin, RAY_T_MIN_RELATIVE);
        return true;
    }
    double factor = pow(10.0, ceil(log10(smallest / fmax(extent, 1e-300))));
    fprintf(out,
            "%s: warning: the scene is %g units across, only %g times the shadow-ray margin %g (and %g times "
            "the ray margin %g); surfaces that close are missed and the picture will differ from POV-Ray's: "
            "scale the scene up %g times or more\n",
            s->path, extent, extent / SHADOW_T_MIN, SHADOW_T_MIN, extent / RAY_T_MIN, RAY_T_MIN, factor);
    return true;
}
