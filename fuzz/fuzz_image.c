/* fuzz_image.c: libFuzzer harness for the image-map reader, image_map_read on any bytes (make fuzz).
 *
 * Each input is written to a file of our own under /tmp (named .jpg when it starts as a JPEG does,
 * .png otherwise) and read by image_map_read, as chapter 14 reads a pigment's file. The reader must
 * either refuse it with a message starting with the file's path, or give a picture that keeps the
 * promises the lookup relies on: at least one pixel, at most IMAGE_MAP_MAX_PIXELS, every texel a number
 * in [0, 1], and `opaque` true exactly when every alpha is 1.
 *
 * Inputs whose header declares more than FUZZ_IMAGE_MAX_PIXELS pixels, but no more than the reader's
 * own limit, are skipped: the reader would rightly decode them, which costs seconds and gigabytes
 * (a few bytes of JPEG can declare 64 million pixels), and libFuzzer would report that as a timeout or
 * running out of memory. Those declaring more than the reader's limit are run: they must be refused.
 *
 * So are the inputs that trigger a known defect not yet fixed (known_defect below), so that the
 * fuzzer looks past it; delete the test when the reader refuses such files itself. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "fuzz_support.h"
#include "image_map.h"

#define FUZZ_IMAGE_MAX_PIXELS (1L << 20)

static char folder[64];

static void remove_folder(void) {
    char path[96];
    snprintf(path, sizeof path, "%s/fuzz.png", folder);
    remove(path);
    snprintf(path, sizeof path, "%s/fuzz.jpg", folder);
    remove(path);
    rmdir(folder);
}

/* Writes data[0..size) to the harness's file and returns its path (static storage). */
static const char *write_input(const uint8_t *data, size_t size) {
    static char path[96];
    if (folder[0] == '\0') {
        snprintf(folder, sizeof folder, "/tmp/whitted-fuzz-image-XXXXXX");
        if (mkdtemp(folder) == NULL)
            fuzz_abort("cannot make a folder under /tmp");
        atexit(remove_folder);
    }
    bool jpeg = size >= 2 && data[0] == 0xff && data[1] == 0xd8;
    snprintf(path, sizeof path, "%s/fuzz.%s", folder, jpeg ? "jpg" : "png");
    FILE *f = fopen(path, "wb");
    if (f == NULL || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        fuzz_abort("cannot write %s", path);
    return path;
}

#define JPEG_HUFFMAN_MAX_SYMBOLS 256 /* a JPEG Huffman table codes at most 256 symbols */

/* The known defect: stb_image 2.27 (Debian's) adds up the 16 code counts of a JPEG Huffman table (a
 * DHT segment) without checking that they come to at most 256, and writes the table's code sizes and
 * symbols past its arrays (stbi__build_huffman, stb_image.h line 1990, and the DHT case of
 * stbi__process_marker): memory corruption from a hostile file. True when some DHT segment of the input
 * (any FF C4 marker, its length, then tables of a class byte, 16 counts and the symbols) holds a table
 * of more than 256 symbols. */
static bool known_defect(const uint8_t *data, size_t size) {
    if (size < 2 || data[0] != 0xff || data[1] != 0xd8)
        return false;
    for (size_t at = 2; at + 4 <= size; at++) {
        if (data[at] != 0xff || data[at + 1] != 0xc4)
            continue;
        size_t end = at + 2 + ((size_t)data[at + 2] << 8 | data[at + 3]), table = at + 4;
        while (table < end && table < size) { /* stb reads tables while the length lasts, zeros past the end */
            size_t symbols = 0;
            for (size_t k = 1; k <= 16 && table + k < size; k++)
                symbols += data[table + k];
            if (symbols > JPEG_HUFFMAN_MAX_SYMBOLS)
                return true;
            table += 17 + symbols;
        }
    }
    return false;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (known_defect(data, size))
        return 0;
    int width, height, channels;
    if (size <= INT32_MAX && stbi_info_from_memory(data, (int)size, &width, &height, &channels)) {
        long pixels = (long)width * height;
        if (pixels > FUZZ_IMAGE_MAX_PIXELS && pixels <= IMAGE_MAP_MAX_PIXELS)
            return 0;
    }
    const char *path = write_input(data, size);
    struct pigment_image image;
    char why[1024] = "";
    if (!image_map_read(path, &image, why, sizeof why)) {
        if (!fuzz_message_names(why, path))
            fuzz_abort("refused with a message that does not start with '%s:': '%s'", path, why);
        if (image.texels != NULL)
            fuzz_abort("refused ('%s') but left texels behind", why);
        return 0;
    }
    if (image.width < 1 || image.height < 1 || (long)image.width * image.height > IMAGE_MAP_MAX_PIXELS)
        fuzz_abort("accepted a picture of %d x %d pixels", image.width, image.height);
    bool opaque = true;
    size_t count = (size_t)image.width * (size_t)image.height * 4;
    for (size_t k = 0; k < count; k++) {
        float v = image.texels[k];
        if (!(v >= 0.0f && v <= 1.0f))
            fuzz_abort("texel %zu of a %d x %d picture is %g", k, image.width, image.height, v);
        if (k % 4 == 3 && v < 1.0f)
            opaque = false;
    }
    if (opaque != image.opaque)
        fuzz_abort("the picture says it is %sopaque, its alphas say otherwise", image.opaque ? "" : "not ");
    free(image.texels);
    return 0;
}
