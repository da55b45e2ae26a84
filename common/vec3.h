/* vec3.h: three-component double-precision vectors for points, directions and colours (chapter 1).
 *
 * Header-only so the compiler can inline the arithmetic in every hot loop. All functions are pure:
 * they take vectors by value and return a new vector, never touching memory they were not given. */
#ifndef WHITTED_VEC3_H
#define WHITTED_VEC3_H

#include <math.h>

typedef struct vec3 {
    double x, y, z;
} vec3;

/* Returns the vector (x, y, z). */
static inline vec3 vec3_make(double x, double y, double z) { return (vec3){x, y, z}; }

/* Returns a + b. */
static inline vec3 vec3_add(vec3 a, vec3 b) { return (vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }

/* Returns a - b. */
static inline vec3 vec3_sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }

/* Returns a scaled by the number s. */
static inline vec3 vec3_scale(vec3 a, double s) { return (vec3){a.x * s, a.y * s, a.z * s}; }

/* Returns the component-wise (Hadamard) product; used to filter one colour by another. */
static inline vec3 vec3_mul(vec3 a, vec3 b) { return (vec3){a.x * b.x, a.y * b.y, a.z * b.z}; }

/* Returns a + s * b, the step used to walk along a ray or accumulate weighted colour. */
static inline vec3 vec3_add_scaled(vec3 a, vec3 b, double s) {
    return (vec3){a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
}

/* Returns -a. */
static inline vec3 vec3_neg(vec3 a) { return (vec3){-a.x, -a.y, -a.z}; }

/* Returns the dot product a . b. */
static inline double vec3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* Returns the right-handed cross product a x b. */
static inline vec3 vec3_cross(vec3 a, vec3 b) {
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/* Returns |a|. */
static inline double vec3_length(vec3 a) { return sqrt(vec3_dot(a, a)); }

/* Returns a / |a|. The zero vector has no direction: it comes back as NaNs, so callers that may see
 * one (parsers of user input) check the length first. */
static inline vec3 vec3_normalize(vec3 a) { return vec3_scale(a, 1.0 / vec3_length(a)); }

/* Returns the component selected by axis (0 = x, 1 = y, 2 = z). */
static inline double vec3_axis(vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }

/* Returns the component-wise minimum of a and b. */
static inline vec3 vec3_min(vec3 a, vec3 b) {
    return (vec3){a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}

/* Returns the component-wise maximum of a and b. */
static inline vec3 vec3_max(vec3 a, vec3 b) {
    return (vec3){a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}

/* Returns the largest of a's three components (a colour's brightest channel); a NaN component is
 * passed over, as fmax does. */
static inline double vec3_largest(vec3 a) { return fmax(a.x, fmax(a.y, a.z)); }

/* Returns true when every component is a finite number (not NaN, not infinite). */
static inline _Bool vec3_is_finite(vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* Returns a divided by its largest |component| (a itself when that is 0 or not finite): a vector of
 * the same direction whose length, between 1 and sqrt(3), and whose products with another such vector
 * neither overflow nor vanish, whatever a's scale. For tests that must not depend on scale, and for a
 * direction given in a scene before it is normalised. Below about 5.6e-309 (subnormal), 1 / largest is
 * infinite and the product would give NaN: such a vector is divided component by component instead. */
static inline vec3 vec3_unit_max(vec3 a) {
    double largest = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
    if (!(largest > 0.0 && isfinite(largest)))
        return a;
    double inverse = 1.0 / largest;
    return isfinite(inverse) ? vec3_scale(a, inverse) : vec3_make(a.x / largest, a.y / largest, a.z / largest);
}

/* Returns the length of a without overflow or underflow on the way (vec3_length squares its
 * components: 1e200 would give infinity and 1e-170 zero). Divided by its largest |component|, which
 * makes that component exactly 1 (times 1 / largest would not always: 1e-18 gave a length just short
 * of 1e-18), so that a vector along an axis has exactly its component's length. */
static inline double vec3_length_scaled(vec3 a) {
    double largest = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
    return largest > 0.0 && isfinite(largest)
               ? largest * vec3_length(vec3_make(a.x / largest, a.y / largest, a.z / largest))
               : vec3_length(a);
}

/* Returns true when a and b are parallel (or either is zero), whatever their lengths: the sine of the
 * angle between them is at most `sine`. */
static inline _Bool vec3_parallel(vec3 a, vec3 b, double sine) {
    vec3 ua = vec3_unit_max(a), ub = vec3_unit_max(b);
    return !(vec3_length(vec3_cross(ua, ub)) > sine * vec3_length(ua) * vec3_length(ub));
}

#endif
