/* embree_ref.c: the benchmark's yardstick, the same frame traced by Intel Embree 3 (chapter 10).
 *
 * Compiled into bench_accel only when Debian's libembree-dev is installed (bench/bench.mk checks for
 * /usr/include/embree3/rtcore.h and defines WHITTED_EMBREE). Embree is a production ray tracing kernel
 * library: wide BVHs, SIMD box and triangle tests, float arithmetic. To compare like with like it runs
 * here as our code does: one thread (device config "threads=1"), one ray at a time (rtcIntersect1 for
 * camera rays, rtcOccluded1 for shadow rays), default scene flags and build quality. Beside rung 10, whose
 * rays walk in packets, it also traces the camera rays in its own packets (rtcIntersect4 on four
 * neighbouring pixels of a row, rtcIntersect8 on 4 x 2 pixels, the context flagged coherent), and their
 * shadow rays either one by one or, as rung 10 does, in packets of the same pixels (rtcOccluded4,
 * rtcOccluded8).
 *
 * The rays are the very rays bench_accel traces, rounded to float: each pixel's camera ray, and from
 * each hit one shadow ray to the light over SHADOW_T_MIN < t < distance - SHADOW_T_MIN. The hit point
 * is computed in double from Embree's (float) distance, as bench_accel computes it from ours. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "camera.h"
#include "clock.h"
#include "embree_ref.h"
#include "mesh.h"

/* Also declared in bench_accel.c (which does without Embree's header). */
bool embree_ref_frame(const struct mesh *m, const struct camera *cam, vec3 light, int packet,
                      bool shadow_packets, int repeats, double *build_ms, double *frame_ms, unsigned char *pixels,
                      char *err, size_t err_size);

RTCScene embree_ref_mesh_scene(RTCDevice device, const struct mesh *m) {
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (scene == NULL || geometry == NULL)
        return NULL;
    float *vertices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                              3 * sizeof(float), m->vertex_count);
    unsigned *indices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                3 * sizeof(unsigned), m->face_count);
    if (vertices == NULL || indices == NULL)
        return NULL;
    for (size_t k = 0; k < m->vertex_count; k++) {
        vertices[3 * k + 0] = (float)m->vertices[k].x;
        vertices[3 * k + 1] = (float)m->vertices[k].y;
        vertices[3 * k + 2] = (float)m->vertices[k].z;
    }
    for (size_t f = 0; f < m->face_count; f++)
        for (int c = 0; c < 3; c++)
            indices[3 * f + c] = m->faces[f].v[c];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    return scene;
}

void embree_ref_set_ray(struct RTCRay *out, vec3 origin, vec3 direction, double t_min, double t_max) {
    out->org_x = (float)origin.x;
    out->org_y = (float)origin.y;
    out->org_z = (float)origin.z;
    out->dir_x = (float)direction.x;
    out->dir_y = (float)direction.y;
    out->dir_z = (float)direction.z;
    out->tnear = (float)t_min;
    out->tfar = (float)t_max;
    out->time = 0.0f;
    out->mask = UINT32_MAX;
    out->id = 0;
    out->flags = 0;
}

/* The shadow ray from a camera ray r's hit at t: 2 when the light is hidden, else 1. */
static unsigned char shadow_code(RTCScene scene, struct RTCIntersectContext *context, ray r, float t, vec3 light) {
    vec3 point = ray_at(r, t);
    vec3 to_light = vec3_sub(light, point);
    double distance = vec3_length(to_light);
    struct RTCRay shadow;
    embree_ref_set_ray(&shadow, point, vec3_scale(to_light, 1.0 / distance), SHADOW_T_MIN, distance - SHADOW_T_MIN);
    rtcOccluded1(scene, context, &shadow);
    return shadow.tfar == -INFINITY ? 2 : 1; /* Embree marks an occluded ray with tfar = -inf */
}

/* Embree's packet of n rays (RTCRayHit4 or RTCRayHit8) as the header lays it out for any n: each field
 * an array of n, in the order of struct RTCRay then struct RTCHit; written and read through these
 * offsets (in 4-byte words) so that one function fills packets of 4 and of 8. */
