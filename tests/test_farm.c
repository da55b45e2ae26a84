/* test_farm.c: the render farm's pieces on one machine, without Slurm: every chapter's --tile draws
 * exactly the whole picture's pixels, whatever samples them (one ray, the antialias methods, the lens and
 * area lights, the paths, chapter 11's packets), so that tiles joined by build/assemble are the very
 * picture; the tile's errors; and assemble's refusals. (make test-farm runs the same on a one-node Slurm
 * cluster: tools/farm/test-one-node.sh.) */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image.h"
#include "image_test_support.h"
#include "palette_png.h"
#include "test_support.h"

#define FARM_OUT TEST_OUT "/farm"
#define FARM_LOG_SIZE 4096

/* The build folder's assemble program. */
static const char *assemble_program(void) {
    static char path[256];
    const char *build = getenv("WHITTED_BUILD");
    snprintf(path, sizeof path, "%s/assemble", build != NULL ? build : "build");
    return path;
}

/* Makes the folder FARM_OUT/name, empty, and returns its path. */
static const char *fresh_folder(const char *name) {
    static char path[256];
    char command[600], log[FARM_LOG_SIZE];
    snprintf(path, sizeof path, FARM_OUT "/%s", name);
    snprintf(command, sizeof command, "rm -rf '%s' && mkdir -p '%s'", path, path);
    cr_assert_eq(run_capturing(command, log, sizeof log), 0, "%s", log);
    return path;
}

/* Renders chapter n's `scene` at width x height (with the words `extra`) whole, and again as tiles of
 * tile_w x tile_h from the top-left corner (smaller at the right and bottom edges), each a program run of
 * its own; joins the tiles with build/assemble and expects the very file of the whole picture (both are
 * written by one PNG writer, so equal pixels make equal bytes). */
static void expect_tiles_join_into_the_picture(const char *name, int n, const char *scene, const char *extra,
                                                int width, int height, int tile_w, int tile_h) {
    const char *folder = fresh_folder(name);
    char words[512], whole[300], joined[300], command[8192], log[FARM_LOG_SIZE];
    snprintf(whole, sizeof whole, "%s/whole.png", folder);
    snprintf(words, sizeof words, "--width %d --height %d --quiet %s", width, height, extra);
    cr_assert_eq(render_chapter(n, scene, whole, words), 0, "%s: the whole picture", name);
    int length = snprintf(command, sizeof command, "%s -o %s/joined.png", assemble_program(), folder);
    for (int y = 0; y < height; y += tile_h)
        for (int x = 0; x < width; x += tile_w) {
            char tile[300], tile_words[700];
            int w = x + tile_w < width ? tile_w : width - x, h = y + tile_h < height ? tile_h : height - y;
            snprintf(tile, sizeof tile, "%s/tile-%d-%d.png", folder, x, y);
            snprintf(tile_words, sizeof tile_words, "%s --tile %d %d %d %d", words, x, y, w, h);
            cr_assert_eq(render_chapter(n, scene, tile, tile_words), 0, "%s: the tile at %d %d", name, x, y);
            struct image tile_picture = {0};
            char err[512];
            tile_picture.rgb = image_read_rgb(tile, &tile_picture.width, &tile_picture.height, err, sizeof err);
            cr_assert_not_null(tile_picture.rgb, "%s", err);
            cr_expect(tile_picture.width == w && tile_picture.height == h, "%s: the tile is %d x %d, not %d x %d",
                      tile, tile_picture.width, tile_picture.height, w, h);
            image_free(&tile_picture);
            length += snprintf(command + length, sizeof command - (size_t)length, " %s", tile);
        }
    cr_assert_eq(run_capturing(command, log, sizeof log), 0, "%s", log);
    snprintf(joined, sizeof joined, "%s/joined.png", folder);
    snprintf(command, sizeof command, "cmp %s %s", whole, joined);
    cr_expect_eq(run_capturing(command, log, sizeof log), 0, "%s: the joined tiles differ from the whole picture: %s",
                 name, log);
}

