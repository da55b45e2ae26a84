/* forest.c: writes chapter 16's forest, a scene of many instanced teapots and bunnies (make bench).
 *
 *   forest [--instances N] [--models DIR] OUTPUT.scene
 *
 * N instances (default 10,000; 1 to FOREST_MAX_INSTANCES) on a square grid of FOREST_SPACING units,
 * centred on the origin, every even-numbered one the big teapot (models/teapot-346k.ply, 349,872
 * triangles) and every odd one the bunny (models/bunny.ply, 3,674 triangles): at 10,000 that is
 * 5,000 teapots and 1,749,360,000 triangles instanced, plus 18,370,000 of the bunnies. DIR is the
 * models' folder as seen from OUTPUT's folder (default "models", for a scene in scenes/).
 *
 * Each instance is moved from its grid point by up to FOREST_JITTER in x and z, turned about y by any
 * angle, tilted about x and z by up to FOREST_TILT_DEGREES, scaled per axis (non-uniformly, a little
 * taller or wider), and given one of the scene's materials: every number comes from a hash of the
 * instance's index (splitmix64), so the file is the same on every machine and every run. The camera
 * looks across the whole grid from above one corner, so that the far rows shrink below a pixel and
 * each ray crosses many instances' boxes: the top level of the two-level BVH is what it measures.
 * The numbers are written with four decimals, which every chapter reads back exactly as written.
 *
 * The file is written to OUTPUT.tmp first and renamed, so that an interrupted run leaves no half file.
 * Exit status: 0, 2 for a bad command line, 3 when OUTPUT cannot be written.
 *
 * Build: gcc -std=c11 -D_DEFAULT_SOURCE -Wall -Wextra -Werror -O2 tools/models/forest.c -o build/forest -lm */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FOREST_DEFAULT_INSTANCES 10000L
/* A million instances, the project's hostile-input size for instance lines. */
#define FOREST_MAX_INSTANCES 1000000L
/* Grid step and the largest move off a grid point, in world units; a teapot is about 6 units long
 * and 3 high at scale 1, the bunny 10 wide and 10 high, here scaled to about 3. */
#define FOREST_SPACING 8.0
#define FOREST_JITTER 1.5
#define FOREST_TILT_DEGREES 8.0
/* Scale ranges: [low, low + range) for the whole object, and each axis by up to +- FOREST_STRETCH. */
#define FOREST_TEAPOT_SCALE_LOW 0.6
#define FOREST_TEAPOT_SCALE_RANGE 0.6
#define FOREST_BUNNY_SCALE_LOW 0.2
#define FOREST_BUNNY_SCALE_RANGE 0.15
#define FOREST_STRETCH 0.15
#define FOREST_SEED 0x16f0e57ULL

static const char *const materials[] = {"china", "clay", "moss", "bark", "gold"};
#define MATERIAL_COUNT (sizeof materials / sizeof materials[0])

/* splitmix64 (Steele, Lea and Flood 2014): a well-mixed 64-bit value of x. */
static uint64_t mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/* The uniform number in [0, 1) for field `field` of instance `index`: its top 53 bits. */
static double uniform(long index, int field) {
    uint64_t h = mix(FOREST_SEED ^ mix((uint64_t)index * 16u + (uint64_t)field));
    return (double)(h >> 11) * 0x1p-53;
}

/* In [-1, 1). */
static double signed_uniform(long index, int field) { return 2.0 * uniform(index, field) - 1.0; }

static void usage(void) {
    fprintf(stderr, "usage: forest [--instances N] [--models DIR] OUTPUT.scene (N from 1 to %ld)\n",
            FOREST_MAX_INSTANCES);
    exit(2);
}

