/* check_antialias.c: the coursework checks of chapter 12: the regular grid's box filter and POV-Ray's
 * colour difference test, on pictures whose answer is worked out by hand (the coursework kit). */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "supersample.h"

/* Means and differences are compared within this: far above rounding, far below any mistake. */
#define ANTIALIAS_TOLERANCE 1e-9
/* Halvings of [0, 4] that find where a wrong supersample_differ turns false, to 4 / 2^30. */
#define DIFFER_BISECTIONS 30

/* ---- 12.1 supersample_grid ------------------------------------------------------------------- */

/* A picture whose colour at (x, y) is (x, y, 1), counting how often it is looked at. */
struct position_view {
    int looks;
};

static vec3 position_colour(const void *context, double x, double y) {
    ((struct position_view *)context)->looks++;
    return vec3_make(x, y, 1);
}

/* The mean of (x, y) over a symmetric grid is the pixel's centre, for every n: samples at the cells'
 * corners instead of their centres pull it up and to the left. */
CHECK(check_grid_centres) {
    static const int sizes[] = {1, 2, 3, 4};
    for (int k = 0; k < 4; k++) {
        int n = sizes[k];
        struct position_view seen = {0};
        struct sample_view view = {position_colour, &seen};
        check_calling("supersample_grid", "pixel (5, 2), n = %d, of a picture whose colour is (x, y, 1)", n);
        vec3 got = supersample_grid(&view, 5, 2, n);
        char g[64];
        if (seen.looks != n * n) {
            snprintf(why, why_size, "supersample_grid(view, 5, 2, %d) looked at the picture %d times; an n x n grid "
                     "is n * n = %d samples", n, seen.looks, n * n);
            return false;
        }
        if (!check_vec_near(got, vec3_make(5.5, 2.5, 1), ANTIALIAS_TOLERANCE)) {
            snprintf(why, why_size, "supersample_grid(view, 5, 2, %d) on a picture whose colour is (x, y, 1): the mean "
                     "of the cells' centres is the pixel's centre (5.5, 2.5, 1); yours is %s%s", n,
                     check_vec_text(got, g),
                     got.z > 1 + ANTIALIAS_TOLERANCE ? ": a sum, not a mean?"
                     : got.x < 5.5 && got.y < 2.5  ? ": samples at the cells' corners, not their centres?"
                                                    : "");
            return false;
        }
    }
    return true;
}

/* White left of x = 7.3, black from there on. */
static vec3 edge_colour(const void *context, double x, double y) {
    (void)context;
    (void)y;
    return x < 7.3 ? vec3_make(1, 1, 1) : vec3_make(0, 0, 0);
}

/* An edge 0.3 of the way across pixel 7: with n = 10, the first 3 columns of samples are white. */
CHECK(check_grid_edge) {
    struct sample_view view = {edge_colour, NULL};
    check_calling("supersample_grid", "pixel (7, 0), n = 10, of a picture white left of x = 7.3, black from there");
    vec3 got = supersample_grid(&view, 7, 0, 10);
    if (check_near(got.x, 0.3, ANTIALIAS_TOLERANCE))
        return true;
    snprintf(why, why_size, "supersample_grid(view, 7, 0, 10) on an edge at x = 7.3 (white to its left): 3 columns of "
             "10 are white, so the pixel is 0.3 grey; yours is %.4g", got.x);
    return false;
}

/* ---- 12.2 supersample_differ ----------------------------------------------------------------- */

CHECK(check_differ_plain) {
    check_calling("supersample_differ", "black and white, and two equal colours (0.4, 0.5, 0.6)");
    if (!supersample_differ(vec3_make(0, 0, 0), vec3_make(1, 1, 1), 0.3)) {
        snprintf(why, why_size, "supersample_differ(black, white, 0.3) is false; their distance is 3");
        return false;
    }
    if (supersample_differ(vec3_make(0.4, 0.5, 0.6), vec3_make(0.4, 0.5, 0.6), 0.3)) {
        snprintf(why, why_size, "supersample_differ(c, c, 0.3) is true for two equal colours");
        return false;
    }
    if (!supersample_differ(vec3_make(0.4, 0.5, 0.6), vec3_make(0.4, 0.5, 0.6), 0.0)) {
        snprintf(why, why_size, "supersample_differ(c, c, 0) is false: a distance of 0 is at least the threshold 0 "
                 "(POV-Ray's test is >=)");
        return false;
    }
    return true;
}