Test(tile, one_ray_a_pixel_tiles_join_into_the_picture, .timeout = 60) {
    expect_tiles_join_into_the_picture("one-ray", 8, chapter_scene(8), "", 70, 50, 23, 17);
}

Test(tile, chapter_11s_packets_tiles_join_into_the_picture, .timeout = 120) {
    expect_tiles_join_into_the_picture("packets", 11, chapter_scene(11), "--rung packet", 70, 50, 30, 19);
}

Test(tile, grid_jitter_and_recursive_tiles_of_any_size_join_into_the_picture, .timeout = 120) {
    expect_tiles_join_into_the_picture("grid", 12, chapter_scene(12), "--set antialias.method=grid", 72, 54, 25, 19);
    expect_tiles_join_into_the_picture("jitter", 12, chapter_scene(12), "--set antialias.method=jitter", 72, 54, 25,
                                       19);
    expect_tiles_join_into_the_picture("recursive", 12, chapter_scene(12), "--set antialias.method=recursive", 72, 54,
                                       25, 19);
}

Test(tile, adaptive_tiles_of_whole_blocks_join_into_the_picture, .timeout = 60) {
    /* POV-Ray's adaptive rule looks at neighbours in the block: tiles of whole 32 x 32 blocks */
    expect_tiles_join_into_the_picture("adaptive", 12, chapter_scene(12), "--set antialias.method=adaptive", 90, 70,
                                       64, 32);
}

Test(tile, chapter_13s_lens_and_area_lights_tiles_join_into_the_picture, .timeout = 120) {
    expect_tiles_join_into_the_picture("lens", 13, "scenes/13-focus.scene", "", 60, 45, 22, 16);
    expect_tiles_join_into_the_picture("area-lights", 13, chapter_scene(13), "", 80, 60, 32, 32);
}

Test(tile, chapter_15s_paths_tiles_join_into_the_picture, .timeout = 60) {
    expect_tiles_join_into_the_picture("paths", 15, "scenes/15-paths.scene", "--set paths.samples=4", 40, 30, 17, 11);
}

Test(tile, chapter_16s_moving_instances_tiles_join_into_the_picture, .timeout = 120) {
    if (access("chapters/16-instances", F_OK) != 0)
        cr_skip_test("chapter 16 is not in this copy");
    /* each sample's time in the shutter is hashed from its point, as the lens's rays are */
    expect_tiles_join_into_the_picture("motion", 16, "scenes/16-instances.scene", "--set antialias.samples=2", 64, 40,
                                       23, 17);
}

/* Reads a Portable Float Map as chapter 15 writes it: its size and its floats, rows from the bottom up. */
static float *read_pfm(const char *path, int *width, int *height) {
    size_t size;
    char *bytes = read_file(path, &size);
    int header = 0;
    cr_assert_eq(sscanf(bytes, "PF\n%d %d\n-1.0\n%n", width, height, &header), 2, "%s: not a PFM", path);
    size_t floats = 3 * (size_t)*width * (size_t)*height;
    cr_assert_eq(size, (size_t)header + 4 * floats, "%s: %zu bytes", path, size);
    float *values = malloc(4 * floats);
    cr_assert_not_null(values);
    memcpy(values, bytes + header, 4 * floats); /* little-endian, as this machine */
    free(bytes);
    return values;
}

Test(tile, chapter_15s_radiance_of_a_tile_is_the_whole_pictures_there, .timeout = 60) {
    const char *folder = fresh_folder("radiance");
    char png[300], pfm[300], words[700];
    int width, height, tile_width, tile_height;
    snprintf(png, sizeof png, "%s/whole.png", folder);
    snprintf(pfm, sizeof pfm, "%s/whole.pfm", folder);
    snprintf(words, sizeof words, "--quiet --width 40 --height 30 --set paths.samples=2 --hdr %s", pfm);
    cr_assert_eq(render_chapter(15, "scenes/15-paths.scene", png, words), 0);
    float *whole = read_pfm(pfm, &width, &height);
    snprintf(png, sizeof png, "%s/tile.png", folder);
    snprintf(pfm, sizeof pfm, "%s/tile.pfm", folder);
    snprintf(words, sizeof words, "--quiet --width 40 --height 30 --set paths.samples=2 --tile 7 11 19 13 --hdr %s",
             pfm);
    cr_assert_eq(render_chapter(15, "scenes/15-paths.scene", png, words), 0);
    float *tile = read_pfm(pfm, &tile_width, &tile_height);
    cr_assert(width == 40 && height == 30 && tile_width == 19 && tile_height == 13);
    for (int row = 0; row < tile_height; row++) { /* the tile's row from the top, the whole's row 11 + row */
        const float *ours = &tile[3 * (size_t)(tile_height - 1 - row) * (size_t)tile_width];
        const float *theirs = &whole[3 * ((size_t)(height - 1 - (11 + row)) * (size_t)width + 7)];
        cr_expect_eq(memcmp(ours, theirs, 3 * (size_t)tile_width * sizeof *ours), 0, "row %d of the tile", row);
    }
    free(whole);
    free(tile);
}

