/* fast_bvh_packet.h: rung 10 of chapter 11's ladder: a packet of up to eight neighbouring camera rays,
 * or of their shadow rays, walked through the hierarchy together, each ray's answer still exactly the
 * brute-force loop's (chapter 11). */
#ifndef WHITTED_FAST_BVH_PACKET_H
#define WHITTED_FAST_BVH_PACKET_H

#include <stdint.h>

#include "camera.h"
#include "fast_bvh_tree.h"
#include "ray.h"

/* The rays of one packet: at most this many, one in each lane of an 8-float vector. */
#define FAST_BVH_PACKET_SIZE 8
/* A packet of camera rays covers this many columns and rows of pixels. */
#define FAST_BVH_PACKET_COLUMNS 4
#define FAST_BVH_PACKET_ROWS 2

/* For every ray k (0 <= k < FAST_BVH_PACKET_SIZE) whose bit k is set in `active`, finds the nearest face
 * hit by rays[k] with t_min[k] < t < t_max[k], exactly as fast_bvh_closest(b, &rays[k], t_min[k],
 * t_max[k], ...) does (the same t to the last bit, the same face, the same tie rule). Returns the mask of
 * the rays that hit something; for those, t[k] and face[k] hold the hit, for the others they are left
 * alone. Lanes whose bit is clear are not read. Works on every rung's tree; the rays walk together where
 * the float box test covers them (all but rays with t_min < 0 or outside FAST_BVH_FLOAT_RANGE), the
 * others one by one. Adds to the calling thread's counters: node_visits once per node the packet visits,
 * box_tests once per box and ray, triangle_tests per ray. Safe from several threads at once. */
unsigned fast_bvh_closest_packet(const struct fast_bvh *b, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                                 const double t_min[FAST_BVH_PACKET_SIZE], const double t_max[FAST_BVH_PACKET_SIZE],
                                 double t[FAST_BVH_PACKET_SIZE], uint32_t face[FAST_BVH_PACKET_SIZE]);

/* For every ray k whose bit k is set in `active`, whether anything lies on rays[k] with t_min[k] < t <
 * t_max[k], exactly as fast_bvh_occluded(b, &rays[k], t_min[k], t_max[k]) says: the mask of the rays
 * that meet something. Lanes whose bit is clear are not read. The rays walk together as in
 * fast_bvh_closest_packet, each leaving the walk at its first hit; they need not share an origin (the
 * shadow rays of neighbouring pixels towards one light). Adds to the calling thread's counters as
 * fast_bvh_closest_packet does. Safe from several threads at once. */
unsigned fast_bvh_occluded_packet(const struct fast_bvh *b, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                                  const double t_min[FAST_BVH_PACKET_SIZE],
                                  const double t_max[FAST_BVH_PACKET_SIZE]);

/* Fills a packet with the camera rays of cam through the pixels (x + k % FAST_BVH_PACKET_COLUMNS,
 * y + k / FAST_BVH_PACKET_COLUMNS), ray k in lane k, each with the window a camera ray is traced in
 * (ray_t_min of its origin, infinity), and returns the mask of the lanes filled: those whose pixel lies
 * left of column `right` and above row `bottom` (the edge of the picture or of a block of it). */
unsigned fast_bvh_camera_packet(const struct camera *cam, int x, int y, int right, int bottom,
                                ray rays[FAST_BVH_PACKET_SIZE], double t_min[FAST_BVH_PACKET_SIZE],
                                double t_max[FAST_BVH_PACKET_SIZE]);

#endif
