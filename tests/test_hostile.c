/* test_hostile.c: hostile inputs for chapters 12 to 15, as a table: numbers that are each in range but
 * make something non-finite inside the program (a texture's transform, texture coordinates, a lens, an
 * area light, an emitter), image files that are not what they claim, numbers read loosely (--set's line
 * numbers, an OBJ index 0, counts shown exactly), and a ray on the edge of a flat mesh, which the
 * brute force of chapters 5 to 8 must not cull. Each row is a scene (and the files it names, written here
 * into a fresh folder), a chapter, and the exit status and exact message expected; or, for a scene that
 * must be accepted, a picture that is not blank. Then the second line of defence: the patterns and the
 * image map looked up at points that are not finite. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include <stb_image.h>

#include "image_map.h"
#include "image_test_support.h"
#include "palette_png.h"
#include "pigment.h"
#include "test_support.h"
#include "texture.h"

/* Each run is tiny (8 x 6 pixels); a run that takes longer than this has hung. */
#define HOSTILE_TIMEOUT "timeout 30"

/* What most rows start with: lines 1 to 3. */
#define VIEW "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40\nlight position 5 8 4\n"
/* A plane seen from above with `light` on it, right where the middle pixel's ray meets it, and a second
 * light that shades the plane from pixel to pixel. */
#define LIGHT_ON_POINT(light)                                                                                  \
    "camera eye 0 5 0 target 0 0 0 up 0 0 1 fov 40\nimage 3 3\nlight position 2 4 1\n" light                   \
    "material m colour 1 1 1 ambient 0.2 diffuse 1\nplane normal 0 1 0 distance 0 material m\n"
/* The scene of the edge hit: one triangle of a flat mesh, seen so that a pixel's ray meets its edge. */
#define EDGE "image 4 3\ncamera eye 0 2 8.5 target 0 0 0 fov 7\nlight position 5 8 4\nmesh @/edge.obj\n"

/* One hostile input. In scene, options and message, @ stands for the folder the files are written to
 * and SCENE for the scene file's path. */
struct hostile {
    int chapter;
    const char *scene;
    const char *options; /* more command-line words, or "" */
    int status;          /* the exit status expected */
    const char *message; /* all of standard error, exactly (less the final newline); NULL: a picture that is
                          * not blank */
};

/* ---- the files the rows name -------------------------------------------------------------------- */

/* Writes size bytes to folder/name. */
static void write_bytes(const char *folder, const char *name, const void *bytes, size_t size) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot write %s", path);
    cr_assert_eq(fwrite(bytes, 1, size, f), size);
    fclose(f);
}

static void write_text(const char *folder, const char *name, const char *text) {
    write_bytes(folder, name, text, strlen(text));
}

