/* probe.c: a chapter-3 program that calls chapter 4's plane_intersect. Linking it with chapter 3's
 * module list must fail: tests/test_layering.c checks that the Makefile enforces the chapter order. */
#include "plane.h"

int main(void) {
    struct plane floor = {{0, 1, 0}, 0.0, 0};
    ray down = {{0, 1, 0}, {0, -1, 0}};
    double t;
    return plane_intersect(&floor, &down, RAY_T_MIN, 10.0, &t) ? 0 : 1;
}