Test(tile, a_tiles_heat_map_is_the_tile_with_its_bar) {
    const char *folder = fresh_folder("heatmap");
    char png[300], heat[300], words[700], err[512];
    snprintf(png, sizeof png, "%s/tile.png", folder);
    snprintf(heat, sizeof heat, "%s/heat.png", folder);
    snprintf(words, sizeof words, "--quiet --width 200 --height 150 --tile 20 30 100 60 --heatmap %s", heat);
    cr_assert_eq(render_chapter(10, chapter_scene(10), png, words), 0);
    int width, height;
    uint8_t *rgb = image_read_rgb(heat, &width, &height, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    cr_expect_eq(width, 100);
    cr_expect_gt(height, 60, "the colour bar is under the tile's 60 rows");
    free(rgb);
}

Test(tile, a_tile_outside_the_picture_or_cutting_adaptive_blocks_is_a_usage_error) {
    expect_chapter_run(2, "--width 64 --height 48 --tile 40 0 30 10", 2,
                       "--tile 40 0 30 10: the tile reaches past the 64 x 48 picture (its columns 40 to 69, rows 0 to "
                       "9; the picture's 0 to 63, 0 to 47)");
    expect_chapter_run(2, "--tile 0 0 0 10", 2, "--tile W needs a whole number from 1 to 16384, got '0'");
    expect_chapter_run(2, "--tile 0 0 10", 2,
                       "--tile needs four whole numbers X Y W H: the tile's left column, top row, width and height");
    expect_chapter_run(2, "--tile 0 0 8 8 --pov out/test/x.pov", 2,
                       "--tile renders part of the picture, --pov writes the scene's POV-Ray twin instead of "
                       "rendering; give one of them");
    expect_chapter_run(12, "--set antialias.method=adaptive --width 80 --height 60 --tile 16 0 32 32", 2,
                       "--tile 16 0 32 32: the scene's antialias method compares each pixel with its neighbours in its "
                       "block of 32 x 32 pixels, so a tile must be made of whole blocks: X and Y multiples of 32, X + W "
                       "and Y + H too or the picture's edge (80, 60)");
    expect_chapter_run(12, "--set antialias.method=adaptive --width 80 --height 60 --tile 32 32 48 28 -o out/test/t.png",
                       0, "(the 48 x 28 tile at column 32, row 32 of the 80 x 60 picture)");
}

/* Writes a width x height PNG of one colour at `path`. */
static void write_plain_png(const char *path, int width, int height) {
    struct image img;
    char err[512];
    cr_assert(image_create(&img, width, height));
    cr_assert(image_write_png(&img, path, err, sizeof err), "%s", err);
    image_free(&img);
}

/* Runs assemble with `arguments` in `folder` and expects exit `status` and `message` among what it
 * prints, and no picture written unless it succeeded. */
static void expect_assemble(const char *folder, const char *arguments, int status, const char *message) {
    char command[1024], log[FARM_LOG_SIZE], here[512];
    cr_assert_not_null(getcwd(here, sizeof here));
    snprintf(command, sizeof command, "cd %s && rm -f out.png && %s/%s -o out.png %s", folder, here,
             assemble_program(), arguments);
    int got = run_capturing(command, log, sizeof log);
    cr_expect_eq(got, status, "assemble %s: exit %d, not %d: %s", arguments, got, status, log);
    cr_expect(strstr(log, message) != NULL, "assemble %s printed\n%s\nnot\n%s", arguments, log, message);
    char out[300];
    snprintf(out, sizeof out, "%s/out.png", folder);
    cr_expect_eq(access(out, F_OK) == 0, status == 0, "assemble %s: the picture %s", arguments,
                 status == 0 ? "is missing" : "was written although it failed");
}

Test(assemble, joins_tiles_and_refuses_overlaps_gaps_and_tiles_past_the_edge) {
    const char *folder = fresh_folder("assemble");
    const char *names[] = {"tile-0-0.png", "tile-10-0.png", "tile-0-8.png", "tile-10-8.png", "odd.png"};
    int sizes[][2] = {{10, 8}, {6, 8}, {10, 4}, {6, 4}, {10, 8}};
    for (int k = 0; k < 5; k++) {
        char path[300];
        snprintf(path, sizeof path, "%s/%s", folder, names[k]);
        write_plain_png(path, sizes[k][0], sizes[k][1]);
    }
    expect_assemble(folder, "tile-0-0.png tile-10-0.png tile-0-8.png tile-10-8.png", 0, "");
    expect_assemble(folder, "--size 16 12 tile-0-0.png tile-10-0.png tile-0-8.png --at 10 8 odd.png", 1,
                    "assemble: odd.png: the 10 x 8 tile at column 10, row 8 reaches past the 16 x 12 picture");
    expect_assemble(folder, "--size 16 12 tile-0-0.png tile-10-0.png tile-0-8.png", 1,
                    "assemble: a gap: no tile holds pixel (10, 8) of the 16 x 12 picture");
    expect_assemble(folder, "tile-0-0.png tile-10-0.png tile-0-8.png --at 8 8 tile-10-8.png", 1,
                    "assemble: tile-0-8.png and tile-10-8.png overlap: both hold pixel (8, 8)");
    expect_assemble(folder, "tile-0-0.png --at 5 0 tile-10-0.png", 1,
                    "assemble: tile-0-0.png and tile-10-0.png overlap: both hold pixel (5, 0)");
    expect_assemble(folder, "odd.png", 2, "assemble: odd.png: the name does not end in tile-X-Y.png; give it as --at X Y odd.png");
    expect_assemble(folder, "tile-0-0.png tile-20-0.png", 1, "assemble: tile-20-0.png: cannot open: No such file or directory");
    char junk[300];
    snprintf(junk, sizeof junk, "%s/tile-0-16.png", folder);
    FILE *f = fopen(junk, "w");
    cr_assert_not_null(f);
    fputs("not a picture\n", f);
    fclose(f);
    expect_assemble(folder, "tile-0-16.png", 1,
                    "assemble: tile-0-16.png: not a PNG (its first bytes are not PNG's signature and header)");
    /* a TGA, which stb decodes too and which has no signature: any 18 bytes of header pass for one */
    snprintf(junk, sizeof junk, "%s/tile-20-0.png", folder);
    f = fopen(junk, "wb");
    cr_assert_not_null(f);
    const unsigned char tga[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 4, 0, 24, 0};
    fwrite(tga, 1, sizeof tga, f);
    for (int k = 0; k < 48; k++)
        fputc(k, f);
    fclose(f);
    expect_assemble(folder, "--size 24 8 tile-0-0.png tile-10-0.png tile-20-0.png", 1,
                    "assemble: tile-20-0.png: not a PNG (its first bytes are not PNG's signature and header)");
    /* a palette tile with a pixel past its palette, which stb_image decoded from memory it never filled */
    snprintf(junk, sizeof junk, "%s/palette-tile-0-0.png", folder);
    f = fopen(junk, "wb");
    cr_assert_not_null(f);
    fwrite(palette_png_index_past_end, 1, sizeof palette_png_index_past_end, f);
    fclose(f);
    expect_assemble(folder, "palette-tile-0-0.png", 1,
                    "assemble: palette-tile-0-0.png: damaged: a pixel's palette index is past the end of its palette (2 "
                    "colours)");
    expect_assemble(folder, "--size 0 4 tile-0-0.png", 2, "assemble: --size needs two whole numbers W H from 1 to 16384");
    expect_assemble(folder, "tile-0-0.png -o", 2, "assemble: -o needs a file name");
    /* a FIFO is refused without waiting for a writer (assemble once hung on it) */
    snprintf(junk, sizeof junk, "%s/fifo-tile-0-0.png", folder);
    remove(junk);
    cr_assert_eq(mkfifo(junk, 0644), 0);
    expect_assemble(folder, "fifo-tile-0-0.png", 1, "assemble: fifo-tile-0-0.png: not a regular file (a FIFO)");
    /* a header declaring a huge tile is refused before a pixel is decoded */
    size_t size = 0;
    snprintf(junk, sizeof junk, "%s/tile-0-0.png", folder);
    unsigned char *png = (unsigned char *)read_file(junk, &size);
    cr_assert_not_null(png);
    memcpy(png + 16, (const unsigned char[]){0, 1, 0x86, 0xa0}, 4); /* 100000 wide */
    snprintf(junk, sizeof junk, "%s/tile-0-20.png", folder);
    f = fopen(junk, "wb");
    cr_assert_not_null(f);
    fwrite(png, 1, size, f);
    fclose(f);
    free(png);
    expect_assemble(folder, "tile-0-20.png", 1,
                    "assemble: tile-0-20.png: its header declares 100000 x 8 pixels; a tile has 1 to 16384 a side");
    /* the picture named as one of its tiles: it was written over the tile, exit 0 */
    size_t before_size = 0, after_size = 0;
    char tile[300];
    snprintf(tile, sizeof tile, "%s/tile-0-0.png", folder);
    char *before = read_file(tile, &before_size);
    expect_assemble(folder, "tile-0-0.png tile-10-0.png tile-0-8.png tile-10-8.png -o ./tile-0-0.png", 2,
                    "assemble: -o names './tile-0-0.png', one of the tiles it reads: writing it would destroy it; give "
                    "another file");
    char *after = read_file(tile, &after_size);
    cr_assert(before != NULL && after != NULL);
    cr_expect(before_size == after_size && memcmp(before, after, before_size) == 0, "the tile was overwritten");
    free(before);
    free(after);
}

/* Runs `command` (a farm script's line) and expects exit 2 with `message` among what it prints. */
static void expect_farm_usage_error(const char *command, const char *message) {
    char log[FARM_LOG_SIZE];
    int got = run_capturing(command, log, sizeof log);
    cr_expect_eq(got, 2, "%s: exit %d, not 2: %s", command, got, log);
    cr_expect(strstr(log, message) != NULL, "%s printed\n%s\nnot\n%s", command, log, message);
}

/* Bash's arithmetic reads 010 as octal (8) and refuses 08: farm.sh once submitted 8 tasks for
 * --frames 010, which the chapter read as 10 frames, and said all 10 were there. Both scripts refuse
 * such numbers before anything is submitted or rendered (no sbatch is needed to get there). */
Test(farm, numbers_with_leading_zeros_or_too_many_digits_are_refused) {
    const char *message = "needs whole numbers from 1 to 999999999, written without leading zeros, got '";
    static const char *const options[] = {"--frames 010", "--frames 08", "--tile-size 64 064", "--size 0100 64",
                                          "--frames 1000000000", "--frames 0"};
    for (size_t k = 0; k < sizeof options / sizeof options[0]; k++) {
        char command[256];
        snprintf(command, sizeof command, "bash tools/farm/farm.sh %s -- /bin/true", options[k]);
        expect_farm_usage_error(command, message);
    }
    expect_farm_usage_error("SLURM_ARRAY_TASK_ID=0 bash tools/farm/render.sbatch frames out/test 010 /bin/true",
                            "render.sbatch: FRAMES must be a whole number from 1 to 999999999, written without leading "
                            "zeros, got '010'");
    expect_farm_usage_error("SLURM_ARRAY_TASK_ID=0 bash tools/farm/render.sbatch tiles out/test 64 64 0100 64 /bin/true",
                            "render.sbatch: WIDTH must be a whole number from 1 to 999999999, written without leading "
                            "zeros, got '0100'");
}

/* Writes the shell script `text` as `folder`/`name`/sbatch, a stand-in for Slurm's that a PATH starting
 * with `folder`/`name` finds first. */
static void write_sbatch(const char *folder, const char *name, const char *text) {
    char path[400];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    cr_assert_eq(mkdir(path, 0755), 0);
    snprintf(path, sizeof path, "%s/%s/sbatch", folder, name);
    FILE *script = fopen(path, "w");
    cr_assert_not_null(script);
    fputs(text, script);
    cr_assert_eq(fclose(script), 0);
    cr_assert_eq(chmod(path, 0755), 0);
}

/* A stand-in for Slurm's sbatch in `folder`/stand-in: it records its words in `folder`/submitted and
 * succeeds at once, so that farm.sh runs without a cluster and a test sees whether it submitted. */
static void make_stand_in_sbatch(const char *folder) {
    char text[600];
    snprintf(text, sizeof text, "#!/bin/sh\necho \"$@\" >> '%s/submitted'\n", folder);
    write_sbatch(folder, "stand-in", text);
}

/* Options of the program whose files a farm cannot make: every task (and the size probe) wrote the one
 * --hdr or --heatmap file, and "3 x 2 tiles joined" left the last task's 4 x 4 tile there, exit 0; the
 * program's -o is overridden by each task's own; --quiet silenced the size probe, which then said only
 * "could not read the picture's size from: ". Each is refused, naming the option and why, with exit 2,
 * before anything is made or submitted. */
Test(farm, options_whose_files_a_farm_cannot_make_are_refused_before_anything_is_submitted) {
    char folder[300], pieces[400], submitted[400], hdr[400], heatmap[400], output[800];
    snprintf(folder, sizeof folder, "%s", fresh_folder("refusals"));
    snprintf(pieces, sizeof pieces, "%s/pieces", folder);
    snprintf(submitted, sizeof submitted, "%s/submitted", folder);
    make_stand_in_sbatch(folder);
    const char *const why_tile = "every task would write its tile's %s to that one file, each over the last, leaving "
                                 "only the last task's tile (farm.sh joins only the pictures); render it on one machine";
    snprintf(hdr, sizeof hdr, "farm.sh: the program's --hdr: ");
    snprintf(hdr + strlen(hdr), sizeof hdr - strlen(hdr), why_tile, "radiance");
    snprintf(heatmap, sizeof heatmap, "farm.sh: the program's --heatmap: ");
    snprintf(heatmap + strlen(heatmap), sizeof heatmap - strlen(heatmap), why_tile, "heat-map");
    snprintf(output, sizeof output, "farm.sh: the program's -o: each task writes its piece to a name of its own in %s "
             "(tile-X-Y.png, frame-NNNN.png), given after the program's arguments, so the program's -o would be "
             "overridden; name the joined picture with farm.sh's -o, before --", pieces);
    const char *const quiet = "farm.sh: the program's --quiet: farm.sh reads the picture's size from what the program "
                              "prints when it renders its top-left pixel, which --quiet silences (every task runs quiet "
                              "anyway); leave it out, or give --size W H";
    const char *const animated_tiles = "farm.sh: the program's %s: farm.sh's tiles make one picture, each task a "
                                       "piece of it; for an animation's frames give farm.sh's --frames N, before --";
    const char *const animated_frames = "farm.sh: the program's %s: farm.sh's --frames N gives each task its own frame "
                                        "(--frames N --frame K); leave it out of the program's arguments (a film is "
                                        "made from the frames afterwards)";
    char frames_in_tiles[400], video_in_tiles[400], frame_in_frames[400];
    snprintf(frames_in_tiles, sizeof frames_in_tiles, animated_tiles, "--frames");
    snprintf(video_in_tiles, sizeof video_in_tiles, animated_tiles, "--video");
    snprintf(frame_in_frames, sizeof frame_in_frames, animated_frames, "--frame");
    const char *const tiles = "--tile-size 8 8 --dir %s -- %s --width 20 --height 12 %s";
    const char *const frames = "--frames 2 --dir %s -- %s %s";
    const char *const sized = "--size 20 12 --tile-size 8 8 --dir %s -- %s %s";
    struct farm_run {
        int chapter;
        const char *layout, *option;
        const char *refusal; /* NULL: taken, submitted */
    } const runs[] = {
        {15, tiles, "--hdr x.pfm", hdr},
        {15, tiles, "--heatmap h.png", heatmap},
        {15, tiles, "-o x.png", output},
        {16, frames, "-o f.png", output},
        {15, tiles, "--quiet", quiet},
        /* chapter 16's own frames: in tile mode every task rendered them all (and the size probe wrote
         * /dev/null-0001 on), then nothing could be joined */
        {16, tiles, "--frames 3", frames_in_tiles},
        {16, tiles, "--video", video_in_tiles},
        {16, frames, "--frame 1", frame_in_frames},
        {16, frames, "--heatmap h.png", NULL}, /* chapter 16 numbers each frame's heat-map */
        {15, sized, "--quiet", NULL},          /* with --size nothing is asked of the program */
    };
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        const struct farm_run *r = &runs[k];
        char program[300], words[1200], command[2000], log[FARM_LOG_SIZE];
        snprintf(program, sizeof program, "%s", chapter_program(r->chapter));
        snprintf(words, sizeof words, r->layout, pieces, program, r->option);
        snprintf(command, sizeof command, "PATH=%s/stand-in:$PATH bash tools/farm/farm.sh %s", folder, words);
        remove(submitted);
        if (r->refusal != NULL) {
            expect_farm_usage_error(command, r->refusal);
            cr_expect_neq(access(submitted, F_OK), 0, "%s: submitted", command);
            cr_expect_neq(access(pieces, F_OK), 0, "%s: made %s", command, pieces);
            continue;
        }
        int status = run_capturing(command, log, sizeof log);
        cr_expect_neq(status, 2, "%s: exit 2: %s", command, log);
        char *said = access(submitted, F_OK) == 0 ? read_text_file(submitted) : NULL;
        cr_expect(said != NULL && strstr(said, r->option) != NULL, "%s did not submit %s: %s", command, r->option,
                  log);
        free(said);
    }
}