/* POV-Ray compares channels raised to 1 / 2.5: 0.01 becomes 0.01^0.4 = 0.1585, so a step from black to
 * 0.01 in one channel differs at threshold 0.15 but not at 0.16; compared linearly it would be 0.01. */
CHECK(check_differ_gamma) {
    vec3 black = vec3_make(0, 0, 0), dark = vec3_make(0.01, 0, 0);
    check_calling("supersample_differ", "(0.01, 0, 0) and black, thresholds 0.15 and 0.16");
    bool at_015 = supersample_differ(dark, black, 0.15), at_016 = supersample_differ(dark, black, 0.16);
    if (at_015 && !at_016)
        return true;
    snprintf(why, why_size, "supersample_differ((0.01, 0, 0), black, t) is %s for t = 0.15 and %s for t = 0.16; the "
             "distance is 0.01^(1/2.5) = 0.1585, so true then false%s", at_015 ? "true" : "false",
             at_016 ? "true" : "false",
             !at_015 ? ": compared without POV-Ray's gamma (the power 1 / ANTIALIAS_GAMMA)?" : "");
    return false;
}

/* The three channels' differences add up; a negative channel counts as 0. */
CHECK(check_differ_channels) {
    double one = pow(0.2, 0.4) - pow(0.1, 0.4); /* 0.1272 */
    vec3 a = vec3_make(0.2, 0.2, 0.2), b = vec3_make(0.1, 0.1, 0.1);
    check_calling("supersample_differ", "(0.2, 0.2, 0.2) and (0.1, 0.1, 0.1), and (-1, 0, 0) and (0.01, 0, 0)");
    if (!supersample_differ(a, b, 3 * one - 1e-6) || supersample_differ(a, b, 3 * one + 1e-6)) {
        /* Where the student's answer turns from true to false: the distance their code computes. */
        double low = 0, high = 4;
        check_calling("supersample_differ", "(0.2, 0.2, 0.2) and (0.1, 0.1, 0.1), thresholds from 0 to 4");
        bool at_low = supersample_differ(a, b, low), at_high = supersample_differ(a, b, high);
        char seen[160];
        if (at_low && !at_high) {
            for (int k = 0; k < DIFFER_BISECTIONS; k++) {
                double middle = 0.5 * (low + high);
                if (supersample_differ(a, b, middle))
                    low = middle;
                else
                    high = middle;
            }
            snprintf(seen, sizeof seen, "your answer turns from true to false at %.4f%s", low,
                     fabs(low - one) < 1e-3 ? " (one channel's difference: the other two forgotten?)" : "");
        } else
            snprintf(seen, sizeof seen, "your answer is %s at threshold 0 and %s at 4, so it measures no distance",
                     at_low ? "true" : "false", at_high ? "true" : "false");
        snprintf(why, why_size, "supersample_differ((0.2, 0.2, 0.2), (0.1, 0.1, 0.1), t): the distance is the sum of "
                 "the three channels' differences, 3 x (0.2^0.4 - 0.1^0.4) = %.4f, so the answer is true below it and "
                 "false above it; %s", 3 * one, seen);
        return false;
    }
    if (!supersample_differ(vec3_make(-1, 0, 0), vec3_make(0.01, 0, 0), 0.1)) {
        snprintf(why, why_size, "supersample_differ((-1, 0, 0), (0.01, 0, 0), 0.1) is false: a negative channel "
                 "counts as 0, so the distance is 0.01^0.4 = 0.1585 (the power of a negative number is not a number, "
                 "and no comparison with it is true)");
        return false;
    }
    return true;
}
