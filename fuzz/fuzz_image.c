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
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *path = write_input(data, size);
    /* The declared size from the reader's own checks, which no decoder runs in (stb_image's own
     * stbi_info would meet the hostile bytes before the reader's checks do). */
    long width, height;
    char header_why[1024];
    if (image_map_check_header(path, data, size, &width, &height, header_why, sizeof header_why)) {
        long pixels = width * height;
        if (pixels > FUZZ_IMAGE_MAX_PIXELS && pixels <= IMAGE_MAP_MAX_PIXELS)
            return 0;
    }
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