/* Sizes no chapter draws, and more tiles than a job array is asked for: --size 999999999 999999999 with
 * tiles of 1 x 1 went on to list 10^18 tiles' names without end, and 2000 x 2000 of them submitted 4
 * million tasks and then could not join them. Refused, with exit 2, before anything is submitted. */
Test(farm, sizes_beyond_a_chapters_and_too_many_tiles_are_refused_before_anything_is_submitted) {
    char folder[300], submitted[400];
    snprintf(folder, sizeof folder, "%s", fresh_folder("sizes"));
    snprintf(submitted, sizeof submitted, "%s/submitted", folder);
    make_stand_in_sbatch(folder);
    static const char *const runs[][2] = {
        {"--size 16385 12", "farm.sh: --size must be at most 16384, got 16385"},
        {"--size 999999999 999999999 --tile-size 1 1", "farm.sh: --size must be at most 16384, got 999999999"},
        {"--size 20 12 --tile-size 8 20000", "farm.sh: --tile-size must be at most 16384, got 20000"},
        {"--frames 100001", "farm.sh: --frames must be at most 100000, got 100001"},
        {"--size 2000 2000 --tile-size 1 1", "farm.sh: 2000 x 2000 tiles of 1 x 1 pixels are 4000000 tasks, more than "
                                             "100000; give a larger --tile-size"},
    };
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        char command[1200];
        snprintf(command, sizeof command, "PATH=%s/stand-in:$PATH bash tools/farm/farm.sh %s --dir %s/pieces -- %s",
                 folder, runs[k][0], folder, chapter_program(2));
        remove(submitted);
        expect_farm_usage_error(command, runs[k][1]);
        cr_expect_neq(access(submitted, F_OK), 0, "%s: submitted", command);
    }
}

