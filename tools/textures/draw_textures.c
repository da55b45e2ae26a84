/* draw_textures.c: draws the pictures chapter 14's scenes wrap over their surfaces, so that nothing is
 * downloaded or copied in: a made-up globe (512 x 256, longitude across and latitude up, for a spherical
 * map) and a (u, v) test grid (256 x 256, with a letter F that shows any mirroring or swap of u and v),
 * as PNG and as JPEG.
 *
 *   draw-textures FOLDER     writes FOLDER/globe.png, FOLDER/grid.png and FOLDER/grid.jpg
 *
 * Every colour is chosen as linear light and stored sRGB-encoded, as a camera or a paint program
 * stores it: the files hold encoded numbers, which a renderer must decode (docs/14-textures.md, "Gamma").
 * The output is the same on every run. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#define GLOBE_WIDTH 512
#define GLOBE_HEIGHT 256
#define GRID_SIDE 256
#define GRID_CELLS 8
#define JPEG_QUALITY 95 /* stb writes full-resolution colour (no chroma subsampling) from 90 up */

/* Encodes linear light in [0, 1] with the sRGB curve, rounded to 8 bits. */
static uint8_t encode_srgb(double linear) {
    linear = linear < 0.0 ? 0.0 : linear > 1.0 ? 1.0 : linear;
    double encoded = linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
    return (uint8_t)lround(encoded * 255.0);
}

static void put(uint8_t *pixels, int width, int x, int y, double r, double g, double b) {
    uint8_t *p = pixels + 3 * ((size_t)y * (size_t)width + (size_t)x);
    p[0] = encode_srgb(r);
    p[1] = encode_srgb(g);
    p[2] = encode_srgb(b);
}

/* Land: where a sum of smooth bumps on the unit sphere passes a threshold (made-up continents). */
static double land(double x, double y, double z) {
    static const double bumps[][5] = {/* centre x, y, z, radius, weight */
                                      {0.6, 0.5, 0.62, 0.55, 1.0},   {0.2, -0.3, 0.93, 0.45, 0.9},
                                      {-0.7, 0.55, -0.45, 0.6, 1.1}, {-0.3, -0.55, -0.78, 0.4, 0.8},
                                      {0.85, -0.2, -0.5, 0.35, 0.9}, {-0.5, 0.2, 0.84, 0.3, 0.7}};
    double sum = 0.0;
    for (size_t k = 0; k < sizeof bumps / sizeof bumps[0]; k++) {
        double dx = x - bumps[k][0], dy = y - bumps[k][1], dz = z - bumps[k][2], r = bumps[k][3];
        sum += bumps[k][4] * exp(-(dx * dx + dy * dy + dz * dz) / (r * r));
    }
    return sum;
}

static uint8_t *draw_globe(void) {
    uint8_t *pixels = malloc(3 * GLOBE_WIDTH * GLOBE_HEIGHT);
    if (pixels == NULL)
        return NULL;
    for (int j = 0; j < GLOBE_HEIGHT; j++)
        for (int i = 0; i < GLOBE_WIDTH; i++) {
            double longitude = (i + 0.5) / GLOBE_WIDTH * 2.0 * M_PI; /* 0 at +x, towards +z */
            double latitude = M_PI / 2.0 - (j + 0.5) / GLOBE_HEIGHT * M_PI; /* the top row is the north */
            double x = cos(latitude) * cos(longitude), y = sin(latitude), z = cos(latitude) * sin(longitude);
            double height = land(x, y, z);
            double r, g, b;
            if (fabs(latitude) > 1.25) {
                r = g = b = 0.85; /* ice */
            } else if (height > 0.55) {
                double dry = fmin(1.0, (height - 0.55) * 1.5);
                r = 0.08 + 0.3 * dry, g = 0.25 + 0.05 * dry, b = 0.04; /* green to brown */
            } else {
                double depth = fmin(1.0, (0.55 - height) * 2.0);
                r = 0.01, g = 0.06 + 0.1 * (1 - depth), b = 0.25 + 0.2 * (1 - depth); /* sea */
            }
            /* The graticule every 30 degrees, and the line of longitude 0 in red. */
            double degrees_lon = longitude * 180.0 / M_PI, degrees_lat = latitude * 180.0 / M_PI;
            double step = 360.0 / GLOBE_WIDTH;
            if (fabs(remainder(degrees_lon, 30.0)) < step * 0.75 || fabs(remainder(degrees_lat, 30.0)) < step * 0.75) {
                r = r * 0.5 + 0.3, g = g * 0.5 + 0.3, b = b * 0.5 + 0.3;
            }
            if (degrees_lon < 2.0 * step || degrees_lon > 360.0 - 2.0 * step)
                r = 0.8, g = 0.05, b = 0.05;
            put(pixels, GLOBE_WIDTH, i, j, r, g, b);
        }
    return pixels;
}

