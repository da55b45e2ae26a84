/* test_io.c: hostile inputs and outputs: FIFOs, devices, symbolic links and standard output as -o,
 * FIFOs as inputs, one file named twice, over-long names, control characters in messages, meshes
 * placed out of range, 100,000 materials, and the memory a large picture takes. */
#include <criterion/criterion.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include "camera.h"
#include "render.h"
#include "stats.h"
#include "image.h"
#include "image_test_support.h"
#include "mesh.h"
#include "name_index.h"
#include "outfile.h"
#include "palette_png.h"
#include "scene.h"
#include "sphere.h"
#include "test_support.h"
#include "text_escape.h"

/* A bound for the commands run here that are not chapter runs (those have expect_chapter_run's). */
#define IO_TIMEOUT "timeout 60"

/* Returns TEST_OUT/name in a static buffer (one of four, so a few can be used together), after making
 * the folder and removing whatever had that name. */
static const char *fresh(const char *name) {
    static char paths[4][256];
    static int next;
    char *path = paths[next++ % 4];
    mkdir("out", 0755);
    mkdir(TEST_OUT, 0755);
    snprintf(path, 256, TEST_OUT "/%s", name);
    unlink(path);
    return path;
}

/* Writes `text` to TEST_OUT/name and returns its path. */
static const char *text_file(const char *name, const char *text) {
    const char *path = fresh(name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
    return path;
}

/* Fails unless `path` is a PNG of width x height. */
static void expect_png(const char *path, int width, int height) {
    char err[512];
    int w = 0, h = 0;
    uint8_t *rgb = image_read_rgb(path, &w, &h, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    cr_assert_eq(w, width);
    cr_assert_eq(h, height);
    free(rgb);
}

/* ---- palette PNGs -------------------------------------------------------------------------------- */

/* Writes `size` bytes to TEST_OUT/name and returns its path. */
static const char *bytes_file(const char *name, const uint8_t *bytes, size_t size) {
    const char *path = fresh(name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(bytes, 1, size, f), size);
    fclose(f);
    return path;
}

/* A palette of two colours in an 8-bit file is read as its colours; a pixel naming colour 2 is refused,
 * where stb_image alone gave the colour of whatever its table held there, another on every run. */
Test(io, a_palette_png_is_read_as_its_colours_and_a_pixel_past_its_palette_is_refused) {
    char err[512] = "";
    int w = 0, h = 0;
    uint8_t *rgb = image_read_rgb(bytes_file("io-palette.png", palette_png_checkerboard,
                                             sizeof palette_png_checkerboard), &w, &h, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    cr_assert_eq(w, 4);
    cr_assert_eq(h, 4);
    for (int k = 0; k < 16; k++) {
        bool red = (k % 4 + k / 4) % 2 == 0;
        const uint8_t want[3] = {red ? 255 : 0, 0, red ? 0 : 255};
        cr_expect_arr_eq(rgb + 3 * k, want, 3, "pixel (%d, %d)", k % 4, k / 4);
    }
    free(rgb);
    const char *past = bytes_file("io-palette-past.png", palette_png_index_past_end, sizeof palette_png_index_past_end);
    cr_assert_null(image_read_rgb(past, &w, &h, err, sizeof err));
    char expected[512];
    snprintf(expected, sizeof expected,
             "%s: damaged: a pixel's palette index is past the end of its palette (2 colours)", past);
    cr_assert_str_eq(err, expected);
}

/* stb_image gives no reason for some damage (here, compressed data no deflate stream starts with); the
 * message says so instead of printing a null pointer. */
Test(io, a_picture_the_decoder_fails_on_without_a_reason_says_so) {
    uint8_t damaged[sizeof palette_png_checkerboard];
    memcpy(damaged, palette_png_checkerboard, sizeof damaged);
    memset(damaged + 61, 0xff, 13); /* the image data after its two bytes of zlib header */
    const char *path = bytes_file("io-damaged.png", damaged, sizeof damaged);
    char err[512] = "", expected[512];
    int w = 0, h = 0;
    cr_assert_null(image_read_rgb(path, &w, &h, err, sizeof err));
    snprintf(expected, sizeof expected, "%s: cannot read image: the decoder gives no reason", path);
    cr_assert_str_eq(err, expected);
}

/* build/compare writes SIDE.png and DIFF.png only when neither names a picture it reads or the other, and
 * both can be created: it wrote its side-by-side picture over its first input, with exit status 1. */
/* Runs a tool's `command`, which must exit with status 2 printing exactly `message` and a line break, and
 * leave no file at `output` (removed first). */
static void expect_tool_refusal(const char *command, const char *message, const char *output_path) {
    char output[1024], expected[1024];
    unlink(output_path);
    cr_expect_eq(run_capturing(command, output, sizeof output), 2, "%s: %s", command, output);
    snprintf(expected, sizeof expected, "%s\n", message);
    cr_expect_str_eq(output, expected, "%s", command);
    cr_expect_neq(access(output_path, F_OK), 0, "%s wrote %s", command, output_path);
}

/* compare's --box N is all of it a number from 1 to a picture's side (atoi read 4294967297 and "1x" as 1,
 * and the pictures then "agreed", exit 0), and an option in a picture's place is refused, not written:
 * "compare A B --diff x.png" wrote its side-by-side picture to a file named --diff. */
Test(io, compare_refuses_a_box_that_is_not_a_number_in_range_and_an_unknown_option) {
    const char *a = bytes_file("io-compare-a.png", palette_png_checkerboard, sizeof palette_png_checkerboard);
    const char *build = getenv("WHITTED_BUILD");
    const struct {
        const char *words, *message;
    } rows[] = {
        {"--box 4294967297 %s %s", "compare: --box '4294967297' is not a whole number from 1 to 16384"},
        {"--box 1x %s %s", "compare: --box '1x' is not a whole number from 1 to 16384"},
        {"--box 0 %s %s", "compare: --box '0' is not a whole number from 1 to 16384"},
        {"--box 99999999999 %s %s", "compare: --box '99999999999' is not a whole number from 1 to 16384"},
        {"%s %s --diff " TEST_OUT "/io-compare.png",
         "compare: unknown option '--diff' (--box N comes first; a picture named so is ./--diff)"},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        char words[512], command[1024];
        snprintf(words, sizeof words, rows[k].words, a, a);
        snprintf(command, sizeof command, "%s/compare %s", build != NULL ? build : "build", words);
        expect_tool_refusal(command, rows[k].message, TEST_OUT "/io-compare.png");
    }
    unlink("--diff");
}

/* draw-textures (chapter 14's pictures) names the file it could not write: it named the last one, grid.jpg,
 * whichever failed, and took --help for a folder ("cannot write --help/grid.jpg"). */
Test(io, draw_textures_names_the_file_it_cannot_write) {
    const char *build = getenv("WHITTED_BUILD");
    char command[512], output[1024];
    snprintf(command, sizeof command, "%s/draw-textures --help", build != NULL ? build : "build");
    cr_expect_eq(run_capturing(command, output, sizeof output), 2, "%s: %s", command, output);
    cr_expect_str_eq(output, "usage: draw-textures FOLDER\n");
    cr_assert_eq(system("rm -rf " TEST_OUT "/textures-blocked && mkdir -p " TEST_OUT "/textures-blocked/grid.png"), 0);
    snprintf(command, sizeof command, "%s/draw-textures " TEST_OUT "/textures-blocked", build != NULL ? build : "build");
    cr_expect_eq(run_capturing(command, output, sizeof output), 1, "%s: %s", command, output);
    cr_expect_str_eq(output, "draw-textures: cannot write " TEST_OUT "/textures-blocked/grid.png\n");
    cr_expect_neq(access(TEST_OUT "/textures-blocked/grid.jpg", F_OK), 0, "it went on after the failure");
}

/* inset's numbers are checked before they are used: a region of 1073741825 pixels at 1073741824 passed the
 * check that it lies inside the picture (the sum wrapped round) and the copy read gigabytes past it, a
 * crash; a zoom of 536870912 wrapped the panel's width. An OUT that names an input is refused too. */
Test(io, inset_refuses_numbers_out_of_range_and_an_output_that_is_an_input) {
    const char *a = bytes_file("io-inset-a.png", palette_png_checkerboard, sizeof palette_png_checkerboard);
    const char *build = getenv("WHITTED_BUILD");
    const struct {
        const char *numbers, *out, *message;
    } rows[] = {
        {"1073741824 0 1073741825 1 4", TEST_OUT "/io-inset.png",
         "inset: X '1073741824' is not a whole number from 0 to 16384"},
        {"0 0 8 6 536870912", TEST_OUT "/io-inset.png", "inset: ZOOM '536870912' is not a whole number from 0 to 16384"},
        {"0 0 1x 1 4", TEST_OUT "/io-inset.png", "inset: W '1x' is not a whole number from 0 to 16384"},
        {"0 0 -1 1 4", TEST_OUT "/io-inset.png", "inset: W '-1' is not a whole number from 0 to 16384"},
        {"0 0 4 4 16384", TEST_OUT "/io-inset.png",
         "inset: the picture would be 131078 x 65536 pixels, more than 16384 on a side: a smaller ZOOM or region"},
        {"0 0 5 4 2", TEST_OUT "/io-inset.png", "inset: the region 5 x 4 at (0, 0) is not inside the 4 x 4 pictures"},
        {"0 0 2 2 2", a, "inset: OUT.png names '" TEST_OUT "/io-inset-a.png', a picture it reads: writing it would "
                         "destroy it; give another file"},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        char command[1024];
        snprintf(command, sizeof command, "%s/inset %s %s %s %s", build != NULL ? build : "build", rows[k].out,
                 rows[k].numbers, a, a);
        expect_tool_refusal(command, rows[k].message, TEST_OUT "/io-inset.png");
    }
    size_t size = 0;
    char *first = read_file(a, &size);
    cr_expect(size == sizeof palette_png_checkerboard && memcmp(first, palette_png_checkerboard, size) == 0,
              "the input was written over");
    free(first);
    /* And a region in range is drawn: two 2 x 2 panels at zoom 2, 6 white pixels apart. */
    char command[1024], output[1024];
    snprintf(command, sizeof command, "%s/inset %s 1 1 2 2 2 %s %s", build != NULL ? build : "build",
             TEST_OUT "/io-inset.png", a, a);
    cr_expect_eq(run_capturing(command, output, sizeof output), 0, "%s: %s", command, output);
    char err[256];
    int width = 0, height = 0;
    uint8_t *drawn = image_read_rgb(TEST_OUT "/io-inset.png", &width, &height, err, sizeof err);
    cr_assert_not_null(drawn, "%s", err);
    cr_expect(width == 2 * 4 + 6 && height == 4, "the inset is %d x %d", width, height);
    free(drawn);
}

Test(io, compare_refuses_outputs_that_name_its_inputs_or_each_other) {
    const char *a = bytes_file("io-compare-a.png", palette_png_checkerboard, sizeof palette_png_checkerboard);
    const char *b = bytes_file("io-compare-b.png", palette_png_checkerboard, sizeof palette_png_checkerboard);
    const char *build = getenv("WHITTED_BUILD");
    const struct {
        const char *side, *diff, *message;
    } rows[] = {
        {a, TEST_OUT "/io-compare-diff.png", "compare: SIDE.png names '" TEST_OUT "/io-compare-a.png', a picture it "
                                             "reads: writing it would destroy it; give another file"},
        {TEST_OUT "/io-compare-side.png", b, "compare: DIFF.png names '" TEST_OUT "/io-compare-b.png', a picture it "
                                             "reads: writing it would destroy it; give another file"},
        {TEST_OUT "/io-compare-side.png", TEST_OUT "/io-compare-side.png",
         "compare: SIDE.png and DIFF.png both name '" TEST_OUT "/io-compare-side.png'; give two files"},
        {TEST_OUT "/io-compare-side.png", "/nonexistent/diff.png",
         "compare: /nonexistent/diff.png: cannot create: No such file or directory"},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        char command[1024];
        snprintf(command, sizeof command, "%s/compare %s %s %s %s", build != NULL ? build : "build", a, b,
                 rows[k].side, rows[k].diff);
        expect_tool_refusal(command, rows[k].message, TEST_OUT "/io-compare-side.png");
    }
    size_t size = 0;
    char *first = read_file(a, &size);
    cr_expect(size == sizeof palette_png_checkerboard && memcmp(first, palette_png_checkerboard, size) == 0,
              "the first picture was written over");
    free(first);
}

/* ---- -o to things that are not regular files -------------------------------------------------- */

Test(io, a_fifo_as_output_gets_the_whole_png) {
    const char *fifo = fresh("io-out.fifo"), *copy = fresh("io-from-fifo.png");
    cr_assert_eq(mkfifo(fifo, 0644), 0);
    char reader[512], arguments[512], output[4096];
    snprintf(reader, sizeof reader, IO_TIMEOUT " cat %s > %s", fifo, copy);
    FILE *cat = popen(reader, "r"); /* reads the FIFO in the background until the writer closes it */
    cr_assert_not_null(cat);
    snprintf(arguments, sizeof arguments, IO_TIMEOUT " %s -o %s --quiet", chapter_program(2), fifo);
    cr_assert_eq(run_capturing(arguments, output, sizeof output), 0, "%s", output);
    cr_assert_eq(pclose(cat), 0);
    struct stat info;
    cr_assert_eq(lstat(fifo, &info), 0);
    cr_assert(S_ISFIFO(info.st_mode), "the FIFO was replaced");
    expect_png(copy, 320, 240);
    unlink(fifo);
}

/* Returns a device like /dev/full (every write fails with "No space left on device") to write to. As
 * root the test makes its own node, so that a writer that replaces its target (the old bug) replaces
 * that node and not the system's /dev/full; other users cannot replace /dev/full. */
static const char *full_device(void) {
    const char *node = fresh("io-full");
    if (mknod(node, S_IFCHR | 0666, makedev(1, 7)) == 0)
        return node;
    if (geteuid() != 0)
        return "/dev/full";
    cr_skip_test("cannot make a device node in " TEST_OUT " (a nodev mount?)");
    return NULL;
}

Test(io, a_full_device_fails_with_a_write_error_and_stays_a_device) {
    const char *full = full_device();
    char arguments[512], expected[512];
    snprintf(expected, sizeof expected, "%s: cannot write: No space left on device", full);
    snprintf(arguments, sizeof arguments, "-o %s --quiet", full);
    expect_chapter_run(2, arguments, 3, expected);
    snprintf(arguments, sizeof arguments, "-o %s --width 512 --height 512 --quiet", full); /* more than a buffer */
    expect_chapter_run(2, arguments, 3, expected);
    struct stat info;
    cr_assert_eq(stat(full, &info), 0);
    cr_assert(S_ISCHR(info.st_mode), "%s is no longer a device", full);
}

Test(io, a_symbolic_link_stays_a_link_and_its_target_gets_the_picture) {
    const char *target = text_file("io-target.png", "not a picture yet");
    const char *link = fresh("io-link.png");
    cr_assert_eq(symlink("io-target.png", link), 0);
    char arguments[512];
    snprintf(arguments, sizeof arguments, "-o %s --quiet", link);
    expect_chapter_run(2, arguments, 0, "");
    struct stat info;
    cr_assert_eq(lstat(link, &info), 0);
    cr_assert(S_ISLNK(info.st_mode), "the link was replaced by a file");
    expect_png(target, 320, 240);
}

/* Two links naming each other: the picture was written over the first link, which became a plain file,
 * exit 0. Now it is refused as opening the name refuses it, the links left as they were. */
Test(io, a_loop_of_symbolic_links_is_refused_and_left_as_it_is) {
    const char *first = fresh("io-loop-a.png"), *second = fresh("io-loop-b.png");
    cr_assert_eq(symlink("io-loop-b.png", first), 0);
    cr_assert_eq(symlink("io-loop-a.png", second), 0);
    char arguments[512], expected[512];
    snprintf(arguments, sizeof arguments, "-o %s --quiet", first);
    snprintf(expected, sizeof expected, "%s: cannot create: Too many levels of symbolic links", first);
    expect_chapter_run(2, arguments, 3, expected);
    const char *const links[] = {first, second};
    for (int k = 0; k < 2; k++) {
        struct stat info;
        cr_assert_eq(lstat(links[k], &info), 0);
        cr_assert(S_ISLNK(info.st_mode), "%s was replaced by a file", links[k]);
    }
}

/* Fails unless the files `piped` (what standard output received) and `direct` hold the same bytes. */
static void expect_same_bytes(const char *piped, const char *direct) {
    size_t piped_size, direct_size;
    char *a = read_file(piped, &piped_size), *b = read_file(direct, &direct_size);
    cr_assert_eq(piped_size, direct_size, "standard output holds %zu bytes, %s %zu", piped_size, direct, direct_size);
    cr_assert_eq(memcmp(a, b, direct_size), 0);
    free(a);
    free(b);
}

Test(io, dash_writes_the_png_to_standard_output_and_nothing_else) {
    const char *piped = fresh("io-stdout.png"), *log = fresh("io-stdout.log"), *direct = fresh("io-direct.png");
    char command[512], output[4096];
    snprintf(command, sizeof command, "%s -o - > %s 2> %s", chapter_program(2), piped, log);
    cr_assert_eq(system(command), 0);
    snprintf(command, sizeof command, "%s -o %s --quiet", chapter_program(2), direct);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    expect_same_bytes(piped, direct);
    char *counters = read_text_file(log);
    cr_assert_not_null(strstr(counters, "sphere tests"), "the counters did not go to standard error:\n%s", counters);
    free(counters);
}

/* ---- FIFOs as inputs --------------------------------------------------------------------------- */

Test(io, a_fifo_as_scene_is_refused_without_waiting) {
    const char *fifo = fresh("io-scene.fifo");
    cr_assert_eq(mkfifo(fifo, 0644), 0);
    char arguments[512], expected[512];
    snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/never.png", fifo);
    snprintf(expected, sizeof expected, "%s: not a regular file (a FIFO)", fifo);
    expect_chapter_run(2, arguments, 1, expected);
    unlink(fifo);
}

Test(io, a_fifo_as_mesh_is_refused_without_waiting) {
    const char *fifo = fresh("io-mesh.fifo");
    cr_assert_eq(mkfifo(fifo, 0644), 0);
    const char *scene = text_file("io-fifo-mesh.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\n"
                                                         "mesh io-mesh.fifo\n");
    char arguments[512], expected[512];
    snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/never.png", scene);
    snprintf(expected, sizeof expected, "%s: not a regular file (a FIFO)", fifo);
    expect_chapter_run(3, arguments, 1, expected);
    unlink(fifo);
}

Test(io, a_directory_as_scene_is_refused) { expect_chapter_run(2, "scenes", 1, "scenes: not a regular file (a directory)"); }

/* ---- one file named twice ---------------------------------------------------------------------- */

Test(io, the_picture_and_the_heat_map_may_not_share_a_file) {
    const char *picture = fresh("io-twice.png");
    char arguments[512], expected[512];
    snprintf(arguments, sizeof arguments, "-o %s --heatmap %s", picture, picture);
    snprintf(expected, sizeof expected, "-o and --heatmap name the same file ('%s' and '%s'); give two", picture,
             picture);
    expect_chapter_run(2, arguments, 2, expected);
    cr_assert_neq(access(picture, F_OK), 0, "something was written");
    /* Two spellings of a file that does not exist yet. */
    snprintf(arguments, sizeof arguments, "-o %s --heatmap " TEST_OUT "/../test/./io-twice.png", picture);
    expect_chapter_run(2, arguments, 2, "name the same file");
    /* A link and its target, both existing. */
    const char *target = text_file("io-twice-target.png", "x"), *link = fresh("io-twice-link.png");
    cr_assert_eq(symlink("io-twice-target.png", link), 0);
    snprintf(arguments, sizeof arguments, "-o %s --heatmap %s", link, target);
    expect_chapter_run(2, arguments, 2, "name the same file");
    /* Two names of different files are fine. */
    snprintf(arguments, sizeof arguments, "-o %s --heatmap " TEST_OUT "/io-twice-heat.png --quiet", picture);
    expect_chapter_run(2, arguments, 0, "");
}

/* Chapter 15's --hdr is a third output with the same rules: a small, quick render of its scene. */
#define IO_QUICK_PATHS "--width 8 --height 8 --set paths.samples=1"

/* Runs chapter n with `arguments` and expects it refused (exit 2) with `message`, and the file at
 * `kept` still holding `text` (the run reads it, so writing it would have destroyed it). */
static void expect_input_kept(int n, const char *arguments, const char *message, const char *kept, const char *text) {
    expect_chapter_run(n, arguments, 2, message);
    char *now = read_text_file(kept);
    cr_assert_not_null(now, "%s is gone", kept);
    cr_expect_str_eq(now, text, "%s was overwritten", kept);
    free(now);
}

/* An output that names a file the run reads: the scene, a mesh, an image map, an object's mesh. The
 * picture is written after the render, so it used to replace that input, with exit status 0. */
Test(io, an_output_that_names_a_file_the_run_reads_is_refused_and_the_file_kept) {
    const char *head = "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40\nlight position 5 8 4\n";
    char text[512], arguments[1024], expected[1024];
    snprintf(text, sizeof text, "%ssphere centre 0 0 0 radius 1\n", head);
    const char *scene = text_file("io-reads.scene", text);
    snprintf(arguments, sizeof arguments, "%s -o %s", scene, scene);
    snprintf(expected, sizeof expected,
             "-o names '%s', which the run reads (the scene file): writing it would destroy it; give another file",
             scene);
    expect_input_kept(12, arguments, expected, scene, text);
    snprintf(arguments, sizeof arguments, "%s --pov " TEST_OUT "/./io-reads.scene", scene);
    expect_input_kept(12, arguments, "--pov names 'out/test/./io-reads.scene', which the run reads (the scene file)",
                      scene, text);
    snprintf(arguments, sizeof arguments, IO_QUICK_PATHS " %s --hdr %s", scene, scene);
    expect_input_kept(15, arguments, "--hdr names", scene, text);

    const char *obj_text = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
    const char *obj = text_file("io-reads.obj", obj_text);
    snprintf(text, sizeof text, "%smesh io-reads.obj\n", head);
    scene = text_file("io-reads-mesh.scene", text);
    snprintf(arguments, sizeof arguments, "%s -o %s --heatmap %s", scene, fresh("io-reads-mesh.png"), obj);
    expect_input_kept(14, arguments, "--heatmap names 'out/test/io-reads.obj', which the run reads (the mesh of line 4)",
                      obj, obj_text);
    snprintf(text, sizeof text, "%sobject o io-reads.obj\ninstance o\n", head);
    scene = text_file("io-reads-object.scene", text);
    snprintf(arguments, sizeof arguments, "%s -o %s", scene, obj);
    expect_input_kept(16, arguments, "-o names 'out/test/io-reads.obj', which the run reads (the mesh of object 'o')",
                      obj, obj_text);

    /* An image map: a file the chapter itself wrote, then named as its picture. */
    const char *image = fresh("io-reads-image.png");
    snprintf(arguments, sizeof arguments, "--width 4 --height 4 --quiet -o %s", image);
    expect_chapter_run(2, arguments, 0, "");
    size_t before_size, after_size;
    char *before = read_file(image, &before_size);
    cr_assert_not_null(before);
    snprintf(text, sizeof text,
             "%spigment p image_map file io-reads-image.png\nmaterial m pigment p\nsphere centre 0 0 0 radius 1 "
             "material m\n",
             head);
    scene = text_file("io-reads-image.scene", text);
    snprintf(arguments, sizeof arguments, "%s -o %s", scene, image);
    expect_chapter_run(14, arguments, 2,
                       "-o names 'out/test/io-reads-image.png', which the run reads (the image of pigment 'p')");
    char *after = read_file(image, &after_size);
    cr_assert_not_null(after);
    cr_expect(after_size == before_size && memcmp(before, after, before_size) == 0, "the image was overwritten");
    free(before);
    free(after);
    /* Chapter 13 does not read image maps: its picture may go there. */
    expect_chapter_run(13, arguments, 0, "");
}

Test(io, the_linear_radiance_may_not_share_a_file_with_the_picture_or_the_heat_map) {
    const char *picture = fresh("io-hdr-twice.png"), *heat = fresh("io-hdr-heat.png");
    char arguments[1024], expected[512];
    snprintf(arguments, sizeof arguments, IO_QUICK_PATHS " -o %s --hdr %s", picture, picture);
    snprintf(expected, sizeof expected, "-o and --hdr name the same file ('%s' and '%s'); give two", picture, picture);
    expect_chapter_run(15, arguments, 2, expected);
    cr_assert_neq(access(picture, F_OK), 0, "something was written");
    snprintf(arguments, sizeof arguments, IO_QUICK_PATHS " --heatmap %s --hdr " TEST_OUT "/../test/./io-hdr-heat.png",
             heat);
    snprintf(expected, sizeof expected,
             "--heatmap and --hdr name the same file ('%s' and '" TEST_OUT "/../test/./io-hdr-heat.png'); give two",
             heat);
    expect_chapter_run(15, arguments, 2, expected);
    /* The default picture's name counts too, and so does standard output named twice. */
    expect_chapter_run(15, IO_QUICK_PATHS " --hdr out/chapter-15.png", 2,
                       "-o and --hdr name the same file ('out/chapter-15.png' and 'out/chapter-15.png'); give two");
    expect_chapter_run(15, IO_QUICK_PATHS " -o - --hdr -", 2, "-o and --hdr name the same file ('-' and '-'); give two");
    /* Under --pov nothing but the twin is written: a render's outputs are refused with it. */
    snprintf(arguments, sizeof arguments, IO_QUICK_PATHS " --pov " TEST_OUT "/io-hdr.pov --hdr out/chapter-15.png "
             "--quiet");
    expect_chapter_run(15, arguments, 2, "--hdr names an output of the render, and --pov writes the scene's POV-Ray "
                                         "twin instead of rendering; give one of them");
}

Test(io, the_linear_radiance_follows_the_rules_of_every_output) {
    static char arguments[PATH_MAX + 512], name[PATH_MAX + 256];
    memset(name, 'h', NAME_MAX);
    name[NAME_MAX] = '\0';
    snprintf(arguments, sizeof arguments, IO_QUICK_PATHS " --hdr %s", name);
    char expected[256];
    snprintf(expected, sizeof expected, "--hdr: the file name is too long (%d bytes; the system allows %d for a path, "
             "%d for one name, less 10 for the temporary file)", NAME_MAX, PATH_MAX - 1, NAME_MAX);
    expect_chapter_run(15, arguments, 2, expected);
    expect_chapter_run(15, IO_QUICK_PATHS " --hdr ''", 2, "--hdr needs a file name");
    expect_chapter_run(15, IO_QUICK_PATHS " --hdr", 2, "--hdr needs a file name");
    expect_chapter_run(15, IO_QUICK_PATHS " --hdr " TEST_OUT "/no-such-folder/x.hdr -o " TEST_OUT "/io-hdr.png", 3,
                       TEST_OUT "/no-such-folder/x.hdr: cannot create: No such file or directory");
}

Test(io, dash_as_hdr_writes_the_radiance_to_standard_output_and_the_report_to_standard_error) {
    const char *piped = fresh("io-hdr-stdout.hdr"), *log = fresh("io-hdr-stdout.log"), *direct = fresh("io-hdr.hdr");
    const char *picture = fresh("io-hdr-picture.png");
    char command[1024], output[4096];
    snprintf(command, sizeof command, IO_TIMEOUT " %s " IO_QUICK_PATHS " -o %s --hdr - > %s 2> %s",
             chapter_program(15), picture, piped, log);
    cr_assert_eq(system(command), 0);
    snprintf(command, sizeof command, IO_TIMEOUT " %s " IO_QUICK_PATHS " -o %s --hdr %s --quiet", chapter_program(15),
             picture, direct);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    expect_same_bytes(piped, direct);
    char *report = read_text_file(log);
    cr_assert_not_null(strstr(report, "linear radiance: standard output\npaths: 1 a pixel"),
                       "the report did not go to standard error:\n%s", report);
    free(report);
}

Test(io, same_file_compares_inodes_and_resolved_names) {
    const char *a = text_file("io-same-a", "a"), *b = fresh("io-same-b");
    cr_assert_eq(link(a, b), 0); /* a hard link: two names, one inode */
    cr_assert(outfile_same_file(a, b));
    cr_assert(outfile_same_file("-", "-"));
    cr_assert(!outfile_same_file(a, "-"));
    cr_assert(outfile_same_file(TEST_OUT "/io-none", "./" TEST_OUT "/io-none"));
    cr_assert(!outfile_same_file(TEST_OUT "/io-none", TEST_OUT "/io-none2"));
    cr_assert(!outfile_same_file(a, TEST_OUT "/io-none"));
}

/* An index of names answers outfile_same_file's question for each of them, the first that names the
 * file: by name, by inode (a hard link, a symbolic link), by the resolved name of a file not there yet,
 * and "-" only for "-". */
Test(io, an_index_of_names_finds_the_first_that_outfile_same_file_matches) {
    const char *a = text_file("io-index-a", "a");
    const char *hard = fresh("io-index-hard"), *soft = fresh("io-index-soft");
    cr_assert_eq(link(a, hard), 0);
    cr_assert_eq(symlink("io-index-a", soft), 0);
    const char *other = text_file("io-index-other", "b");
    unlink(TEST_OUT "/io-index-none");
    unlink(TEST_OUT "/io-index-none2");
    const char *const names[] = {NULL, TEST_OUT "/io-index-none", other, hard, "-", a, "./" TEST_OUT "/io-index-none",
                                 soft, TEST_OUT "/io-index-none2", other};
    size_t count = sizeof names / sizeof names[0];
    const char *const asked[] = {a, hard, soft, other, "-", TEST_OUT "/io-index-none", "./" TEST_OUT "/io-index-none",
                                 TEST_OUT "/./io-index-none2", TEST_OUT "/io-index-never", "./" TEST_OUT
                                 "/io-index-other", "io-index-a"};
    struct outfile_index index;
    cr_assert(outfile_index_build(&index, names, count));
    for (size_t q = 0; q < sizeof asked / sizeof asked[0]; q++) {
        size_t expected = OUTFILE_INDEX_NONE;
        for (size_t k = 0; expected == OUTFILE_INDEX_NONE && k < count; k++)
            if (names[k] != NULL && outfile_same_file(asked[q], names[k]))
                expected = k;
        size_t found = outfile_index_find(&index, asked[q]);
        cr_expect_eq(found, expected, "%s: found %zu, outfile_same_file says %zu", asked[q], found, expected);
    }
    /* the positions of the answers, to see that the cases above are the ones meant */
    cr_expect_eq(outfile_index_find(&index, a), 3); /* its hard link comes first */
    cr_expect_eq(outfile_index_find(&index, "-"), 4);
    cr_expect_eq(outfile_index_find(&index, "./" TEST_OUT "/io-index-none"), 1);
    cr_expect_eq(outfile_index_find(&index, TEST_OUT "/./io-index-none2"), 8);
    cr_expect_eq(outfile_index_find(&index, TEST_OUT "/io-index-never"), OUTFILE_INDEX_NONE);
    outfile_index_free(&index);
    cr_assert(outfile_index_build(&index, names, 0)); /* an empty list finds nothing */
    cr_expect_eq(outfile_index_find(&index, a), OUTFILE_INDEX_NONE);
    outfile_index_free(&index);
}

/* ---- names longer than the system takes -------------------------------------------------------- */

Test(io, an_output_name_longer_than_the_system_limit_is_refused) {
    static char arguments[PATH_MAX + 512], name[PATH_MAX + 256];
    memset(name, 'a', PATH_MAX + 100);
    name[PATH_MAX + 100] = '\0';
    snprintf(arguments, sizeof arguments, "-o %s", name);
    char expected[256];
    snprintf(expected, sizeof expected, "-o: the file name is too long (%d bytes; the system allows %d for a path, "
             "%d for one name, less 10 for the temporary file)", PATH_MAX + 100, PATH_MAX - 1, NAME_MAX);
    expect_chapter_run(2, arguments, 2, expected);
    /* One name (no folder) too long for its temporary file, though short as a path. */
    memset(name, 'b', NAME_MAX);
    name[NAME_MAX] = '\0';
    snprintf(arguments, sizeof arguments, "--heatmap %s", name);
    expect_chapter_run(2, arguments, 2, "--heatmap: the file name is too long");
    cr_assert(outfile_name_fits("out/ok.png"));
    cr_assert(outfile_name_fits("-"));
    cr_assert(!outfile_name_fits(name));
}

/* ---- control characters in messages ------------------------------------------------------------ */

Test(io, control_characters_in_a_message_are_escaped) {
    const char *scene = text_file("io-escape.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\n"
                                                     "sph\x1b[2Jere centre 0 0 0 radius 1\n");
    char command[512], output[4096], expected[512];
    snprintf(command, sizeof command, "%s %s -o " TEST_OUT "/never.png", chapter_program(2), scene);
    cr_assert_eq(run_capturing(command, output, sizeof output), 1, "%s", output);
    snprintf(expected, sizeof expected, "%s:3: unknown directive 'sph\\x1b[2Jere'\n", scene);
    cr_assert_str_eq(output, expected);
    expect_chapter_run(2, "\"$(printf -- '-r\\033]0;x\\007')\"", 2, "unknown option '-r\\x1b]0;x\\x07'");
    expect_chapter_run(10, "--accel \"$(printf -- 'b\\033vh')\"", 2, "got 'b\\x1bvh'");
    expect_chapter_run(10, "--split \"$(printf -- 's\\033ah')\"", 2, "got 's\\x1bah'");
}

/* The note a chapter prints about shapes it does not draw quotes the scene's path, which comes from the
 * command line: escaped too. */
Test(io, the_note_about_ignored_shapes_escapes_the_scene_path) {
    const char *scene = text_file("io-note\x1b[2J.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\n"
                                                           "plane normal 0 1 0 distance -1\n");
    char arguments[512], expected[512];
    snprintf(arguments, sizeof arguments, "'%s' -o " TEST_OUT "/io-note.png", scene);
    snprintf(expected, sizeof expected, TEST_OUT "/io-note\\x1b[2J.scene: chapter 2 ignores 1 plane (not introduced yet)");
    expect_chapter_run(2, arguments, 0, expected);
}

Test(io, escaping_keeps_utf8_and_escapes_everything_else) {
    char out[128];
    text_escape("plain text, caf\xc3\xa9 \xc3\x97 \xe2\x82\xac \xf0\x9f\x90\x87", out, sizeof out);
    cr_assert_str_eq(out, "plain text, caf\xc3\xa9 \xc3\x97 \xe2\x82\xac \xf0\x9f\x90\x87");
    text_escape("a\tb\nc\x7f" "d\x1b", out, sizeof out);
    cr_assert_str_eq(out, "a\\x09b\\x0ac\\x7fd\\x1b");
    text_escape("\xc2\x9b" "1m", out, sizeof out); /* U+009B, the one-byte CSI of C1 */
    cr_assert_str_eq(out, "\\xc2\\x9b1m");
    text_escape("\xc0\xaf \xed\xa0\x80 \xc3 \xff", out, sizeof out); /* overlong, surrogate, cut, invalid */
    cr_assert_str_eq(out, "\\xc0\\xaf \\xed\\xa0\\x80 \\xc3 \\xff");
    /* a right-to-left override, a no-break space, a byte-order mark, a zero-width space: they showed
     * "unknown material '<RLO>y'" as "'y'", "radius 1<NBSP>" as "radius 1 " and "<BOM>sphere" as "sphere" */
    text_escape("\xe2\x80\xaey 1\xc2\xa0 \xef\xbb\xbfsphere a\xe2\x80\x8b" "b", out, sizeof out);
    cr_assert_str_eq(out, "\\xe2\\x80\\xaey 1\\xc2\\xa0 \\xef\\xbb\\xbfsphere a\\xe2\\x80\\x8bb");
    text_escape("\xe2\x80\x94 \xe2\x80\x99", out, sizeof out); /* a dash and a quote mark are printable */
    cr_assert_str_eq(out, "\xe2\x80\x94 \xe2\x80\x99");
    cr_assert_eq(text_escape("ab\x01" "c", out, 6), 2); /* the escape does not fit whole: stop before it */
    cr_assert_str_eq(out, "ab");
}

/* ---- meshes placed out of range ---------------------------------------------------------------- */

/* Renders a one-triangle mesh placed by `placement` and expects the message `what` for line 3. The
 * files are named after `tag`: the tests run in parallel, so each writes its own. */
static void expect_out_of_range(const char *tag, const char *placement, const char *what) {
    char obj[64], scene_name[64];
    snprintf(obj, sizeof obj, "io-range-%s.obj", tag);
    snprintf(scene_name, sizeof scene_name, "io-range-%s.scene", tag);
    text_file(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char text[256], arguments[512], expected[512];
    snprintf(text, sizeof text, "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\nmesh %s %s\n", obj, placement);
    const char *scene = text_file(scene_name, text);
    for (int n = 3; n <= 10; n += 7) {
        snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/never-%s.png", scene, tag);
        snprintf(expected, sizeof expected, "%s:3: mesh " TEST_OUT "/%s placed out of range: %s", scene, obj, what);
        expect_chapter_run(n, arguments, 1, expected);
    }
}

Test(io, a_mesh_scaled_beyond_float_range_is_refused) {
    expect_out_of_range("big", "scale 1e308", "vertex 1 lands at (1e+308, 0, 0); coordinates must stay within "
                                              "-1e+18 .. 1e+18");
}

Test(io, a_mesh_scaled_below_float_range_is_refused) {
    expect_out_of_range("small", "scale 1e-40", "it is 1e-40 across; it must be at least 1e-18 across");
}

Test(io, a_mesh_moved_beyond_float_range_is_refused) {
    expect_out_of_range("far", "translate 1e39 0 0", "vertex 0 lands at (1e+39, 0, 0); coordinates must stay within "
                                                     "-1e+18 .. 1e+18");
}

Test(io, a_mesh_at_the_edge_of_the_range_renders) {
    text_file("io-edge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const char *scene = text_file("io-edge.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\n"
                                                   "mesh io-edge.obj scale 1e-18\nmesh io-edge.obj translate 1e18 0 0\n");
    char arguments[512];
    snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/io-edge.png --quiet", scene);
    expect_chapter_run(10, arguments, 0, "");
}

/* ---- the memory a scene's meshes take ------------------------------------------------------------ */

/* A flat grid of IO_GRID x IO_GRID vertices, two triangles a square, as a binary PLY file: its arrays, and
 * chapter 16's tree over it, are small enough for malloc to take from its heap, so that under `ulimit -d`
 * the data grow by about what the meshes count (a big array takes whole 2 MB pages, big_alloc.c). */
#define IO_GRID 50
#define IO_GRID_LIMIT_KB 100000 /* ulimit -d for the runs */
#define IO_GRID_SHARE 0.0625    /* of the memory, for the meshes (memory_budget.h) */

static const char *grid_ply(void) {
    const char *path = fresh("io-grid.ply");
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
               "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n",
            IO_GRID * IO_GRID, 2 * (IO_GRID - 1) * (IO_GRID - 1));
    for (int j = 0; j < IO_GRID; j++) /* little-endian floats: the machines the tests run on are */
        for (int i = 0; i < IO_GRID; i++) {
            float p[3] = {(float)i / (IO_GRID - 1), (float)j / (IO_GRID - 1), 0.0f};
            fwrite(p, sizeof p, 1, f);
        }
    for (int j = 0; j + 1 < IO_GRID; j++)
        for (int i = 0; i + 1 < IO_GRID; i++) {
            int32_t a = j * IO_GRID + i, b = a + IO_GRID; /* the square's corners a, a + 1, b + 1, b */
            int32_t corners[2][3] = {{a, a + 1, b + 1}, {a, b + 1, b}};
            for (int t = 0; t < 2; t++) {
                fputc(3, f);
                fwrite(corners[t], sizeof corners[t], 1, f);
            }
        }
    cr_assert_eq(fclose(f), 0);
    return path;
}

/* Renders `scene` with chapter n under `ulimit -d IO_GRID_LIMIT_KB` (one thread, so that no other
 * thread's stack counts), into `png`; returns the exit status and the output in output[size]. */
static int run_under_limit(int n, const char *scene, const char *png, char *output, size_t size) {
    char command[1024];
    snprintf(command, sizeof command, "ulimit -d %d; OMP_NUM_THREADS=1 " IO_TIMEOUT " %s %s --quiet -o %s",
             IO_GRID_LIMIT_KB, chapter_program(n), scene, png);
    return run_capturing(command, output, size);
}

/* What the memory tests repeat, the k-th time (k from 0): a mesh line naming the grid, an object line and
 * an instance of it, an image_map pigment naming io-image-K.png, or one naming io-image-0.png each time. */
enum repeated_line { REPEAT_MESH, REPEAT_OBJECT, REPEAT_IMAGE, REPEAT_ONE_IMAGE };

/* Writes a scene of a camera, an 8 x 8 image and a light (lines 1 to 3), then `count` repeated lines of
 * `what`, and for pigments a sphere painted by the last; returns its path. */
static const char *repeated_scene(const char *name, enum repeated_line what, int count) {
    size_t size = 256 + (size_t)count * 64, used = 0;
    char *text = malloc(size);
    cr_assert_not_null(text);
    used += (size_t)snprintf(text, size, "camera eye 0.5 0.5 3 target 0.5 0.5 0 fov 40\nimage 8 8\n"
                                         "light position 0 0 5 colour 1 1 1\n");
    for (int k = 0; k < count; k++) {
        char *at = text + used;
        size_t room = size - used;
        if (what == REPEAT_MESH)
            used += (size_t)snprintf(at, room, "mesh io-grid.ply\n");
        else if (what == REPEAT_OBJECT)
            used += (size_t)snprintf(at, room, "object o%d io-grid.ply\ninstance o%d\n", k, k);
        else
            used += (size_t)snprintf(at, room, "pigment p%d image_map file io-image-%d.png\n", k,
                                     what == REPEAT_ONE_IMAGE ? 0 : k);
    }
    if (what == REPEAT_IMAGE || what == REPEAT_ONE_IMAGE)
        snprintf(text + used, size - used, "material m pigment p%d\nsphere centre 0.5 0.5 0 radius 1 material m\n",
                 count - 1);
    const char *path = text_file(name, text);
    free(text);
    return path;
}

/* Skips the current test in the sanitizers' build, whose shadow memory no such limit allows. */
static void skip_under_sanitizers(void) {
    const char *build = getenv("WHITTED_BUILD");
    if (build != NULL && strstr(build, "san") != NULL)
        cr_skip_test("the sanitizers reserve more memory than the limit");
}

Test(io, meshes_beyond_their_share_of_memory_are_refused_at_the_line_that_goes_over, .timeout = 120) {
    skip_under_sanitizers();
    char grid[256], meshes[256], objects[256]; /* fresh's buffers are reused */
    snprintf(grid, sizeof grid, "%s", grid_ply());
    /* What each grid counts (its vertices in double, its faces as three numbers), and how many fit in the
     * share: the next one's line is refused. The scenes' first mesh or object is on line 4. */
    double bytes = IO_GRID * IO_GRID * sizeof(vec3) + 2.0 * (IO_GRID - 1) * (IO_GRID - 1) * sizeof(struct mesh_face);
    double budget = IO_GRID_SHARE * IO_GRID_LIMIT_KB * 1024.0;
    int fitting = (int)(budget / bytes), over = fitting + 1;
    snprintf(meshes, sizeof meshes, "%s", repeated_scene("io-heavy.scene", REPEAT_MESH, 3 * over));
    snprintf(objects, sizeof objects, "%s", repeated_scene("io-heavy-objects.scene", REPEAT_OBJECT, 3 * over));
    static const int chapters[] = {3, 9, 11, 16}; /* brute force, the kd-tree's gathered copy, 11, objects */
    static char output[16384];
    for (size_t k = 0; k < sizeof chapters / sizeof chapters[0]; k++) {
        int n = chapters[k];
        char expected[2048], line[1024];
        if (n == 16)
            snprintf(line, sizeof line, "%s:%d: object 'o%d'", objects, 4 + 2 * fitting, fitting);
        else
            snprintf(line, sizeof line, "%s:%d: mesh %s", meshes, 3 + over, grid);
        snprintf(expected, sizeof expected,
                 "%s: the scene's meshes take %.1f MB up to this line, more than 6.25%% of the %.1f MB of memory "
                 "this program may use (the machine's, or ulimit -d's)",
                 line, over * bytes / 1e6, IO_GRID_LIMIT_KB * 1024.0 / 1e6);
        const char *png = fresh("io-heavy.png");
        int status = run_under_limit(n, n == 16 ? objects : meshes, png, output, sizeof output);
        cr_assert_eq(status, 1, "chapter %d exited with %d:\n%s", n, status, output);
        cr_assert_not_null(strstr(output, expected), "chapter %d said\n%s\nnot\n%s", n, output, expected);
        cr_assert_eq(access(png, F_OK), -1, "chapter %d wrote a picture", n);
    }
    /* As many as fit are drawn, under the same limit. */
    char fits[2][256];
    snprintf(fits[0], sizeof fits[0], "%s", repeated_scene("io-fits.scene", REPEAT_MESH, fitting));
    snprintf(fits[1], sizeof fits[1], "%s", repeated_scene("io-fits-objects.scene", REPEAT_OBJECT, fitting));
    for (int k = 0; k < 3; k++) {
        int n = k == 2 ? 16 : 3 + 8 * k;
        const char *png = fresh("io-fits.png");
        int status = run_under_limit(n, fits[n == 16], png, output, sizeof output);
        cr_assert_eq(status, 0, "chapter %d exited with %d:\n%s", n, status, output);
        expect_png(png, 8, 8);
    }
}

/* Images: IO_IMAGE_SIDE pixels square, 16 MiB each as floats (image_map.h), against their share. */
#define IO_IMAGE_SIDE 1024
#define IO_IMAGE_SHARE 0.5 /* of the memory, for the images (texture.c) */

Test(io, images_beyond_their_share_of_memory_are_refused_and_a_file_named_again_is_read_once, .timeout = 120) {
    skip_under_sanitizers();
    double bytes = (double)IO_IMAGE_SIDE * IO_IMAGE_SIDE * 4 * sizeof(float);
    int fitting = (int)(IO_IMAGE_SHARE * IO_GRID_LIMIT_KB * 1024.0 / bytes), over = fitting + 1;
    uint8_t *rgb = malloc((size_t)3 * IO_IMAGE_SIDE * IO_IMAGE_SIDE);
    cr_assert_not_null(rgb);
    for (size_t k = 0; k < (size_t)3 * IO_IMAGE_SIDE * IO_IMAGE_SIDE; k++)
        rgb[k] = (uint8_t)(k % 3 == 0 ? 200 : 90);
    for (int k = 0; k < over; k++) {
        char name[64], err[512];
        snprintf(name, sizeof name, "io-image-%d.png", k);
        cr_assert(image_write_png_bytes(rgb, IO_IMAGE_SIDE, IO_IMAGE_SIDE, fresh(name), err, sizeof err), "%s", err);
    }
    free(rgb);
    char scene[256], expected[2048];
    snprintf(scene, sizeof scene, "%s", repeated_scene("io-images.scene", REPEAT_IMAGE, over));
    snprintf(expected, sizeof expected,
             "%s:%d: pigment 'p%d': the scene's images take %.1f MB up to this line, more than 50%% of the %.1f MB "
             "of memory this program may use (the machine's, or ulimit -d's)",
             scene, 4 + fitting, fitting, over * bytes / 1e6, IO_GRID_LIMIT_KB * 1024.0 / 1e6);
    static char output[16384];
    for (int n = 14; n <= 15; n++) {
        const char *png = fresh("io-images.png");
        int status = run_under_limit(n, scene, png, output, sizeof output);
        cr_assert_eq(status, 1, "chapter %d exited with %d:\n%s", n, status, output);
        cr_assert_not_null(strstr(output, expected), "chapter %d said\n%s\nnot\n%s", n, output, expected);
        cr_assert_eq(access(png, F_OK), -1, "chapter %d wrote a picture", n);
    }
    /* Thirty pigments naming one file take its pixels once: well within the share. */
    snprintf(scene, sizeof scene, "%s", repeated_scene("io-one-image.scene", REPEAT_ONE_IMAGE, 30));
    const char *png = fresh("io-one-image.png");
    int status = run_under_limit(14, scene, png, output, sizeof output);
    cr_assert_eq(status, 0, "chapter 14 exited with %d:\n%s", status, output);
    expect_png(png, 8, 8);
}

/* Chapter 9's kd-tree over the 346,000-triangle teapot, under a limit that its mesh fits in but the
 * tree does not: the program says so and exits with 1, as on bad input (it aborted, status 134). */
#define IO_KDTREE_LIMIT_KB 100000 /* ulimit -v for the run: the build fails from 60 MB to 150 MB */

Test(io, a_kd_tree_that_memory_cannot_hold_ends_the_program_with_a_message, .timeout = 60) {
    skip_under_sanitizers();
    char cwd[1024], text[2048];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    snprintf(text, sizeof text,
             "camera eye 0 1 6 target 0 0 0 fov 40\nimage 8 8\nlight position 0 5 5 colour 1 1 1\n"
             "mesh %s/scenes/models/teapot-346k.ply\n", cwd);
    const char *scene = text_file("io-kdtree-memory.scene", text);
    const char *png = fresh("io-kdtree-memory.png");
    static char command[2048], output[16384];
    snprintf(command, sizeof command, "ulimit -v %d; OMP_NUM_THREADS=1 " IO_TIMEOUT " %s %s --quiet -o %s",
             IO_KDTREE_LIMIT_KB, chapter_program(9), scene, png);
    int status = run_capturing(command, output, sizeof output);
    cr_assert_eq(status, 1, "'%s' exited with %d:\n%s", command, status, output);
    const char *said = "kd-tree: out of memory (a block of ";
    cr_assert(strncmp(output, said, strlen(said)) == 0, "it said:\n%s", output);
    cr_assert_eq(access(png, F_OK), -1, "a picture was written");
}

/* ---- pixels that are not numbers ------------------------------------------------------------------- */

/* A trace that answers NaN for rays leaning right and up, and grey for the others. */
static vec3 nan_up_right(const void *world, const ray *r) {
    (void)world;
    return r->direction.x > 0.0 && r->direction.y > 0.0 ? vec3_make(NAN, 0.5, 0.5) : vec3_make(0.5, 0.5, 0.5);
}

Test(io, the_renderer_counts_the_pixels_that_are_not_numbers) {
    struct camera cam;
    char err[256];
    cr_assert(camera_init(&cam, vec3_make(0, 0, 5), vec3_make(0, 0, 0), vec3_make(0, 1, 0), 40, 8, 6, err, sizeof err),
              "%s", err);
    for (int threads = 1; threads <= 2; threads++) {
        struct image img;
        cr_assert(image_create(&img, 8, 6));
        struct render_job job = {.camera = &cam, .trace = nan_up_right, .threads = threads};
        struct stats total = {0};
        render_image(&job, &img, &total);
        cr_assert_eq(total.non_finite_pixels, 4 * 3, "%" PRIu64 " on %d threads", total.non_finite_pixels, threads);
        image_free(&img);
    }
}

Test(io, a_picture_whose_pixels_are_not_numbers_is_not_written) {
    /* Chapter 8 built with tests/mutants/nan-colour.patch, where total internal reflection comes out NaN,
     * inside a glass sphere looking out at a slant: every ray is reflected back inside. */
    const char *scene = text_file("io-nan.scene", "camera eye 0 0 9 target 1 0 9 fov 60\nimage 16 12\n"
                                                  "light position 0 20 0 colour 1 1 1\n"
                                                  "material glass colour 1 1 1 ambient 0 diffuse 0.05 transmit 0.9 "
                                                  "ior 1.5\nsphere centre 0 0 0 radius 10 material glass\n");
    char command[1024], output[4096], expected[512];
    snprintf(expected, sizeof expected, "%s: 192 pixels came out not a number or infinite, a fault of chapter 8's "
                                        "renderer that this scene brings out; nothing written", scene);
    const char *png = fresh("io-nan.png");
    snprintf(command, sizeof command, IO_TIMEOUT " %s %s --quiet -o %s", mutant_program("nan-colour"), scene, png);
    int status = run_capturing(command, output, sizeof output);
    cr_assert_eq(status, 1, "%s exited with %d:\n%s", command, status, output);
    cr_assert_not_null(strstr(output, expected), "it said:\n%s", output);
    cr_assert_eq(access(png, F_OK), -1, "a picture was written");
    /* The chapter itself draws the scene. */
    snprintf(command, sizeof command, IO_TIMEOUT " %s %s --quiet -o %s", chapter_program(8), scene, png);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    expect_png(png, 16, 12);
}

Test(io, a_pfm_name_in_capitals_is_a_pfm) {
    const char *pfm = fresh("io-radiance.PFM");
    char arguments[512];
    snprintf(arguments, sizeof arguments, "%s --width 8 --height 6 --set paths.samples=1 --quiet -o %s --hdr %s",
             chapter_scene(15), fresh("io-radiance.png"), pfm);
    expect_chapter_run(15, arguments, 0, "");
    size_t size = 0;
    char *bytes = read_file(pfm, &size);
    cr_assert(size > 3 && strncmp(bytes, "PF\n", 3) == 0, "%s does not start as a colour PFM", pfm);
    free(bytes);
}

/* ---- many materials ---------------------------------------------------------------------------- */

#define IO_MANY 100000 /* materials, and spheres using them: a linear search took 17 s for the materials */

Test(io, a_hundred_thousand_materials_parse_quickly, .timeout = 15) {
    size_t size = (size_t)IO_MANY * 80 + 256, used = 0;
    char *text = malloc(size);
    used += (size_t)snprintf(text + used, size - used, "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\n");
    for (int k = 0; k < IO_MANY; k++)
        used += (size_t)snprintf(text + used, size - used, "material m%d diffuse %g\n", k, k / (double)IO_MANY);
    for (int k = IO_MANY - 1; k >= 0; k -= 7)
        used += (size_t)snprintf(text + used, size - used, "sphere centre 0 0 0 radius 1 material m%d\n", k);
    struct scene s;
    char err[256];
    cr_assert(scene_parse("many.scene", text, NULL, &s, err, sizeof err), "%s", err);
    cr_assert_eq(s.material_count, IO_MANY + 1);
    const struct sphere *spheres = scene_shapes(&s, &sphere_syntax)->items;
    cr_assert_eq(spheres[0].material, IO_MANY); /* m99999, after "default" */
    cr_assert_eq(spheres[1].material, IO_MANY - 7);
    cr_assert_eq(scene_find_material(&s, "m123"), 124);
    scene_free(&s);
    free(text);
}

Test(io, name_index_finds_every_name_and_only_those) {
    struct name_index ix;
    name_index_init(&ix);
    cr_assert_eq(name_index_find(&ix, "anything"), -1);
    char name[32];
    for (int k = 0; k < 5000; k++) {
        snprintf(name, sizeof name, "n%d", k);
        cr_assert(name_index_add(&ix, name, k));
    }
    for (int k = 0; k < 5000; k++) {
        snprintf(name, sizeof name, "n%d", k);
        cr_assert_eq(name_index_find(&ix, name), k);
    }
    cr_assert_eq(name_index_find(&ix, "n5000"), -1);
    cr_assert_eq(name_index_find(&ix, ""), -1);
    cr_assert_eq(name_index_find(&ix, "N1"), -1);
    name_index_free(&ix);
}

/* ---- memory --------------------------------------------------------------------------------------- */

/* A 4096 x 4096 picture (16.8 million pixels) with its heat-map. Held as doubles it took 57 bytes a
 * pixel; held as the PNG's bytes, 3 for the picture, 3 for the heat-map and about 3 while stb encodes. */
#define IO_BIG_SIDE 4096
#define IO_MAX_BYTES_PER_PIXEL 12.0

Test(io, a_large_picture_takes_a_few_bytes_per_pixel, .timeout = 120) {
    const char *build = getenv("WHITTED_BUILD");
    if (build != NULL && strstr(build, "san") != NULL)
        cr_skip_test("the sanitizers' shadow memory says nothing about ours");
    char command[512];
    snprintf(command, sizeof command, "%s --width %d --height %d --quiet -o %s --heatmap %s", chapter_program(1),
             IO_BIG_SIDE, IO_BIG_SIDE, fresh("io-big.png"), fresh("io-big-heat.png"));
    cr_assert_eq(system(command), 0);
    struct rusage usage;
    cr_assert_eq(getrusage(RUSAGE_CHILDREN, &usage), 0);
    double bytes_per_pixel = (double)usage.ru_maxrss * 1024.0 / ((double)IO_BIG_SIDE * IO_BIG_SIDE);
    cr_log_info("peak %.1f bytes per pixel", bytes_per_pixel);
    cr_assert_lt(bytes_per_pixel, IO_MAX_BYTES_PER_PIXEL, "peak memory %.1f bytes per pixel", bytes_per_pixel);
    unlink(TEST_OUT "/io-big.png");
    unlink(TEST_OUT "/io-big-heat.png");
}