/* Writes the whole scene to f; returns whether every write succeeded. */
static int write_forest(FILE *f, long count, const char *models) {
    long side = (long)ceil(sqrt((double)count));
    double extent = (double)side * FOREST_SPACING; /* the grid's width */
    double half = 0.5 * (double)(side - 1) * FOREST_SPACING;
    long teapots = (count + 1) / 2;
    fprintf(f, "# Chapter 16's forest, written by tools/models/forest.c (make bench): %ld instances, %ld of\n"
               "# the 349,872-triangle teapot and %ld of the 3,674-triangle bunny, on a %ld x %ld grid.\n",
            count, teapots, count - teapots, side, side);
    fprintf(f, "camera eye %.4f %.4f %.4f  target 0 %.4f 0  fov 40\n", -0.52 * extent, 0.025 * extent, -0.52 * extent,
            -0.03 * extent);
    fprintf(f, "image 800 600\nbackground 0.55 0.7 0.9\n");
    fprintf(f, "light position %.4f %.4f %.4f  colour 1 1 1\n", 0.3 * extent, extent, -0.6 * extent);
    fprintf(f, "material ground colour 0.45 0.5 0.35 ambient 0.15 diffuse 0.7\n"
               "material china colour 0.35 0.55 0.85 ambient 0.1 diffuse 0.7 phong 0.8 phong_size 120\n"
               "material clay colour 0.85 0.55 0.35 ambient 0.1 diffuse 0.8\n"
               "material moss colour 0.3 0.6 0.25 ambient 0.1 diffuse 0.8\n"
               "material bark colour 0.45 0.3 0.2 ambient 0.1 diffuse 0.8\n"
               "material gold colour 0.9 0.75 0.3 ambient 0.1 diffuse 0.6 phong 0.6 phong_size 60\n");
    fprintf(f, "object teapot %s/teapot-346k.ply\nobject bunny %s/bunny.ply\n", models, models);
    fprintf(f, "plane normal 0 1 0 distance 0  material ground\n");
    for (long k = 0; k < count; k++) {
        int teapot = k % 2 == 0;
        double x = (double)(k % side) * FOREST_SPACING - half + FOREST_JITTER * signed_uniform(k, 0);
        double z = (double)(k / side) * FOREST_SPACING - half + FOREST_JITTER * signed_uniform(k, 1);
        double s = teapot ? FOREST_TEAPOT_SCALE_LOW + FOREST_TEAPOT_SCALE_RANGE * uniform(k, 2)
                          : FOREST_BUNNY_SCALE_LOW + FOREST_BUNNY_SCALE_RANGE * uniform(k, 2);
        const char *material = materials[mix((uint64_t)k ^ FOREST_SEED) % MATERIAL_COUNT];
        fprintf(f, "instance %s material %s scale %.4f %.4f %.4f rotate %.4f %.4f %.4f translate %.4f 0 %.4f\n",
                teapot ? "teapot" : "bunny", material, s * (1.0 + FOREST_STRETCH * signed_uniform(k, 3)),
                s * (1.0 + FOREST_STRETCH * signed_uniform(k, 4)), s * (1.0 + FOREST_STRETCH * signed_uniform(k, 5)),
                FOREST_TILT_DEGREES * signed_uniform(k, 6), 360.0 * uniform(k, 7),
                FOREST_TILT_DEGREES * signed_uniform(k, 8), x, z);
    }
    return !ferror(f);
}

int main(int argc, char **argv) {
    long count = FOREST_DEFAULT_INSTANCES;
    const char *models = "models";
    int a = 1;
    for (; a + 1 < argc && strncmp(argv[a], "--", 2) == 0; a += 2) {
        if (strcmp(argv[a], "--instances") == 0) {
            char *end;
            errno = 0;
            count = strtol(argv[a + 1], &end, 10);
            if (errno != 0 || end == argv[a + 1] || *end != '\0' || count < 1 || count > FOREST_MAX_INSTANCES)
                usage();
        } else if (strcmp(argv[a], "--models") == 0) {
            models = argv[a + 1];
        } else {
            usage();
        }
    }
    if (a + 1 != argc || argv[a][0] == '-') /* an option left over (--help, say) is no file name */
        usage();
    const char *path = argv[a];
    size_t length = strlen(path) + sizeof ".tmp";
    char *temporary = malloc(length);
    if (temporary == NULL) {
        fprintf(stderr, "forest: out of memory\n");
        return 3;
    }
    snprintf(temporary, length, "%s.tmp", path);
    FILE *f = fopen(temporary, "w");
    int ok = f != NULL && write_forest(f, count, models);
    if (f != NULL && fclose(f) != 0)
        ok = 0;
    if (ok && rename(temporary, path) != 0)
        ok = 0;
    if (!ok) {
        fprintf(stderr, "forest: %s: %s\n", path, strerror(errno));
        remove(temporary);
    }
    free(temporary);
    return ok ? 0 : 3;
}
