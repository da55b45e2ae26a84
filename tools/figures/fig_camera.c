/* fig_camera.c: chapter 1's figure, the pixel grid on the window and the camera's basis seen from the side. */
#include "camera.h"
#include "figures.h"
#include "svg.h"

/* The chapter's camera (eye at the origin, looking down -z, fov 90 degrees) on an 8 x 6 picture: the
 * same shape as its 320 x 240, with pixels large enough to see. */
#define GRID_WIDTH 8
#define GRID_HEIGHT 6
#define FOV_DEGREES 90.0

/* Where the ray of pixel (i, j) crosses the window at distance 1: (x along right, y along up'). */
static svg_point window_point(const struct camera *cam, int i, int j) {
    vec3 d = camera_ray(cam, i, j).direction;
    double along = vec3_dot(d, cam->forward);
    return (svg_point){vec3_dot(d, cam->right) / along, vec3_dot(d, cam->up) / along};
}

void figure_camera(FILE *out) {
    struct camera cam;
    char err[256];
    camera_init(&cam, vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), FOV_DEGREES, GRID_WIDTH,
                GRID_HEIGHT, err, sizeof err);
    double w = cam.half_width, h = cam.half_height;
    struct svg s;
    svg_begin(&s, out, 900, 440, "Chapter 1: the pixel grid on the window, and the camera seen from the side");

    /* Left: the window as the eye sees it. */
    svg_view(&s, 0, 0, 250, 215, 150);
    svg_text_px(&s, 250, 28, "middle", SVG_INK, "the window, seen from the eye (%d × %d pixels)", GRID_WIDTH,
                GRID_HEIGHT);
    for (int i = 0; i <= GRID_WIDTH; i++) {
        double x = -w + 2 * w * i / GRID_WIDTH;
        svg_line(&s, (svg_point){x, -h}, (svg_point){x, h}, SVG_MUTED, SVG_THIN);
    }
    for (int j = 0; j <= GRID_HEIGHT; j++) {
        double y = -h + 2 * h * j / GRID_HEIGHT;
        svg_line(&s, (svg_point){-w, y}, (svg_point){w, y}, SVG_MUTED, SVG_THIN);
    }
    for (int j = 0; j < GRID_HEIGHT; j++)
        for (int i = 0; i < GRID_WIDTH; i++)
            svg_dot(&s, window_point(&cam, i, j), i == 0 && j == 0 ? SVG_RAY : SVG_MUTED);
    svg_rect(&s, (svg_point){-w, -h}, (svg_point){w, h}, SVG_INK, SVG_SOLID, 0);
    svg_text_px(&s, 250, 425, "middle", SVG_RAY, "red: pixel (0, 0), whose ray passes through its centre (0.5, 0.5)");
    svg_text(&s, (svg_point){-w, -h}, 0, 20, "start", SVG_INK, "i = 0 → %d", GRID_WIDTH - 1);
    svg_text(&s, (svg_point){-w, h}, -8, 15, "end", SVG_INK, "j = 0");
    svg_text(&s, (svg_point){-w, -h}, -8, -5, "end", SVG_INK, "j = %d", GRID_HEIGHT - 1);
    svg_line(&s, (svg_point){0, 0}, (svg_point){0.6, 0}, SVG_NORMAL, SVG_ARROW);
    svg_line(&s, (svg_point){0, 0}, (svg_point){0, 0.6}, SVG_NORMAL, SVG_ARROW);
    /* in the corner of a cell, clear of its dot and of the grid lines */
    svg_text(&s, (svg_point){0.6, 0}, 12, -4, "start", SVG_NORMAL, "right");
    svg_text(&s, (svg_point){0, 0.6}, 6, 4, "start", SVG_NORMAL, "up′");
    /* forward points into the page: a circle with a cross, the tail of an arrow seen from behind */
    svg_circle(&s, (svg_point){0, 0}, 0.07, SVG_NORMAL, SVG_THIN, 0);
    svg_line(&s, (svg_point){-0.05, -0.05}, (svg_point){0.05, 0.05}, SVG_NORMAL, SVG_THIN);
    svg_line(&s, (svg_point){-0.05, 0.05}, (svg_point){0.05, -0.05}, SVG_NORMAL, SVG_THIN);
    svg_text_px(&s, 250, 405, "middle", SVG_NORMAL, "⊗ at the centre: forward, into the page"); /* the grid has no room */
    svg_text(&s, (svg_point){w, -h}, 0, 20, "end", SVG_INK, "half_width = %.4g", w);
    svg_text(&s, (svg_point){w, h}, 8, 15, "start", SVG_INK, "+%.4g", h);
    svg_text(&s, (svg_point){w, -h}, 8, 0, "start", SVG_INK, "−%.4g", h);

    /* Right: the same camera from its right-hand side; forward runs to the right, up' up. */
    svg_view(&s, 0, 0, 590, 215, 140);
    svg_text_px(&s, 700, 28, "middle", SVG_INK, "seen from the side");
    svg_point eye = {0, 0};
    svg_line(&s, (svg_point){1, -h}, (svg_point){1, h}, SVG_INK, SVG_SOLID);
    svg_line(&s, eye, (svg_point){1, h}, SVG_MUTED, SVG_DASHED);
    svg_line(&s, eye, (svg_point){1, -h}, SVG_MUTED, SVG_DASHED);
    svg_angle(&s, eye, (svg_point){1, -h}, (svg_point){1, h}, 38, SVG_MUTED);
    svg_text(&s, eye, 50, 30, "start", SVG_MUTED, "fov = %.0f°", FOV_DEGREES); /* between forward and the lower edge */
    svg_line(&s, eye, (svg_point){1, 0}, SVG_NORMAL, SVG_ARROW);
    svg_text(&s, (svg_point){0.55, 0}, 0, -8, "middle", SVG_NORMAL, "forward");
    svg_line(&s, eye, (svg_point){0, 0.55}, SVG_NORMAL, SVG_ARROW);
    svg_text(&s, (svg_point){0, 0.55}, 0, -8, "middle", SVG_NORMAL, "up′");
    svg_dot(&s, eye, SVG_INK);
    svg_text(&s, eye, -10, 5, "end", SVG_INK, "eye");
    svg_text(&s, eye, -10, 24, "end", SVG_NORMAL, "right ⊙");
    svg_point top_row = {1, window_point(&cam, 0, 0).y};
    svg_line(&s, eye, svg_along(eye, top_row, 1.55), SVG_RAY, SVG_ARROW);
    svg_dot(&s, top_row, SVG_RAY);
    svg_text(&s, top_row, 8, 20, "start", SVG_RAY, "row j = 0: y = %.4g", top_row.y);
    svg_text(&s, (svg_point){1, h}, 0, -12, "middle", SVG_INK, "half_height = tan(fov/2) = %.4g", h);
    svg_text(&s, (svg_point){1, -h}, 0, 22, "middle", SVG_INK, "the window, at distance 1");
    svg_end(&s);
}
