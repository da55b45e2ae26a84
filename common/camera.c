/* camera.c: builds the camera basis and the primary ray of each pixel (chapter 1). */
#include "camera.h"

#include "shape.h" /* KEY_NUMBER_SHOWN */

#include <stdio.h>

/* Up vectors closer than this to the viewing direction (|sin angle| below it) give no usable basis. */
#define CAMERA_MIN_UP_SINE 1e-9
/* The shortest view (eye to target) and up vector taken: below about 1e-154 the squares in a length
 * vanish, and a vector of 1e-310 would be read as zero (or give NaN); no scene is drawn at such a
 * scale (sizes end at 1e-18, as a mesh's or an area light's). */
#define CAMERA_MIN_LENGTH 1e-18

bool camera_init(struct camera *cam, vec3 eye, vec3 target, vec3 up, double vfov_degrees, int width,
                 int height, char *err, size_t err_size) {
    vec3 view = vec3_sub(target, eye);
    if (vec3_length_scaled(view) == 0.0) {
        snprintf(err, err_size, "camera eye and target are the same point");
        return false;
    }
    if (vec3_length_scaled(view) < CAMERA_MIN_LENGTH) {
        snprintf(err, err_size, "camera eye and target are " KEY_NUMBER_SHOWN " apart; they must be at least %g apart",
                 KEY_NUMBER(vec3_length_scaled(view)), CAMERA_MIN_LENGTH);
        return false;
    }
    if (!(vfov_degrees > 0.0 && vfov_degrees < 180.0)) {
        snprintf(err, err_size, "camera fov must be between 0 and 180 degrees, got " KEY_NUMBER_SHOWN,
                 KEY_NUMBER(vfov_degrees));
        return false;
    }
    if (width <= 0 || height <= 0) {
        snprintf(err, err_size, "image size must be positive, got %d x %d", width, height);
        return false;
    }
    double up_length = vec3_length_scaled(up);
    if (up_length > 0.0 && up_length < CAMERA_MIN_LENGTH) {
        snprintf(err, err_size, "camera up vector is " KEY_NUMBER_SHOWN " long; it must be at least %g long",
                 KEY_NUMBER(up_length), CAMERA_MIN_LENGTH);
        return false;
    }
    vec3 forward = vec3_normalize(view);
    vec3 side = vec3_cross(forward, up);
    if (!(up_length > 0.0) || vec3_length(side) <= CAMERA_MIN_UP_SINE * up_length) {
        snprintf(err, err_size, "camera up vector is zero or parallel to the viewing direction");
        return false;
    }
    cam->eye = eye;
    cam->forward = forward;
    cam->right = vec3_normalize(side);
    cam->up = vec3_cross(cam->right, forward);
    cam->half_height = tan(vfov_degrees * M_PI / 360.0);
    cam->half_width = cam->half_height * (double)width / (double)height;
    cam->width = width;
    cam->height = height;
    return true;
}

/* TASK 1.1: the primary ray through a pixel centre */
ray camera_ray(const struct camera *cam, int i, int j) {
    /* Pixel centre in [-1, 1] image-plane coordinates: x grows to the right, y grows upwards (row j is
     * counted down from the top, so the centre is height - j - 0.5 rows above the bottom edge). */
    double x = 2.0 * (i + 0.5) / cam->width - 1.0;
    double y = 2.0 * (cam->height - j - 0.5) / cam->height - 1.0;
    /* The window's half-width and half-height as vectors first, then x and y times them: POV-Ray's
     * order (see docs/01-camera.md), so that the ray is its ray to the last bit. */
    vec3 half_across = vec3_scale(cam->right, cam->half_width), half_up = vec3_scale(cam->up, cam->half_height);
    vec3 direction = cam->forward;
    direction = vec3_add_scaled(direction, half_across, x);
    direction = vec3_add_scaled(direction, half_up, y);
    return (ray){cam->eye, vec3_normalize(direction)};
}

/* TASK 1.1 ALSO: the primary ray through any point of the picture (camera_ray at a pixel centre) */
ray camera_ray_through(const struct camera *cam, double x, double y) {
    double u = 2.0 * x / cam->width - 1.0, v = 2.0 * (cam->height - y) / cam->height - 1.0; /* [-1, 1], v upwards */
    vec3 half_across = vec3_scale(cam->right, cam->half_width), half_up = vec3_scale(cam->up, cam->half_height);
    vec3 direction = vec3_add_scaled(cam->forward, half_across, u);
    direction = vec3_add_scaled(direction, half_up, v);
    return (ray){cam->eye, vec3_normalize(direction)};
}
