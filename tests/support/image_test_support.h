/* image_test_support.h: running chapter programs and POV-Ray from tests, and comparing their pictures.
 *
 * The tests run with the repository as working directory. WHITTED_BUILD names the build folder whose
 * chapter programs are tested (build, or build/san for the sanitizer run). */
#ifndef WHITTED_IMAGE_TEST_SUPPORT_H
#define WHITTED_IMAGE_TEST_SUPPORT_H

#include <stdbool.h>

#include "image_compare.h"

/* Folder for everything the image tests write. */
#define TEST_OUT "out/test"

/* The regression rule against reference_images/: floating-point noise moves a handful of pixels by one
 * level (values exactly on a half level), a real change moves many pixels or moves them far. */
#define REGRESSION_MIN_WITHIN_1 0.9995 /* at most 1 pixel in 2000 more than 1 level off */
#define REGRESSION_MAX_MEAN 0.01       /* levels, averaged over all channels of all pixels */

/* Returns the scene file of chapter n (1..16), e.g. "scenes/02-sphere.scene". */
const char *chapter_scene(int n);

/* Returns the program of chapter n in the build under test, e.g. "build/chapter-02". */
const char *chapter_program(int n);

/* Runs chapter n on `scene`, writing `png`, with extra command-line words `extra` (may be ""). Returns
 * the exit status (or -1 if the program could not be run). */
int render_chapter(int n, const char *scene, const char *png, const char *extra);

/* Draws chapter n's own scene as the chapter draws it with no options, to TEST_OUT/chapter-NN.png, whose
 * path it puts in png (size bytes), once in a run of the tests: the chapter's reference test, its POV-Ray
 * test and any other test that needs that very picture share it, and it takes a few seconds on chapter 3.
 * The first test to ask draws it while holding a lock, and the others wait for it; a file beside it
 * (.run) names the run that drew it, so a picture an earlier run left is drawn again. Returns the exit
 * status of the chapter's run (0 when the picture was drawn earlier in this run). */
int render_own_scene(int n, char *png, size_t size);

/* Runs chapter n with the command-line words `arguments` (within a generous time bound, so a program
 * that hangs fails the test) and fails the current test unless it exits with `status` and prints
 * `expected` (on standard output or error). */
void expect_chapter_run(int n, const char *arguments, int status, const char *expected);

/* Runs the chapter program `program` (a path) as render_chapter does. */
int render_with(const char *program, const char *scene, const char *png, const char *extra);

/* Returns the path of the deliberately wrong program `name` that the Makefile builds for the tests
 * from tests/mutants/NAME.patch, e.g. "build/mutant-highlight-times-pigment". */
const char *mutant_program(const char *name);

/* Writes chapter n's POV-Ray twin of `scene` and renders it with POV-Ray to `png` at the scene's size,
 * as the twin's antialias comment lines say (chapter 12): with POV-Ray's anti-aliasing options, or at
 * n times the size averaged down by n x n blocks. Returns true on success. */
bool render_povray(int n, const char *scene, const char *png);

/* Reads two PNG files and compares them; fails the current test if either cannot be read or their
 * sizes differ. */
struct image_difference compare_png(const char *a, const char *b);

/* Returns true when d passes the regression rule above. */
bool regression_passes(const struct image_difference *d);

/* Copies scene file `from` to `to` (which must be in the same folder, so relative mesh paths still
 * work), replacing the first occurrence of each text olds[k] by news[k] (count pairs). The line that
 * starts with "camera" is replaced by `camera_line` when it is not NULL. Fails the test if an old text
 * is not found. */
void write_scene_variant(const char *from, const char *to, const char *const *olds, const char *const *news,
                         int count, const char *camera_line);

/* Returns a camera line for the scene in `path` with eye and target moved right by `pixels` pixel
 * widths (measured at the target's distance). */
const char *shifted_camera_line(const char *path, double pixels);

/* Renders chapter n's own scene with the line `old_line` replaced by `new_line`, and its width and height
 * divided by `divisor` (1 keeps the scene's size), by chapter n to TEST_OUT/NAME-ours.png, and its twin
 * by POV-Ray to TEST_OUT/NAME-povray.png (the variant scene file is written beside the scene and removed
 * afterwards); reports and returns their difference. Fails the current test when either cannot render. */
struct image_difference variant_against_povray(int n, const char *old_line, const char *new_line, const char *name,
                                              int divisor);

/* The share of pixels within one level of POV-Ray that the chapters 12 and 13 variants promise. */
#define VARIANT_AGREEMENT_MIN_WITHIN_1 0.9999

/* variant_against_povray, expecting (not asserting) VARIANT_AGREEMENT_MIN_WITHIN_1 of the pixels within
 * one level of POV-Ray's. */
void expect_variant_agrees_with_povray(int n, const char *old_line, const char *new_line, const char *name,
                                       int divisor);

/* Prints one line "what: max M, mean X, within 1: P%, within 2: Q%" to stderr for the log. */
void report_difference(const char *what, const struct image_difference *d);

#endif