/* A stand-in for sbatch in `folder`/runner that runs the job array here, its tasks one after another
 * (SLURM_ARRAY_TASK_ID from 0 to the array's last), and fails when a task fails. */
static void make_running_sbatch(const char *folder) {
    write_sbatch(folder, "runner",
                 "#!/bin/sh\nlast=0\nwhile [ $# -gt 0 ]; do\n    case $1 in\n    --array=*) last=${1#--array=0-} ;;\n"
                 "    -*) ;;\n    *) break ;;\n    esac\n    shift\ndone\nk=0\nwhile [ $k -le $last ]; do\n"
                 "    SLURM_ARRAY_TASK_ID=$k bash \"$@\" || exit 1\n    k=$((k + 1))\ndone\n");
}

/* Runs farm.sh's `command`, which must succeed saying `joined`, and leave at `picture` the very bytes of
 * `whole`, the picture of one run. */
static void expect_farm_joins(const char *command, const char *joined, const char *whole, const char *picture) {
    char log[FARM_LOG_SIZE];
    int status = run_capturing(command, log, sizeof log);
    cr_assert_eq(status, 0, "%s exited with %d:\n%s", command, status, log);
    cr_assert_not_null(strstr(log, joined), "%s", log);
    size_t a_size, b_size;
    char *a = read_file(whole, &a_size), *b = read_file(picture, &b_size);
    cr_assert(a_size == b_size && memcmp(a, b, a_size) == 0, "the joined picture is not the picture of one run");
    free(a);
    free(b);
}

