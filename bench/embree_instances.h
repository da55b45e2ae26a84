/* embree_instances.h: chapter 16's forest traced by Intel Embree 3 with its own instances, the
 * yardstick of bench_instances (make bench). */
#ifndef WHITTED_EMBREE_INSTANCES_H
#define WHITTED_EMBREE_INSTANCES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "camera.h"
#include "mesh.h"
#include "transform.h"

/* The instance number of a pixel whose camera ray hit nothing. */
#define INSTANCE_PIXEL_NONE UINT32_MAX

/* What one pixel's camera ray saw: the instance it hit first (its index among the scene's instances),
 * and whether that point is hidden from the light. Both tracers of the benchmark fill these. */
struct instance_pixel {
    uint32_t instance;
    bool shadowed;
};

/* A scene of instances: object_count meshes in their own space, and instance_count placements, each of
 * one object by one transform (object space to world). */
struct instance_scene {
    const struct mesh *const *objects;
    size_t object_count;
    const uint32_t *instance_object;     /* the object of each instance, < object_count */
    const struct transform *to_world;    /* the transform of each instance */
    size_t instance_count;
};

/* Embree's times, in processor milliseconds on one thread, the fastest of the repeats. */
struct embree_instance_times {
    double objects_ms; /* building every object's scene (bottom level) */
    double top_ms;     /* making the instance geometries and building the scene over them (top level) */
    double frame_ms;   /* the camera rays, one per pixel, and one shadow ray from every hit */
};

/* Builds s in Embree (one scene of triangles per object, one RTC_GEOMETRY_TYPE_INSTANCE per instance,
 * numbered as s numbers them) and traces cam's frame (camera_ray of every pixel, one ray at a time,
 * and from each hit one shadow ray to light), `repeats` times, into pixels (width * height, row by
 * row). Returns false with a message in err when Embree fails. */
bool embree_instances_frame(const struct instance_scene *s, const struct camera *cam, vec3 light, int repeats,
                            struct embree_instance_times *times, struct instance_pixel *pixels, char *err,
                            size_t err_size);

#endif
