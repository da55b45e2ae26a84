/* speck_triangle.h: the triangle a unit in the last place or two across, and the ray that passes 1.6
 * units from it, which the tests of the watertight test's exact edge signs share (test_geometry.c,
 * test_accel.c, test_watertight.c). Its three corners move to nearly one point of the ray's sheared
 * plane, where two edge functions' products round alike; counted as 0, "on the edge", they made the ray
 * hit it, 0.1 along. Each value is written once, as numbers and, for a scene file, as text. */
#ifndef WHITTED_TEST_SPECK_TRIANGLE_H
#define WHITTED_TEST_SPECK_TRIANGLE_H

/* The corners and the ray's direction, as three coordinates each (the ray starts at the origin). */
#define SPECK_A -1.5818233809349238, 0.20938174482871832, -0.047218961197519234
#define SPECK_B -1.5818233809349238, 0.20938174482871832, -0.047218961197519213
#define SPECK_C -1.5818233809349238, 0.2093817448287183, -0.047218961197519213
#define SPECK_DIRECTION 0.29805563450700401, 0.15023926885344063, -0.48162659419776244

/* SPECK_TEXT(SPECK_A) is "-1.5818233809349238 0.20938174482871832 -0.047218961197519234": a point's
 * three coordinates as a scene file writes them, each number the very text of the one above. */
#define SPECK_TEXT(point) SPECK_TEXT_OF(point)
#define SPECK_TEXT_OF(x, y, z) #x " " #y " " #z

#endif