/* Makes a fresh folder under TEST_OUT and writes every file the rows name into it. */
static void make_files(char folder[64]) {
    snprintf(folder, 64, TEST_OUT "/hostile-XXXXXX");
    cr_assert_not_null(mkdtemp(folder));
    write_text(folder, "edge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_text(folder, "zero-vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2/0 3/0\n");
    write_text(folder, "big-uv.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1e308 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    write_text(folder, "big-uv.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "property double u\nproperty double v\nelement face 1\nproperty list uchar int vertex_indices\n"
               "end_header\n-1 -1 0 0 0\n1 -1 0 1 1e308\n0 1 0 0 1\n3 0 1 2\n");
    /* Pictures: a real PNG (the one chapter 14's scenes use), and files that only pretend to be one. */
    size_t size = 0;
    uint8_t *png = (uint8_t *)read_file("scenes/textures/grid.png", &size);
    cr_assert_gt(size, 200, "scenes/textures/grid.png is missing (make builds it)");
    write_bytes(folder, "grid.png", png, size);
    write_bytes(folder, "grid.jpg", png, size); /* a PNG by its bytes */
    size_t jpeg_size = 0;
    uint8_t *jpeg = (uint8_t *)read_file("scenes/textures/grid.jpg", &jpeg_size);
    write_bytes(folder, "photo.png", jpeg, jpeg_size); /* a JPEG by its bytes */
    free(jpeg);
    write_bytes(folder, "cut-header.png", png, 20);  /* the signature and half a chunk header */
    /* A whole header, then an image data chunk of 1000 bytes cut off after 50: 954 bytes short of its
     * end (its 1000 bytes and its 4-byte CRC). */
    uint8_t cut_pixels[33 + 8 + 50] = {0};
    memcpy(cut_pixels, png, 33);
    memcpy(cut_pixels + 33, (const uint8_t[]){0, 0, 0x03, 0xe8, 'I', 'D', 'A', 'T'}, 8);
    write_bytes(folder, "cut-pixels.png", cut_pixels, sizeof cut_pixels);
    uint8_t *changed = malloc(size);
    cr_assert_not_null(changed);
    memcpy(changed, png, size);
    const uint8_t huge[8] = {0, 1, 0x86, 0xa0, 0, 1, 0x86, 0xa0}; /* 100000 x 100000 */
    memcpy(changed + 16, huge, sizeof huge);
    write_bytes(folder, "huge.png", changed, size);
    memcpy(changed, png, size);
    const uint8_t wide[8] = {0x01, 0, 0, 0x01, 0, 0, 0, 1}; /* 16777217 x 1: a side past the decoder's */
    memcpy(changed + 16, wide, sizeof wide);
    write_bytes(folder, "wide.png", changed, size);
    /* A whole header, then an image data chunk of a zlib header and 40 bytes no deflate stream starts
     * with, then the end chunk (CRCs are not checked). */
    uint8_t bad_zlib[33 + 12 + 42 + 12] = {0};
    memcpy(bad_zlib, png, 33);
    memcpy(bad_zlib + 33, (const uint8_t[]){0, 0, 0, 42, 'I', 'D', 'A', 'T', 0x78, 0x9c}, 10);
    memset(bad_zlib + 43, 0xff, 40);
    memcpy(bad_zlib + 33 + 12 + 42, (const uint8_t[]){0, 0, 0, 0, 'I', 'E', 'N', 'D'}, 8);
    write_bytes(folder, "bad-zlib.png", bad_zlib, sizeof bad_zlib);
    memcpy(changed, png, size);
    changed[25] = 5; /* colour type 5: none that PNG defines */
    write_bytes(folder, "kind.png", changed, size);
    free(changed);
    free(png);
    const char bmp[] = "BM\x3a\0\0\0\0\0\0\0\x36\0\0\0\x28\0\0\0\x01\0\0\0\x01\0\0\0\x01\0\x18\0";
    write_bytes(folder, "bmp.png", bmp, sizeof bmp);
    const char gif[] = "GIF89a\x01\0\x01\0\x80\0\0\0\0\0\xff\xff\xff!\xf9\x04\x01\0\0\0\0,\0\0\0\0\x01\0\x01\0\0\x02";
    write_bytes(folder, "gif.png", gif, sizeof gif);
    const uint8_t cut_jpeg[] = {0xff, 0xd8, 0xff, 0xe0, 0x00, 0x10, 'J', 'F', 'I', 'F', 0, 1};
    write_bytes(folder, "cut.jpg", cut_jpeg, sizeof cut_jpeg);
    const uint8_t lossless[] = {0xff, 0xd8, 0xff, 0xc3, 0x00, 0x0b, 8, 0, 16, 0, 16, 1, 1, 0x11, 0, 0xff, 0xd9};
    write_bytes(folder, "lossless.jpg", lossless, sizeof lossless);
    /* Palette files of two colours: one every pixel of which names one of them, and one with a pixel that
     * names colour 2, which stb_image looked up in a table the file never filled (palette_png.h). */
    write_bytes(folder, "palette.png", palette_png_checkerboard, sizeof palette_png_checkerboard);
    write_bytes(folder, "palette-past.png", palette_png_index_past_end, sizeof palette_png_index_past_end);
    /* The libFuzzer find: a Huffman table of more than 256 symbols, which stb_image writes past its
     * arrays on. */
    size_t huffman_size = 0;
    uint8_t *huffman =
        (uint8_t *)read_file("tests/data/fuzz/image/jpeg-huffman-table-of-more-than-256-symbols.jpg", &huffman_size);
    cr_assert_not_null(huffman);
    write_bytes(folder, "huffman.jpg", huffman, huffman_size);
    free(huffman);
}

/* ---- running a row -------------------------------------------------------------------------------- */

/* Copies text into out with every @ replaced by folder and every SCENE by scene; with folder NULL, "@/"
 * is left out (a scene names its files relative to its own folder). */
static void expand(const char *text, const char *folder, const char *scene, char *out, size_t size) {
    size_t used = 0;
    out[0] = '\0';
    for (const char *c = text; *c != '\0' && used + 1 < size;) {
        const char *with = NULL;
        if (*c == '@') {
            with = folder != NULL ? folder : "";
            c += folder != NULL || c[1] != '/' ? 1 : 2;
        } else if (strncmp(c, "SCENE", 5) == 0) {
            with = scene;
            c += 5;
        }
        if (with != NULL)
            used += (size_t)snprintf(out + used, size - used, "%s", with);
        else
            out[used++] = *c++;
        if (used >= size)
            used = size - 1;
        out[used] = '\0';
    }
}

/* True when the PNG at path has two pixels of different colours. */
static bool not_blank(const char *path) {
    int w, h, channels;
    uint8_t *pixels = stbi_load(path, &w, &h, &channels, 3);
    cr_assert_not_null(pixels, "cannot read %s", path);
    bool different = false;
    for (long k = 1; k < (long)w * h && !different; k++)
        different = memcmp(pixels, pixels + 3 * k, 3) != 0;
    stbi_image_free(pixels);
    return different;
}

/* Runs row `index` of `rows` in folder and checks its status and message, or its picture. */
static void run_row(const struct hostile *row, int index, const char *folder) {
    char scene[256], picture[256], log[256], text[4096], options[1024], expected[4096], command[4096];
    snprintf(scene, sizeof scene, "%s/row-%d.scene", folder, index);
    snprintf(picture, sizeof picture, "%s/row-%d.png", folder, index);
    snprintf(log, sizeof log, "%s/row-%d.stderr", folder, index);
    expand(row->scene, NULL, scene, text, sizeof text);
    write_text(folder, strrchr(scene, '/') + 1, text);
    expand(row->options, folder, scene, options, sizeof options);
    snprintf(command, sizeof command, HOSTILE_TIMEOUT " %s %s -o %s --quiet %s 2> %s", chapter_program(row->chapter),
             scene, picture, options, log);
    int status = system(command);
    status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    char *err = read_text_file(log);
    size_t length = strlen(err);
    if (length > 0 && err[length - 1] == '\n')
        err[length - 1] = '\0';
    cr_expect_eq(status, row->status, "row %d: '%s' exited with %d, not %d:\n%s\n(scene:\n%s)", index, command, status,
                 row->status, err, text);
    if (row->message != NULL) {
        expand(row->message, folder, scene, expected, sizeof expected);
        cr_expect_str_eq(err, expected, "row %d (chapter %d): said\n%s\nnot\n%s", index, row->chapter, err, expected);
    } else if (status == 0) {
        cr_expect_str_eq(err, "", "row %d: accepted, but said:\n%s", index, err);
        cr_expect(not_blank(picture), "row %d (chapter %d): the picture is blank:\n%s", index, row->chapter, text);
    }
    free(err);
}

static void run_rows(const struct hostile *rows, size_t count) {
    char folder[64];
    make_files(folder);
    for (size_t k = 0; k < count; k++)
        run_row(&rows[k], (int)k, folder);
}

#define RUN_ROWS(rows) run_rows(rows, sizeof rows / sizeof rows[0])

/* ---- 1: non-finite numbers born inside the program ---------------------------------------------- */

#define SPHERE_PAINTED "material m colour 1 1 1 pigment p\nsphere centre 0 0 0 radius 1.5 material m\n"

/* A triangle 2 long and 1e-170 wide: its normal's squared length vanished, and the row of rays on its
 * edge (the 8th of 15) came out NaN, so the chapters refused to write the picture. */
#define THIN_TRIANGLE "image 15 15\ncamera eye 0 0 5 target 0 0 0 fov 40\nlight position 0 0 5\n" \
                      "triangle a -1 0 0 b 1 0 0 c 0 1e-170 0\n"

static const struct hostile non_finite[] = {
    {3, THIN_TRIANGLE, "", 0, NULL},
    {11, THIN_TRIANGLE, "", 0, NULL},
    {16, THIN_TRIANGLE, "", 0, NULL},
    /* the texture transform: the point it makes must stay finite */
    {14, VIEW "pigment p image_map file @/grid.png rotate 1e308 0 0\n" SPHERE_PAINTED, "", 1,
     "SCENE:4: pigment 'p': rotate is (1e+308, 0, 0); it must stay within -1e+06 .. 1e+06"},
    {14, VIEW "pigment p image_map file @/grid.png scale 1e-320 1 1\n" SPHERE_PAINTED, "", 1,
     "SCENE:4: pigment 'p': scale 9.99988867182683e-321 is out of range (its size must be from 1e-09 to 1e+09)"},
    {14, VIEW "pigment p checker colour 1 1 1 colour2 0 0 0 translate 1e308 0 0\n" SPHERE_PAINTED, "", 1,
     "SCENE:4: pigment 'p': translate is (1e+308, 0, 0); it must stay within -1e+18 .. 1e+18"},
    {12, VIEW "pigment p checker colour 1 1 1 colour2 0 0 0 scale 1 1e10 1\n" SPHERE_PAINTED, "", 1,
     "SCENE:4: pigment 'p': scale 10000000000 is out of range (its size must be from 1e-09 to 1e+09)"},
    /* at the limits the patterns draw: the points are huge, and still safe */
    {14, VIEW "pigment p checker colour 1 1 1 colour2 0 0 0 scale 1e-9 1e-9 1e-9 translate 1e18 -1e18 1e18\n"
              SPHERE_PAINTED "plane normal 0 1 0 distance -2 material m\n", "", 0, NULL},
    {14, VIEW "pigment p brick colour 1 1 1 colour2 0 0 0 scale 1e-9 1e-9 1e-9 rotate 1e6 -1e6 1e6\n" SPHERE_PAINTED,
     "", 0, NULL},
    {15, VIEW "pigment p image_map file @/grid.png interpolate 2 scale 1e-9 1e-9 1 translate 1e18 1e18 0\n"
              "material m colour 1 1 1 pigment p\nsphere centre 0 0 0 radius 1.5 material m\n"
              "paths samples 2\nmaterial lamp emission 4 4 4\nsphere centre 3 3 3 radius 1 material lamp\n",
     "", 0, NULL},
    /* texture coordinates from mesh files */
    {14, VIEW "pigment p image_map file @/grid.png map uv\nmaterial m colour 1 1 1 pigment p\n"
              "mesh @/big-uv.obj material m\n", "", 1,
     "SCENE:6: mesh @/big-uv.obj: texture coordinate 2 is (1e+308, 0); texture coordinates must stay within "
     "-1e+18 .. 1e+18"},
    {15, VIEW "pigment p image_map file @/grid.png map uv\nmaterial m colour 1 1 1 pigment p\n"
              "mesh @/big-uv.ply material m\n", "", 1,
     "SCENE:6: mesh @/big-uv.ply: texture coordinate 2 is (1, 1e+308); texture coordinates must stay within "
     "-1e+18 .. 1e+18"},
    /* the lens */
    {13, "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40 aperture 1e308 focal_point 0 0 0\n"
         "light position 5 8 4\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:2: camera aperture must be at most 1e+18, got 1e+308"},
    {13, "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40 aperture 0.1 focal_point 1e200 0 0\n"
         "light position 5 8 4\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:2: camera focal_point is (1e+200, 0, 0); it must stay within -1e+18 .. 1e+18"},
    {12, "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40 aperture 0.1 focal_point 0 0 -1e200\n"
         "light position 5 8 4\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:2: camera focal_point is (0, 0, -1e+200); it must stay within -1e+18 .. 1e+18"},
    /* a lens so wide against its focal distance that its rays start where no box can be told from another
     * (every ray would test every triangle): refused, in every chapter that draws a lens */
    {13, "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40 aperture 1e18 focal_point 0 0 0\n"
         "light position 5 8 4\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:2: camera aperture must be at most 1000 times the focal_point's distance from the eye (5), got 1e+18: "
     "a wider lens blurs everything off the focal plane over the whole picture"},
    {16, "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40 aperture 5001 focal_point 0 0 0\n"
         "light position 5 8 4\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:2: camera aperture must be at most 1000 times the focal_point's distance from the eye (5), got 5001: "
     "a wider lens blurs everything off the focal plane over the whole picture"},
    {13, "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40 aperture 5000 focal_point 0 0 0\n"
         "light position 5 8 4\nsphere centre 0 0 0 radius 1\n", "", 0, NULL},
    {13, "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40 aperture 1e18 focal_point 0 0 -1e18\n"
         "light position 5 8 4\nplane normal 0 0 1 distance -1e17\nsphere centre 0 0 0 radius 1\n", "", 0, NULL},
    /* area lights: zero, too long, too short and parallel whatever the scale */
    {13, VIEW "light position 0 3 0 axis1 1e200 0 0 axis2 0 0 1e200 samples 2 2\nsphere centre 0 0 0 radius 1\n",
     "", 1, "SCENE:4: light axis1 is (1e+200, 0, 0); it must stay within -1e+18 .. 1e+18"},
    {13, VIEW "light position 0 3 0 axis1 1e-170 0 0 axis2 0 0 1e-170 samples 2 2\nsphere centre 0 0 0 radius 1\n",
     "", 1, "SCENE:4: light axis1 is 1e-170 long; an axis must be at least 1e-18 long"},
    {13, VIEW "light position 0 3 0 axis1 0 0 0 axis2 0 0 1 samples 2 2\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: light axis1 is zero: the area light has no rectangle"},
    {13, VIEW "light position 0 3 0 axis1 1e17 1e17 0 axis2 2e17 2e17 0 samples 2 2\nsphere centre 0 0 0 radius 1\n",
     "", 1, "SCENE:4: light axis1 and axis2 are parallel: the area light has no rectangle"},
    {13, VIEW "light position 0 3 0 axis1 1e-17 1e-17 0 axis2 2e-17 2e-17 0 samples 2 2\n"
              "sphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: light axis1 and axis2 are parallel: the area light has no rectangle"},
    {13, VIEW "light position 0 3 0 axis1 1e-17 0 0 axis2 0 0 1e-17 samples 3 3\nsphere centre 0 0 0 radius 1\n", "", 0,
     NULL},
    /* the least length itself is enough (it was measured just short of it, and refused as "1e-18 long; an
     * axis must be at least 1e-18 long"); a little less is not */
    {13, VIEW "light position 0 3 0 axis1 1e-18 0 0 axis2 0 0 1e-18 samples 2 2\nsphere centre 0 0 0 radius 1\n", "", 0,
     NULL},
    {13, VIEW "light position 0 3 0 axis1 0 -9.9e-19 0 axis2 0 0 1e-18 samples 2 2\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: light axis1 is 9.9e-19 long; an axis must be at least 1e-18 long"},
    {15, VIEW "light position 0 3 0 axis1 1e-17 0 0 axis2 0 0 1e-17 samples 3 3\nsphere centre 0 0 0 radius 1\n"
              "paths samples 2\nmaterial lamp emission 4 4 4\nsphere centre 3 3 3 radius 1 material lamp\n",
     "", 0, NULL},
    {15, VIEW "light position 1e300 3 0 axis1 1 0 0 axis2 0 0 1 samples 2 2\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: an area light's position is (1e+300, 3, 0); it must stay within -1e+18 .. 1e+18"},
    /* emitters: a sum of powers that would be infinite (a radius past KEY_MAX_COORD is refused first),
     * and the largest emitter in range drawn */
    {15, VIEW "material e emission 1e308 1e308 1e308\nsphere centre 0 0 0 radius 1 material e\n", "", 1,
     "SCENE:4: material 'e': emission must be at most 1e+18 in each channel, got 1e+308 1e+308 1e+308"},
    {15, VIEW "light position 0 3 0 colour 1e300 1 1 axis1 1 0 0 axis2 0 0 1 samples 2 2\n"
              "sphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: light colour is (1e+300, 1, 1); it must stay within -1e+18 .. 1e+18"},
    {15, VIEW "material e emission 1e18 1e18 1e18\nsphere centre 0 0 -1e200 radius 1e199 material e\n"
              "sphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:5: sphere radius must be between 1e-18 and 1e+18, got 1e+199"},
    {15, VIEW "material e emission 1e18 1e18 1e18\nsphere centre 0 0 -1e18 radius 1e18 material e\n"
              "sphere centre 0 0 0 radius 1\npaths samples 2\n", "", 0, NULL},
    {15, VIEW "material e emission 1e18 1e18 1e18\nsphere centre 0 3 0 radius 0.5 material e\n"
              "sphere centre 0 0 0 radius 1\npaths samples 2\n", "", 0, NULL},
    /* surfaces that give back more light than reaches them: a colour of 1e300 seen through glass twice was
     * infinite; every chapter holds a surface's values to 100, and the path tracers to 1 */
    {8, VIEW "material g colour 1e300 0 0 filter 0.9 ior 1.5\nsphere centre 0 0 0 radius 1 material g\n", "", 1,
     "SCENE:4: material 'g': colour must be at most 100 in each channel, got 1e+300 0 0"},
    {8, VIEW "material g colour 1 1 1 reflection 1e300\nsphere centre 0 0 0 radius 1 material g\n", "", 1,
     "SCENE:4: material 'g': reflection must be at most 100, got 1e+300"},
    {14, VIEW "pigment p checker colour 1 1 1 colour2 0 1e300 0\n", "", 1,
     "SCENE:4: pigment 'p': colour2 must be at most 100 in each channel, got 0 1e+300 0"},
    {15, VIEW "background 1e300 0 0\nsphere centre 0 0 0 radius 1\npaths samples 2\n", "", 1,
     "SCENE:4: background is (1e+300, 0, 0); it must stay within -1e+18 .. 1e+18"},
    {8, VIEW "material g colour 1 1 1 diffuse 0.8 reflection 0.5\nsphere centre 0 0 0 radius 1 material g\n", "", 0,
     NULL}, /* POV-Ray's reflection comes on top of the rest */
    {15, VIEW "material g colour 1 1 1 diffuse 0.8 reflection 0.5\nsphere centre 0 0 0 radius 1 material g\n"
              "paths samples 2\nmaterial lamp emission 4 4 4\nsphere centre 3 3 3 radius 1 material lamp\n", "", 1,
     "SCENE:4: material 'g': diffuse * colour + reflection is 1.3; a surface gives back at most the light that "
     "reaches it, so it must be at most 1"},
    {17, VIEW "pigment p checker colour 1 1 1 colour2 2 0 0\nmaterial g pigment p diffuse 0.5\n"
              "sphere centre 0 0 0 radius 1 material g\npaths samples 2\nmaterial lamp emission 4 4 4\n"
              "sphere centre 3 3 3 radius 1 material lamp\n", "", 1,
     "SCENE:5: material 'g': a colour channel of 2 (its pigment's); a surface gives back at most the light that "
     "reaches it, so each channel must be at most 1"},
    {15, VIEW "material g colour 1 1 1 filter 1 ior 1.5\nsphere centre 0 0 0 radius 1 material g\n"
              "paths samples 2\nmaterial lamp emission 4 4 4\nsphere centre 3 3 3 radius 1 material lamp\n"
              "background 0.2 0.3 0.4\n", "", 0, NULL},
    /* nothing at all gives off light: not a black picture with exit 0, but a reason */
    {15, VIEW "sphere centre 0 0 0 radius 1\npaths samples 2\n", "", 1,
     "SCENE: nothing gives off light, so the picture would be black: no material has an emission, no light has an "
     "area (chapter 15 ignores 1 point light) and the background is black"},
    {15, VIEW "background 0.2 0.3 0.4\nsphere centre 0 0 0 radius 1\npaths samples 2\n", "", 0, NULL},
    /* an area light of colour 0: it has an area, but gives off nothing */
    {15, VIEW "sphere centre 0 0 0 radius 1\npaths samples 2\n"
              "light position 0 3 0 colour 0 0 0 axis1 1 0 0 axis2 0 0 1 samples 2 2\n", "", 1,
     "SCENE: nothing gives off light, so the picture would be black: no material has an emission, the area light "
     "gives off nothing (its colour not above 0) (chapter 15 ignores 1 point light) and the background is black"},
    /* an area light with a negative channel: light taken away in the Whitted chapters (POV-Ray's rule), a
     * surface giving off less than none to a path, refused as a negative emission is */
    {15, VIEW "sphere centre 0 0 0 radius 1\npaths samples 2\n"
              "light position 0 3 0 colour 3 -1 -1 axis1 1 0 0 axis2 0 0 1 samples 2 2\n", "", 1,
     "SCENE:6: light colour must not be negative in chapter 15, got 3 -1 -1: an area light is a surface that gives "
     "off light here, and none gives off less than none"},
    {17, VIEW "sphere centre 0 0 0 radius 1\npaths samples 2\n"
              "light position 0 3 0 colour 3 1 -1e-300 axis1 1 0 0 axis2 0 0 1 samples 2 2\n", "", 1,
     "SCENE:6: light colour must not be negative in chapter 17, got 3 1 -1e-300: an area light is a surface that "
     "gives off light here, and none gives off less than none"},
    {13, VIEW "sphere centre 0 0 0 radius 1\n"
              "light position 0 3 0 colour 3 -1 -1 axis1 1 0 0 axis2 0 0 1 samples 2 2\n", "", 0, NULL},
    /* a negative background: light from every direction, less than none to a path (it drew black with exit 0
     * without an emitter, and wrote negative radiance into --hdr with one) */
    {15, VIEW "background -1 -1 -1\nsphere centre 0 0 0 radius 1\npaths samples 2\nmaterial lamp emission 4 4 4\n"
              "sphere centre 3 3 3 radius 1 material lamp\n", "", 1,
     "SCENE:4: background must not be negative in chapter 15, got -1 -1 -1: it is light that comes from every "
     "direction here, and none gives off less than none"},
    {17, VIEW "background 0.5 0.5 -1e-300\nsphere centre 0 0 0 radius 1\npaths samples 2\n", "", 1,
     "SCENE:4: background must not be negative in chapter 17, got 0.5 0.5 -1e-300: it is light that comes from "
     "every direction here, and none gives off less than none"},
    /* an ior so small that the square of the ratio of two overflowed (NaN pixels in chapter 17) */
    {17, VIEW "material g colour 1 1 1 ambient 0 diffuse 0 transmit 1 ior 1e-155 roughness 0.5\n"
              "sphere centre 0 0 0 radius 1 material g\n", "", 1,
     "SCENE:4: material 'g': ior 1e-155 is out of range (from 1e-50 to 1e+50)"},
    /* an emitter no ray can hit: a triangle with its corners in a line */
    {17, VIEW "sphere centre 0 0 0 radius 1\npaths samples 2\nmaterial lamp emission 4 4 4\n"
              "triangle a 0 3 0 b 1 4 1 c 2 5 2 material lamp\n", "", 1,
     "SCENE: nothing gives off light, so the picture would be black: the 1 emissive surface gives no power (no "
     "area, its corners in a line, or an emission times area below double's range) and the background is black"},
    /* a light on the very point a camera ray hits (the middle pixel's): no direction to it, which made a NaN
     * pixel and a refused picture; it lights nothing there */
    {6, LIGHT_ON_POINT("light position 0 0 0\n"), "", 0, NULL},
    {8, LIGHT_ON_POINT("light position 0 0 0\n"), "", 0, NULL},
    {13, LIGHT_ON_POINT("light position 0 0 0 axis1 1 0 0 axis2 0 0 1 samples 3 3 circular on orient on\n"), "", 0, NULL},
    {16, LIGHT_ON_POINT("light position 0 0 0\n"), "", 0, NULL},
};

Test(hostile, numbers_that_are_in_range_make_nothing_that_is_not_finite, .timeout = 120) { RUN_ROWS(non_finite); }

/* ---- 4: image files ------------------------------------------------------------------------------- */

#define PAINT(file) VIEW "pigment p image_map file " file "\n" SPHERE_PAINTED

/* Chapter `chapter` refuses the picture `file` of the pigment on line 4 with the reason `why`. */
#define REFUSED_IMAGE(chapter, file, why) {chapter, PAINT("@/" file), "", 1, "SCENE:4: pigment 'p': @/" file ": " why}

static const struct hostile image_files[] = {
    REFUSED_IMAGE(14, "bmp.png", "not a PNG or JPEG image (its first bytes are neither signature: a BMP, it seems)"),
    REFUSED_IMAGE(14, "gif.png", "not a PNG or JPEG image (its first bytes are neither signature: a GIF, it seems)"),
    REFUSED_IMAGE(14, "cut-header.png", "truncated: 20 bytes, too few for a PNG's header"),
    REFUSED_IMAGE(14, "cut-pixels.png", "truncated: the file ends inside its 'IDAT' chunk, 954 bytes short"),
    REFUSED_IMAGE(15, "huffman.jpg", "a damaged JPEG: a Huffman table codes more than 256 symbols"),
    REFUSED_IMAGE(14, "huge.png", "its header declares 100000 x 100000 pixels, more than the 67108864 an image map "
                                  "may have"),
    REFUSED_IMAGE(14, "wide.png", "its header declares 16777217 x 1 pixels: a side of more than 16777216 pixels, "
                                  "which the decoder does not take"),
    /* stb_image gives no reason of its own here; it once showed a JPEG test's stale one ("no SOI") */
    REFUSED_IMAGE(14, "bad-zlib.png", "truncated or damaged: its pixels cannot be decoded (the decoder gives no "
                                      "reason)"),
    REFUSED_IMAGE(15, "kind.png", "a kind of PNG that is not supported (colour type 5, bit depth 8, compression 0, "
                                  "filter 0, interlace 0)"),
    REFUSED_IMAGE(14, "grid.jpg", "a PNG named as a JPEG: POV-Ray reads an image map by its name (.jpg or .jpeg "
                                  "for a JPEG, anything else for a PNG), so rename it"),
    REFUSED_IMAGE(15, "photo.png", "a JPEG named as a PNG: POV-Ray reads an image map by its name (.jpg or "
                                   ".jpeg for a JPEG, anything else for a PNG), so rename it"),
    REFUSED_IMAGE(14, "cut.jpg", "truncated or damaged: 12 bytes, and no JPEG frame header among them"),
    REFUSED_IMAGE(15, "lossless.jpg", "a kind of JPEG that is not supported (frame type 0xc3: only baseline and "
                                      "progressive JPEGs are)"),
    REFUSED_IMAGE(14, "palette-past.png", "damaged: a pixel's palette index is past the end of its palette (2 "
                                          "colours)"),
    {14, PAINT("@/grid.png"), "", 0, NULL},
    {14, PAINT("@/palette.png"), "", 0, NULL},
    /* chapters 12 and 13 draw no pigments and read no pictures: the scene is drawn in the material's colour */
    {12, PAINT("@/bmp.png"), "", 0, NULL},
    {13, PAINT("@/huge.png"), "", 0, NULL},
};

Test(hostile, image_files_are_checked_before_they_are_decoded, .timeout = 120) { RUN_ROWS(image_files); }

/* ---- 5: numbers read loosely ---------------------------------------------------------------------- */

static const struct hostile loose_numbers[] = {
    {12, VIEW "sphere centre 0 0 0 radius 1\n", "--set light.4294967297.colour='1 0 0'", 2,
     "--set light.4294967297.colour=1 0 0: '4294967297' is not a line number (digits only, at most 2147483647)"},
    {13, VIEW "sphere centre 0 0 0 radius 1\n", "--set light.2x.colour='1 0 0'", 2,
     "--set light.2x.colour=1 0 0: '2x' is not a line number (digits only, at most 2147483647)"},
    {14, VIEW "sphere centre 0 0 0 radius 1\n", "--set light.1.colour='1 0 0'", 0, NULL},
    {14, VIEW "mesh @/zero-vt.obj\n", "", 1, "SCENE:4: mesh: @/zero-vt.obj:5: vt index 0 is invalid (OBJ indices start at 1)"},
    {12, VIEW "mesh @/zero-vt.obj\n", "", 1, "SCENE:4: mesh: @/zero-vt.obj:5: vt index 0 is invalid (OBJ indices start at 1)"},
    {15, VIEW "paths samples 1048577\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: paths samples must be a whole number from 1 to 1048576, got 1048577"},
    {12, VIEW "antialias method grid samples 1234567\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: antialias samples must be a whole number from 1 to 16 for method grid, got 1234567"},
    {13, VIEW "light position 0 3 0 axis1 1 0 0 axis2 0 0 1 samples 1234567 2\nsphere centre 0 0 0 radius 1\n", "", 1,
     "SCENE:4: light samples must be whole numbers from 1 to 33, got 1234567 2"},
    /* a byte-order mark before the first word, as some editors write UTF-8 */
    {2, "\xef\xbb\xbf" VIEW "sphere centre 0 0 0 radius 1\n", "", 0, NULL},
};

Test(hostile, numbers_are_read_strictly_and_shown_exactly, .timeout = 120) { RUN_ROWS(loose_numbers); }

/* ---- 6: a ray on the edge of a flat mesh -------------------------------------------------------- */

static const struct hostile edge_hits[] = {
    {12, EDGE, "", 0, NULL},
    {13, EDGE, "", 0, NULL},
    {14, EDGE, "", 0, NULL},
    {15, EDGE "paths samples 2\nmaterial lamp emission 40 40 40\nsphere centre 5 8 4 radius 1 material lamp\n", "", 0,
     NULL},
};

Test(hostile, a_flat_mesh_is_drawn_by_every_later_chapter, .timeout = 120) { RUN_ROWS(edge_hits); }

/* The brute force (chapters 5 to 8) culls each mesh by its box; a flat mesh's box has no thickness, and
 * the bare slab test turned away a ray through pixel (3, 1) that meets the triangle's edge and that the
 * triangle test, and so chapter 10's BVH, counts as a hit. Chapters 8, 9 and 10 shade alike and must
 * draw the very same picture. */
Test(hostile, the_brute_force_draws_an_edge_hit_as_the_bvh_does, .timeout = 60) {
    char folder[64], scene[128], pictures[3][128];
    make_files(folder);
    snprintf(scene, sizeof scene, "%s/edge.scene", folder);
    char text[512];
    expand(EDGE, NULL, scene, text, sizeof text);
    write_text(folder, "edge.scene", text);
    const int chapters[3] = {10, 8, 9};
    for (int k = 0; k < 3; k++) {
        snprintf(pictures[k], sizeof pictures[k], "%s/edge-%d.png", folder, chapters[k]);
        cr_assert_eq(render_chapter(chapters[k], scene, pictures[k], "--quiet"), 0, "chapter %d", chapters[k]);
    }
    cr_assert(not_blank(pictures[0]), "chapter 10 draws the triangle");
    for (int k = 1; k < 3; k++) {
        struct image_difference d = compare_png(pictures[k], pictures[0]);
        cr_expect_eq(d.max, 0, "chapter %d differs from chapter 10 by up to %d levels (%ld pixels over 2)",
                     chapters[k], d.max, d.pixels_over_2);
    }
}

/* A file's normals are made unit however long they are: normals of length 1e200 (whose squares overflow)
 * shade exactly as the same directions of length 1, not as a flat triangle. */
Test(hostile, a_files_normals_of_any_length_shade_alike, .timeout = 60) {
    char folder[64], pictures[3][128];
    make_files(folder);
    static const char *const meshes[3] = {
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 1e200 0 1e200\nf 1//1 2//1 3//1\n",
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 1 0 1\nf 1//1 2//1 3//1\n",
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n", /* flat */
    };
    for (int k = 0; k < 3; k++) {
        char name[32], scene[128], text[512];
        snprintf(name, sizeof name, "normals-%d.obj", k);
        write_text(folder, name, meshes[k]);
        snprintf(text, sizeof text, VIEW "mesh %s\n", name);
        snprintf(name, sizeof name, "normals-%d.scene", k);
        write_text(folder, name, text);
        snprintf(scene, sizeof scene, "%s/%s", folder, name);
        snprintf(pictures[k], sizeof pictures[k], "%s/normals-%d.png", folder, k);
        cr_assert_eq(render_chapter(14, scene, pictures[k], "--quiet"), 0, "%s", meshes[k]);
    }
    struct image_difference same = compare_png(pictures[0], pictures[1]);
    cr_expect_eq(same.max, 0, "normals of length 1e200 shade unlike those of length 1, by up to %d levels", same.max);
    struct image_difference flat = compare_png(pictures[1], pictures[2]);
    cr_expect_gt(flat.max, 0, "the tilted normals change the shading (else this test could not fail)");
}

/* ---- the second line of defence: patterns at any point ---------------------------------------- */

static const double strange[] = {NAN, INFINITY, -INFINITY, 1e300, -1e300, 4e9, -4e9};
#define STRANGE_COUNT (sizeof strange / sizeof strange[0])

/* A 2 x 2 image map with every mapping, wrap and interpolation, looked up at points that are not finite
 * or far beyond int's range: each lookup reads a texel of the image (ASan would see any other read) and
 * gives a finite colour. */
Test(hostile, an_image_map_looked_up_anywhere_reads_only_its_texels) {
    float texels[16] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1};
    struct pigment p = {.pattern = PIGMENT_IMAGE_MAP, .image = {.width = 2, .height = 2, .texels = texels, .opaque = true}};
    for (int mapping = 0; mapping < 2; mapping++)
        for (int once = 0; once < 2; once++)
            for (int interpolate = 0; interpolate <= 2; interpolate += 2)
                for (size_t a = 0; a < STRANGE_COUNT; a++)
                    for (size_t b = 0; b < STRANGE_COUNT; b++) {
                        p.mapping = (enum pigment_mapping)mapping;
                        p.once = once;
                        p.interpolate = interpolate;
                        double rgba[4];
                        image_map_lookup(&p, vec3_make(strange[a], strange[b], 0.5), rgba);
                        for (int c = 0; c < 4; c++)
                            cr_assert(rgba[c] >= 0.0 && rgba[c] <= 1.0,
                                      "mapping %d once %d interpolate %d at (%g, %g): channel %d is %g", mapping,
                                      once, interpolate, strange[a], strange[b], c, rgba[c]);
                    }
}

/* Every pattern at such points: a colour that is one of its two, or between them; never NaN. */
Test(hostile, every_pattern_at_any_point_gives_a_finite_colour) {
    const enum pigment_pattern patterns[] = {PIGMENT_CHECKER, PIGMENT_GRADIENT, PIGMENT_BRICK, PIGMENT_RADIAL};
    for (size_t k = 0; k < sizeof patterns / sizeof patterns[0]; k++) {
        struct pigment p = {.pattern = patterns[k], .colour = {{0.25, 0.25, 0.25}, {0.75, 0.75, 0.75}},
                            .axis = {0, 1, 0}, .brick_size = {8, 3, 4.5}, .mortar = 0.5, .scale = {1, 1, 1}};
        for (size_t a = 0; a < STRANGE_COUNT; a++)
            for (size_t b = 0; b < STRANGE_COUNT; b++) {
                struct texture_colour c = texture_pigment_at(&p, vec3_make(strange[a], strange[b], strange[a]));
                cr_assert(c.colour.x >= 0.25 && c.colour.x <= 0.75 && vec3_is_finite(c.colour),
                          "pattern %d at (%g, %g, %g): %g", (int)patterns[k], strange[a], strange[b], strange[a],
                          c.colour.x);
            }
    }
}
