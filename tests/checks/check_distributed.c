/* check_distributed.c: the coursework checks of chapter 13: POV-Ray's rule for an area light's shadow
 * and the thin lens's rays, on set-ups whose answer is worked out by hand (the coursework kit). */
#include <math.h>
#include <stdio.h>

#include "box.h"
#include "check.h"
#include "scene.h"
#include "soft_shadow.h"
#include "stats.h"
#include "thin_lens.h"
#include "world.h"

/* Shares and positions are compared within this: far above rounding, far below any mistake. */
#define DISTRIBUTED_TOLERANCE 1e-9

/* ---- 13.1 the area light's shadow ------------------------------------------------------------ */

/* The share of the first light of `lines` reaching the origin, and the shadow rays it took. False with
 * the reason in why when the check's own scene does not parse. */
static bool share_at_origin(const char *lines, vec3 *share, unsigned long *rays, char *why, size_t why_size) {
    static const struct shape_kind *const kinds[] = {&box_kind, NULL};
    char text[1024];
    snprintf(text, sizeof text, "camera eye 0 0 5  target 0 0 0  fov 40\nimage 8 8\n%s\n", lines);
    struct scene s;
    struct world w;
    if (!check_scene_world(text, kinds, &s, &w, why, why_size))
        return false;
    stats_reset_thread();
    *share = soft_shadow_filtered(&w, vec3_make(0, 0, 0), &s.lights[0]);
    *rays = (unsigned long)stats_thread.shadow_rays;
    world_free(&w);
    scene_free(&s);
    return true;
}

/* A light 10 above the origin, 3 x 3 points from x = -1 to 1; the wall hides its column x = -1 only. */
#define LIGHT "light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 3 3"
#define WALL "box min -0.6 4.9 -3 max -0.45 5.1 3"

CHECK(check_area_open_sky) {
    vec3 share;
    unsigned long rays;
    if (!share_at_origin(LIGHT, &share, &rays, why, why_size))
        return false;
    if (check_vec_near(share, vec3_make(1, 1, 1), DISTRIBUTED_TOLERANCE) && rays == 9)
        return true;
    char s[64];
    snprintf(why, why_size, "a 3 x 3 area light with nothing in the way, no adaptive key: every point is traced "
             "(9 shadow rays) and all the light arrives, (1, 1, 1); your code gave %s with %lu shadow rays%s",
             check_vec_text(share, s), rays, rays < 9 ? ": without adaptive every rectangle is quartered" : "");
    return false;
}

CHECK(check_area_weights) {
    vec3 share;
    unsigned long rays;
    if (!share_at_origin(LIGHT "\n" WALL, &share, &rays, why, why_size))
        return false;
    if (check_near(share.x, 0.75, DISTRIBUTED_TOLERANCE) && rays == 9)
        return true;
    snprintf(why, why_size, "a 3 x 3 area light whose column x = -1 is hidden: the whole is the mean of its four "
             "quarters, each the mean of its corners, so the edge columns weigh 1/4 and the middle one 1/2: 0.75 "
             "arrives; your code gave %.6g with %lu shadow rays%s", share.x, rays,
             check_near(share.x, 2.0 / 3.0, 1e-6) ? ": a plain mean of the 9 points is not POV-Ray's rule"
             : check_near(share.x, 1, 1e-6) ? ": nothing was hidden: do the points run from -1/2 to +1/2 of each axis "
                                               "around the light's position?"
                                             : "");
    return false;
}

CHECK(check_area_adaptive) {
    vec3 share;
    unsigned long rays;
    if (!share_at_origin("light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 9 9 adaptive 0", &share, &rays,
                         why, why_size))
        return false;
    if (rays != 4 || !check_near(share.x, 1, DISTRIBUTED_TOLERANCE)) {
        snprintf(why, why_size, "a 9 x 9 light with adaptive 0 and nothing in the way: the four corners agree, so "
                 "nothing is quartered: 4 shadow rays and all the light; your code took %lu and gave %.6g", rays,
                 share.x);
        return false;
    }
    if (!share_at_origin("light position 0 10 0 colour 0.03 0.03 0.03 axis1 2 0 0 axis2 0 0 2 samples 9 9 "
                         "adaptive 0\n" WALL, &share, &rays, why, why_size))
        return false;
    if (rays == 4 && check_near(share.x, 0.5, DISTRIBUTED_TOLERANCE))
        return true;
    snprintf(why, why_size, "a dim 9 x 9 light (colour 0.03) with adaptive 0, its left corners hidden: corners differ "
             "by the light they let through, here 3 x 0.03 = 0.09, not more than 0.1, so nothing is quartered: 4 "
             "shadow rays, and the mean of the corners, 0.5; your code took %lu and gave %.6g%s", rays, share.x,
             rays > 4 ? ": compare light colour times share, not the shares alone" : "");
    return false;
}

