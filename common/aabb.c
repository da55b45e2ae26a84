/* aabb.c: axis-aligned boxes (chapter 5): the boxes of the shapes that have one and the normal of a
 * box's face. The box maths and the slab test are in aabb.h. */
#include "aabb.h"

struct aabb aabb_of_sphere(const struct sphere *s) {
    vec3 extent = vec3_make(s->radius, s->radius, s->radius);
    return (struct aabb){vec3_sub(s->centre, extent), vec3_add(s->centre, extent)};
}

struct aabb aabb_of_triangle(vec3 a, vec3 b, vec3 c) {
    return (struct aabb){vec3_min(a, vec3_min(b, c)), vec3_max(a, vec3_max(b, c))};
}

struct aabb aabb_of_box(const struct box *b) { return (struct aabb){b->min, b->max}; }

vec3 aabb_normal(const struct aabb *b, vec3 p) {
    double distance[6] = {fabs(p.x - b->min.x), fabs(p.x - b->max.x), fabs(p.y - b->min.y),
                          fabs(p.y - b->max.y), fabs(p.z - b->min.z), fabs(p.z - b->max.z)};
    static const vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    int nearest = 0;
    for (int k = 1; k < 6; k++)
        if (distance[k] < distance[nearest])
            nearest = k;
    return normals[nearest];
}
