/* aabb.c: axis-aligned boxes (chapter 5): the normal of a box's face. The box maths and the slab test
 * are in aabb.h. */
#include "aabb.h"

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