enum packet_field { P_ORG_X, P_ORG_Y, P_ORG_Z, P_TNEAR, P_DIR_X, P_DIR_Y, P_DIR_Z, P_TIME, P_TFAR, P_MASK, P_ID,
                    P_FLAGS, P_NG_X, P_NG_Y, P_NG_Z, P_U, P_V, P_PRIM_ID, P_GEOM_ID, P_INST_ID, P_FIELDS };

/* The shadow rays of a packet of n camera rays rays[k], from their hits at t[k] in the lanes where hit[k]
 * is -1 (0: no hit, or no ray), in one packet of Embree's: into codes[k], 0 for no hit, 1 lit, 2 in
 * shadow. */
static void shadow_packet(RTCScene scene, struct RTCIntersectContext *context, const ray rays[8], const float t[8],
                          const int hit[8], vec3 light, int n, unsigned char codes[8]) {
    _Alignas(32) union { float f[P_FIELDS * 8]; unsigned u[P_FIELDS * 8]; } packet;
    _Alignas(32) int valid[8];
    for (int k = 0; k < n; k++) {
        valid[k] = hit[k];
        vec3 point = ray_at(rays[k], hit[k] ? t[k] : 0.0f);
        vec3 to_light = vec3_sub(light, point);
        double distance = vec3_length(to_light);
        struct RTCRay one;
        embree_ref_set_ray(&one, point, vec3_scale(to_light, 1.0 / distance), SHADOW_T_MIN, distance - SHADOW_T_MIN);
        float values[] = {one.org_x, one.org_y, one.org_z, one.tnear, one.dir_x, one.dir_y, one.dir_z, 0.0f, one.tfar};
        for (int f = P_ORG_X; f <= P_TFAR; f++)
            packet.f[f * n + k] = values[f];
        packet.u[P_MASK * n + k] = UINT32_MAX;
        packet.u[P_ID * n + k] = 0;
        packet.u[P_FLAGS * n + k] = 0;
    }
    if (n == 4)
        rtcOccluded4(valid, scene, context, (struct RTCRay4 *)&packet);
    else
        rtcOccluded8(valid, scene, context, (struct RTCRay8 *)&packet);
    for (int k = 0; k < n; k++)
        codes[k] = !hit[k] ? 0 : packet.f[P_TFAR * n + k] == -INFINITY ? 2 : 1; /* occluded: tfar = -inf */
}

/* One frame with the camera rays in Embree's packets of n (4: four pixels of a row; 8: 4 x 2 pixels),
 * their shadow rays in packets too when shadow_packets is true; as trace_frame otherwise. */
static double trace_frame_in_packets(RTCScene scene, const struct camera *cam, vec3 light, int n, bool shadow_packets,
                                     unsigned char *pixels) {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    int rows = n / 4;
    double start = 1e3 * clock_processor_seconds();
    for (int y = 0; y < cam->height; y += rows) {
        for (int x = 0; x < cam->width; x += 4) {
            _Alignas(32) union { float f[P_FIELDS * 8]; unsigned u[P_FIELDS * 8]; } packet;
            _Alignas(32) int valid[8];
            ray rays[8];
            for (int k = 0; k < n; k++) {
                int i = x + k % 4, j = y + k / 4;
                valid[k] = i < cam->width && j < cam->height ? -1 : 0;
                rays[k] = camera_ray(cam, valid[k] ? i : x, valid[k] ? j : y);
                float values[] = {(float)rays[k].origin.x, (float)rays[k].origin.y, (float)rays[k].origin.z,
                                  (float)RAY_T_MIN, (float)rays[k].direction.x, (float)rays[k].direction.y,
                                  (float)rays[k].direction.z, 0.0f, INFINITY};
                for (int f = P_ORG_X; f <= P_TFAR; f++)
                    packet.f[f * n + k] = values[f];
                packet.u[P_MASK * n + k] = UINT32_MAX;
                packet.u[P_ID * n + k] = 0;
                packet.u[P_FLAGS * n + k] = 0;
                packet.u[P_GEOM_ID * n + k] = RTC_INVALID_GEOMETRY_ID;
                packet.u[P_PRIM_ID * n + k] = RTC_INVALID_GEOMETRY_ID;
            }
            if (n == 4)
                rtcIntersect4(valid, scene, &context, (struct RTCRayHit4 *)&packet);
            else
                rtcIntersect8(valid, scene, &context, (struct RTCRayHit8 *)&packet);
            _Alignas(32) int hit[8];
            float t[8];
            unsigned char codes[8];
            for (int k = 0; k < n; k++) {
                hit[k] = valid[k] && packet.u[P_GEOM_ID * n + k] != RTC_INVALID_GEOMETRY_ID ? -1 : 0;
                t[k] = packet.f[P_TFAR * n + k];
            }
            if (shadow_packets)
                shadow_packet(scene, &context, rays, t, hit, light, n, codes);
            for (int k = 0; k < n; k++) {
                if (!valid[k])
                    continue;
                unsigned char code = shadow_packets ? codes[k] : 0;
                if (!shadow_packets && hit[k])
                    code = shadow_code(scene, &context, rays[k], t[k], light);
                pixels[(size_t)(y + k / 4) * cam->width + x + k % 4] = code;
            }
        }
    }
    return 1e3 * clock_processor_seconds() - start;
}