/* ---- 13.2 the thin lens ---------------------------------------------------------------------- */

/* A camera looking down -z from (0, 0, 5), 64 x 48 pixels, with a lens of diameter `aperture` focused
 * on the plane z = 0, 37 lens points. */
static void lens_at(struct thin_lens *t, struct camera *c, double aperture) {
    char err[256];
    camera_init(c, vec3_make(0, 0, 5), vec3_make(0, 0, 0), vec3_make(0, 1, 0), 40, 64, 48, err, sizeof err);
    struct lens l = {aperture, vec3_make(0, 0, 0), 37};
    thin_lens_init(t, c, &l, 0);
}

/* Where ray r meets the plane z = 0, as a point of the picture (pixels from the top-left corner). */
static void image_point(const struct camera *c, ray r, double *x, double *y) {
    vec3 p = ray_at(r, -r.origin.z / r.direction.z);
    *x = (p.x / 5 / c->half_width + 1) * c->width / 2;
    *y = (1 - p.y / 5 / c->half_height) * c->height / 2;
}

CHECK(check_lens_focus) {
    struct thin_lens t;
    struct camera c;
    lens_at(&t, &c, 0.5);
    for (int k = 0; k < t.samples; k++) {
        ray r = thin_lens_ray(&t, 20.5, 10.5, k);
        double x, y, shift = 1.0 / 32;
        image_point(&c, r, &x, &y);
        bool on_lens = fabs(r.origin.z - 5) < DISTRIBUTED_TOLERANCE && hypot(r.origin.x, r.origin.y) < 0.27;
        bool in_pixel = x > 20 - shift - 1e-9 && x < 21 - shift + 1e-9 && y > 10 - shift - 1e-9 && y < 11 - shift + 1e-9;
        if (!on_lens || !in_pixel || !check_near(vec3_length(r.direction), 1, DISTRIBUTED_TOLERANCE)) {
            char o[64], d[64];
            snprintf(why, why_size, "lens ray %d of image point (20.5, 10.5), lens diameter 0.5 focused on z = 0: it "
                     "starts at %s and goes along %s; it must start on the lens (z = 5, within about 0.25 of the eye), "
                     "have unit length, and cross z = 0 where the pinhole's ray through a point of the pixel "
                     "(moved 1/32 up and left) does; it crosses at image point (%.4g, %.4g)%s", k,
                     check_vec_text(r.origin, o), check_vec_text(r.direction, d), x, y,
                     !on_lens ? ": the lens point is scaled by the aperture, along right and up" : "");
            return false;
        }
    }
    return true;
}

CHECK(check_lens_spread) {
    struct thin_lens t;
    struct camera c;
    lens_at(&t, &c, 0.5);
    vec3 sum = vec3_make(0, 0, 0);
    double farthest = 0;
    for (int k = 0; k < t.samples; k++) {
        ray r = thin_lens_ray(&t, 20.5, 10.5, k);
        sum = vec3_add(sum, r.origin);
        farthest = fmax(farthest, hypot(r.origin.x, r.origin.y));
    }
    vec3 mean = vec3_scale(sum, 1.0 / t.samples);
    if (hypot(mean.x, mean.y) < 0.5 * t.cell && farthest > 0.2) {
        lens_at(&t, &c, 0.0);
        ray r = thin_lens_ray(&t, 20.5, 10.5, 5);
        if (vec3_length(vec3_sub(r.origin, c.eye)) < DISTRIBUTED_TOLERANCE)
            return true;
        snprintf(why, why_size, "with aperture 0 the lens is a pinhole: every ray starts at the eye");
        return false;
    }
    char m[64];
    snprintf(why, why_size, "the 37 lens rays of one image point (lens diameter 0.5) start at points spread over the "
             "lens around the eye: their mean is %s, the farthest %.4g from the eye; grid point k (t->grid) plus its "
             "jitter, times the aperture, along the camera's right and up", check_vec_text(mean, m), farthest);
    return false;
}
