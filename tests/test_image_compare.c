/* test_image_compare.c: the picture comparison behind the image tests and `make compare`, on small
 * pictures whose statistics can be worked out by hand. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "image_compare.h"

Test(image_compare, identical_pictures_differ_by_nothing) {
    const uint8_t a[2 * 2 * 3] = {1, 2, 3, 40, 50, 60, 255, 0, 7, 9, 9, 9};
    struct image_difference d = image_compare(a, a, 2, 2);
    cr_assert_eq(d.max, 0);
    cr_assert_eq(d.mean, 0.0);
    cr_assert_eq(d.within_1, 1.0);
    cr_assert_eq(d.within_2, 1.0);
    cr_assert_eq(d.pixels_over_2, 0);
    cr_assert(isinf(d.psnr) && d.psnr > 0, "psnr %f", d.psnr);
    cr_assert(image_difference_agrees(&d));
}

Test(image_compare, one_channel_three_levels_off_counts_as_a_pixel_over_2) {
    uint8_t a[2 * 2 * 3] = {0}, b[2 * 2 * 3] = {0};
    b[4] = 3; /* pixel 1, green: 3 levels */
    b[9] = 1; /* pixel 3, red: 1 level */
    struct image_difference d = image_compare(a, b, 2, 2);
    cr_assert_eq(d.max, 3);
    cr_assert_float_eq(d.mean, 4.0 / 12.0, 1e-12);
    cr_assert_float_eq(d.within_1, 3.0 / 4.0, 1e-12, "pixels 0, 2 and 3 are within 1");
    cr_assert_float_eq(d.within_2, 3.0 / 4.0, 1e-12);
    cr_assert_eq(d.pixels_over_2, 1);
    /* mean squared error (9 + 1) / 12 */
    cr_assert_float_eq(d.psnr, 10.0 * log10(255.0 * 255.0 / (10.0 / 12.0)), 1e-9);
}

Test(image_compare, the_agreement_rule_sits_exactly_at_the_oracles_thresholds) {
    struct image_difference d = {.max = 50, .mean = AGREEMENT_MAX_MEAN, .within_1 = 0.99,
                                 .within_2 = AGREEMENT_MIN_WITHIN_2, .psnr = 60.0, .pixels_over_2 = 1};
    cr_assert(image_difference_agrees(&d), "exactly at both thresholds: agrees");
    d.within_2 = 0.9989;
    cr_assert_not(image_difference_agrees(&d), "too few pixels within 2");
    d.within_2 = 1.0;
    d.mean = 0.0501;
    cr_assert_not(image_difference_agrees(&d), "mean too large");
}

Test(image_compare, side_by_side_puts_the_first_picture_on_the_left) {
    const uint8_t a[2 * 1 * 3] = {1, 2, 3, 4, 5, 6}, b[2 * 1 * 3] = {7, 8, 9, 10, 11, 12};
    uint8_t out[4 * 1 * 3];
    image_compare_side_by_side(a, b, 2, 1, out);
    const uint8_t expected[4 * 1 * 3] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    cr_assert_arr_eq(out, expected, sizeof expected);
}

Test(image_compare, the_difference_picture_amplifies_and_clamps) {
    const uint8_t a[1 * 2 * 3] = {10, 0, 200, 5, 5, 5}, b[1 * 2 * 3] = {12, 100, 200, 5, 4, 6};
    uint8_t out[1 * 2 * 3];
    image_compare_difference(a, b, 1, 2, 16, out);
    const uint8_t expected[1 * 2 * 3] = {32, 255, 0, 0, 16, 16};
    cr_assert_arr_eq(out, expected, sizeof expected);
}