/* Traces one frame into pixels (0 nothing hit, 1 lit, 2 in shadow); returns the elapsed ms. */
static double trace_frame(RTCScene scene, const struct camera *cam, vec3 light, unsigned char *pixels) {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    double start = 1e3 * clock_processor_seconds();
    for (int j = 0; j < cam->height; j++) {
        for (int i = 0; i < cam->width; i++) {
            ray r = camera_ray(cam, i, j);
            struct RTCRayHit hit;
            embree_ref_set_ray(&hit.ray, r.origin, r.direction, RAY_T_MIN, INFINITY);
            hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            hit.hit.primID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &hit);
            unsigned char code = 0;
            if (hit.hit.geomID != RTC_INVALID_GEOMETRY_ID)
                code = shadow_code(scene, &context, r, hit.ray.tfar, light);
            pixels[(size_t)j * cam->width + i] = code;
        }
    }
    return 1e3 * clock_processor_seconds() - start;
}

/* Builds the scene `repeats` times and traces the frame `repeats` times, its camera rays one by one
 * (packet 1) or in packets of 4 or 8, and then their shadow rays in packets of the same pixels when
 * shadow_packets is true (else one by one); reports the fastest of each (the least disturbed by the rest of the
 * machine). Returns false with a message in err on failure. */
bool embree_ref_frame(const struct mesh *m, const struct camera *cam, vec3 light, int packet,
                      bool shadow_packets, int repeats, double *build_ms, double *frame_ms, unsigned char *pixels,
                      char *err, size_t err_size) {
    RTCDevice device = rtcNewDevice("threads=1");
    if (device == NULL) {
        snprintf(err, err_size, "embree: rtcNewDevice failed (error %d)", (int)rtcGetDeviceError(NULL));
        return false;
    }
    *build_ms = INFINITY;
    *frame_ms = INFINITY;
    for (int k = 0; k < repeats; k++) {
        RTCScene scene = embree_ref_mesh_scene(device, m);
        if (scene == NULL) {
            snprintf(err, err_size, "embree: could not make the scene (error %d)", (int)rtcGetDeviceError(device));
            rtcReleaseDevice(device);
            return false;
        }
        double start = 1e3 * clock_processor_seconds();
        rtcCommitScene(scene);
        double built = 1e3 * clock_processor_seconds() - start;
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
            snprintf(err, err_size, "embree: rtcCommitScene failed");
            rtcReleaseScene(scene);
            rtcReleaseDevice(device);
            return false;
        }
        double traced = packet == 1 ? trace_frame(scene, cam, light, pixels)
                                    : trace_frame_in_packets(scene, cam, light, packet, shadow_packets, pixels);
        *build_ms = built < *build_ms ? built : *build_ms;
        *frame_ms = traced < *frame_ms ? traced : *frame_ms;
        rtcReleaseScene(scene);
    }
    rtcReleaseDevice(device);
    return true;
}