/* WHITTED_BUILD may name the build folder by an absolute path: farm.sh took it as relative to the
 * repository, looked for assemble under /work/repo//work/repo/build, and said "the tiles could not be
 * joined" (exit 1) after every task had run. Run by the stand-in above, the tiles join into the very
 * picture of one run. */
Test(farm, an_absolute_build_folder_finds_assemble) {
    char folder[300], cwd[512], build[700], whole[400], picture[400], command[3000];
    snprintf(folder, sizeof folder, "%s", fresh_folder("absolute-build"));
    make_running_sbatch(folder);
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    const char *relative = getenv("WHITTED_BUILD");
    snprintf(build, sizeof build, "%s/%s", cwd, relative != NULL ? relative : "build");
    snprintf(whole, sizeof whole, "%s/whole.png", folder);
    snprintf(picture, sizeof picture, "%s/picture.png", folder);
    cr_assert_eq(render_chapter(2, chapter_scene(2), whole, "--width 20 --height 12"), 0);
    snprintf(command, sizeof command,
             "PATH=%s/runner:$PATH WHITTED_BUILD=%s bash tools/farm/farm.sh --size 20 12 --tile-size 8 8 --dir %s/pieces "
             "-o %s -- %s %s --width 20 --height 12",
             folder, build, folder, picture, chapter_program(2), chapter_scene(2));
    expect_farm_joins(command, "farm.sh: 3 x 2 tiles joined into", whole, picture);
}

/* A picture smaller than a block of 32 x 32 with an adaptive antialias line: its top-left pixel alone is
 * refused (it cuts a block), and so was the size probe's second try, the block, which reaches past the
 * picture ("could not render its top-left corner"). The refusal says the size, which farm.sh now reads. */
Test(farm, the_size_of_an_adaptive_picture_smaller_than_a_block_is_found) {
    char folder[300], whole[400], picture[400], command[3000];
    snprintf(folder, sizeof folder, "%s", fresh_folder("small-adaptive"));
    make_running_sbatch(folder);
    snprintf(whole, sizeof whole, "%s/whole.png", folder);
    snprintf(picture, sizeof picture, "%s/picture.png", folder);
    cr_assert_eq(render_chapter(12, chapter_scene(12), whole, "--width 16 --height 12"), 0);
    snprintf(command, sizeof command,
             "PATH=%s/runner:$PATH bash tools/farm/farm.sh --tile-size 32 32 --dir %s/pieces -o %s -- %s %s --width 16 "
             "--height 12", folder, folder, picture, chapter_program(12), chapter_scene(12));
    expect_farm_joins(command, "farm.sh: 1 x 1 tiles joined into", whole, picture);
}
