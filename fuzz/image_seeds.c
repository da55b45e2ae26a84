/* image_seeds.c: writes the tiny images (tiny_images.h) into a folder: the image harness's seed corpus,
 * made by make fuzz-build into build/libfuzzer/seeds/image/ (docs/fuzzing.md).
 *
 *   image-seeds FOLDER */
#include <stdio.h>

#include "tiny_images.h"

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: image-seeds FOLDER\n");
        return 2;
    }
    char err[4200];
    if (!tiny_images_write(argv[1], err, sizeof err)) {
        fprintf(stderr, "image-seeds: %s\n", err);
        return 3;
    }
    return 0;
}
