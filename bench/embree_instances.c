/* embree_instances.c: chapter 16's forest traced by Intel Embree 3 with its own instances (make bench).
 *
 * The two levels as Embree makes them: one scene of triangles per object, committed (built) once, and
 * a top scene holding one RTC_GEOMETRY_TYPE_INSTANCE geometry per instance, each pointing at its
 * object's scene with its transform (rounded to float, as Embree stores it), attached under the
 * instance's own number so that a hit's instID names the instance as the scene file does. As in
 * embree_ref.c it runs as our code does: one thread ("threads=1"), one ray at a time, default flags
 * and build quality; the rays are camera_ray's, each hit's point is computed in double from Embree's
 * distance and one shadow ray goes to the light over SHADOW_T_MIN < t < distance - SHADOW_T_MIN. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "clock.h"
#include "embree_instances.h"
#include "embree_ref.h"

/* The processor time of the process, in milliseconds (bench_accel.c's clock). */
static double processor_ms(void) { return 1e3 * clock_processor_seconds(); }

/* The objects' scenes and the top scene over the instances, as one build made them. */
struct embree_forest {
    RTCScene *objects;
    size_t object_count;
    RTCScene top;
};

static void forest_release(struct embree_forest *f) {
    for (size_t k = 0; k < f->object_count; k++)
        if (f->objects[k] != NULL)
            rtcReleaseScene(f->objects[k]);
    free(f->objects);
    if (f->top != NULL)
        rtcReleaseScene(f->top);
    *f = (struct embree_forest){NULL, 0, NULL};
}

/* Builds every object's scene (timed into *objects_ms), then the instances and the top scene (timed into
 * *top_ms). Returns false with a message in err on failure, *f released. */
static bool forest_build(RTCDevice device, const struct instance_scene *s, struct embree_forest *f,
                         double *objects_ms, double *top_ms, char *err, size_t err_size) {
    *f = (struct embree_forest){calloc(s->object_count, sizeof(RTCScene)), s->object_count, NULL};
    if (f->objects == NULL) {
        snprintf(err, err_size, "embree: out of memory");
        return false;
    }
    bool made = true;
    double start = processor_ms();
    for (size_t k = 0; made && k < s->object_count; k++) {
        f->objects[k] = embree_ref_mesh_scene(device, s->objects[k]);
        made = f->objects[k] != NULL;
        if (made)
            rtcCommitScene(f->objects[k]);
    }
    *objects_ms = processor_ms() - start;
    start = processor_ms();
    f->top = made ? rtcNewScene(device) : NULL;
    for (size_t k = 0; f->top != NULL && made && k < s->instance_count; k++) {
        RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        made = instance != NULL;
        if (!made)
            break;
        float to_world[12];
        for (int row = 0; row < 3; row++)
            for (int column = 0; column < 4; column++)
                to_world[4 * row + column] = (float)s->to_world[k].m[row][column];
        rtcSetGeometryInstancedScene(instance, f->objects[s->instance_object[k]]);
        rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, to_world);
        rtcCommitGeometry(instance);
        rtcAttachGeometryByID(f->top, instance, (unsigned)k);
        rtcReleaseGeometry(instance);
    }
    if (f->top != NULL && made)
        rtcCommitScene(f->top);
    *top_ms = processor_ms() - start;
    if (f->top == NULL || !made || rtcGetDeviceError(device) != RTC_ERROR_NONE) {
        snprintf(err, err_size, "embree: could not build the instances (error %d)", (int)rtcGetDeviceError(device));
        forest_release(f);
        return false;
    }
    return true;
}

/* Traces the frame into pixels; returns the elapsed ms. */
static double trace_frame(RTCScene top, const struct camera *cam, vec3 light, struct instance_pixel *pixels) {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    double start = processor_ms();
    for (int j = 0; j < cam->height; j++)
        for (int i = 0; i < cam->width; i++) {
            ray r = camera_ray(cam, i, j);
            struct RTCRayHit hit;
            embree_ref_set_ray(&hit.ray, r.origin, r.direction, RAY_T_MIN, INFINITY);
            hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(top, &context, &hit);
            struct instance_pixel p = {INSTANCE_PIXEL_NONE, false};
            if (hit.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
                p.instance = hit.hit.instID[0];
                vec3 point = ray_at(r, hit.ray.tfar);
                vec3 to_light = vec3_sub(light, point);
                double distance = vec3_length(to_light);
                struct RTCRay shadow;
                embree_ref_set_ray(&shadow, point, vec3_scale(to_light, 1.0 / distance), SHADOW_T_MIN,
                                   distance - SHADOW_T_MIN);
                rtcOccluded1(top, &context, &shadow);
                p.shadowed = shadow.tfar == -INFINITY; /* Embree marks an occluded ray with tfar = -inf */
            }
            pixels[(size_t)j * cam->width + i] = p;
        }
    return processor_ms() - start;
}

bool embree_instances_frame(const struct instance_scene *s, const struct camera *cam, vec3 light, int repeats,
                            struct embree_instance_times *times, struct instance_pixel *pixels, char *err,
                            size_t err_size) {
    RTCDevice device = rtcNewDevice("threads=1");
    if (device == NULL) {
        snprintf(err, err_size, "embree: rtcNewDevice failed (error %d)", (int)rtcGetDeviceError(NULL));
        return false;
    }
    *times = (struct embree_instance_times){INFINITY, INFINITY, INFINITY};
    for (int k = 0; k < repeats; k++) {
        struct embree_forest forest;
        double objects_ms, top_ms;
        if (!forest_build(device, s, &forest, &objects_ms, &top_ms, err, err_size)) {
            rtcReleaseDevice(device);
            return false;
        }
        double frame_ms = trace_frame(forest.top, cam, light, pixels);
        times->objects_ms = fmin(times->objects_ms, objects_ms);
        times->top_ms = fmin(times->top_ms, top_ms);
        times->frame_ms = fmin(times->frame_ms, frame_ms);
        forest_release(&forest);
    }
    rtcReleaseDevice(device);
    return true;
}