/* Is (u, v) on the letter F, drawn in the middle of the grid with v up? */
static bool on_letter_f(double u, double v) {
    bool stem = u >= 0.40 && u < 0.47 && v >= 0.30 && v < 0.72;
    bool top = u >= 0.40 && u < 0.62 && v >= 0.65 && v < 0.72;
    bool bar = u >= 0.40 && u < 0.56 && v >= 0.49 && v < 0.55;
    return stem || top || bar;
}

static uint8_t *draw_grid(void) {
    uint8_t *pixels = malloc(3 * GRID_SIDE * GRID_SIDE);
    if (pixels == NULL)
        return NULL;
    for (int j = 0; j < GRID_SIDE; j++)
        for (int i = 0; i < GRID_SIDE; i++) {
            double u = (i + 0.5) / GRID_SIDE, v = 1.0 - (j + 0.5) / GRID_SIDE; /* v up, rows down */
            int cell_u = (int)(u * GRID_CELLS), cell_v = (int)(v * GRID_CELLS);
            double shade = (cell_u + cell_v) % 2 == 0 ? 1.0 : 0.55;
            double r = shade * (0.1 + 0.8 * u), g = shade * (0.1 + 0.8 * v), b = shade * 0.35;
            if (on_letter_f(u, v))
                r = g = b = 0.95;
            put(pixels, GRID_SIDE, i, j, r, g, b);
        }
    return pixels;
}

/* Writes `pixels` (RGB, width x height) to folder/name, a JPEG when the name ends in .jpg, else a PNG;
 * says which file could not be written. */
static bool write_picture(const char *folder, const char *name, const uint8_t *pixels, int width, int height) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    size_t length = strlen(name);
    bool jpeg = length > 4 && strcmp(name + length - 4, ".jpg") == 0;
    bool ok = jpeg ? stbi_write_jpg(path, width, height, 3, pixels, JPEG_QUALITY)
                   : stbi_write_png(path, width, height, 3, pixels, 3 * width);
    if (!ok)
        fprintf(stderr, "draw-textures: cannot write %s\n", path);
    return ok;
}

int main(int argc, char **argv) {
    if (argc != 2 || argv[1][0] == '-') { /* --help, or an option: not a folder */
        fprintf(stderr, "usage: draw-textures FOLDER\n");
        return 2;
    }
    uint8_t *globe = draw_globe(), *grid = draw_grid();
    bool ok = globe != NULL && grid != NULL;
    if (!ok)
        fprintf(stderr, "draw-textures: out of memory\n");
    ok = ok && write_picture(argv[1], "globe.png", globe, GLOBE_WIDTH, GLOBE_HEIGHT) &&
         write_picture(argv[1], "grid.png", grid, GRID_SIDE, GRID_SIDE) &&
         write_picture(argv[1], "grid.jpg", grid, GRID_SIDE, GRID_SIDE);
    free(globe);
    free(grid);
    return ok ? 0 : 1;
}
