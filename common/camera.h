/* camera.h: the pinhole camera, one primary ray through the centre of each pixel (chapter 1).
 *
 * The camera looks from `eye` towards `target`; `up` says which way is up in the picture; `vfov` is
 * the vertical field of view in degrees. Pixel (i, j) has i = 0 at the left and j = 0 at the TOP row,
 * the order in which PNG stores rows. Its ray passes through the pixel's centre (i + 0.5, j + 0.5),
 * exactly as POV-Ray shoots its rays, so a scene renders identically in both. */
#ifndef WHITTED_CAMERA_H
#define WHITTED_CAMERA_H

#include <stdbool.h>
#include <stddef.h>

#include "ray.h"

struct camera {
    vec3 eye;
    vec3 forward; /* unit vector from eye to target */
    vec3 right;   /* unit vector, points to the right of the picture */
    vec3 up;      /* unit vector, points to the top of the picture, orthogonal to forward and right */
    double half_height; /* tan(vfov / 2): half the image plane's height at distance 1 */
    double half_width;  /* half_height * width / height */
    int width, height;  /* in pixels */
};

/* Sets up `cam`. Returns false, and writes a reason into err (err_size bytes), when the set-up has no
 * picture: eye == target, up parallel to the viewing direction, vfov outside (0, 180) degrees, or a
 * size that is not positive. */
bool camera_init(struct camera *cam, vec3 eye, vec3 target, vec3 up, double vfov_degrees, int width,
                 int height, char *err, size_t err_size);

/* Returns the primary ray through the centre of pixel (i, j), j = 0 being the top row. The direction
 * has unit length. Valid for any i, j (pixels outside the image give rays outside the view). */
ray camera_ray(const struct camera *cam, int i, int j);

/* Returns the primary ray through point (x, y) of the picture, measured in pixels from its top-left
 * corner: pixel (i, j) covers [i, i + 1) x [j, j + 1), and camera_ray(cam, i, j) is the ray through
 * (i + 0.5, j + 0.5), to the last bit. Chapter 12 uses it for several rays per pixel. The direction has
 * unit length; valid for any x, y. */
ray camera_ray_through(const struct camera *cam, double x, double y);

#endif
