/* float_triangle.c: rung 11's exact float triangle filter: its float copy of the triangles, its counters
 * (chapter 11; float_triangle.h derives the bounds and holds the test; fast_bvh_build makes rung 11's tree). */
#include "float_triangle.h"

#include <stdlib.h>

#include "big_alloc.h"

_Thread_local struct float_triangle_counts float_triangle_thread;

bool float_triangle_prepare(struct fast_bvh *b) {
    size_t padded = (b->tree_count + FLOAT_TRIANGLE_LANES - 1) / FLOAT_TRIANGLE_LANES * FLOAT_TRIANGLE_LANES;
    size_t floats = (padded > 0 ? padded : FLOAT_TRIANGLE_LANES) * 9; /* nine per triangle: whole blocks */
    /* aligned to 64 bytes (an AVX2 load of eight floats wants 32), on 2 MB pages as rung 9's blocks */
    float *corners = big_alloc(floats * sizeof(float), true);
    if (corners == NULL)
        return false;
    const vec3 zero = {0.0, 0.0, 0.0}; /* the lanes past the last triangle */
    for (size_t k = 0; k < padded; k++) {
        const struct bvh_triangle *t = k < b->tree_count ? &b->triangles[k] : NULL;
        for (int i = 0; i < 9; i++) { /* corner i / 3, axis i % 3 */
            vec3 corner = t == NULL ? zero : i < 3 ? t->a : i < 6 ? t->b : t->c;
            corners[float_triangle_index(k, i / 3, i % 3)] = (float)vec3_axis(corner, i % 3);
        }
    }
    b->float_corners = corners;
    return true;
}
