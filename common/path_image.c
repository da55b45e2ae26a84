/* path_image.c: the path tracer's pixels, its tone map and its HDR file (chapter 15). */
#include "path_image.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "heatmap.h"
#include "outfile.h"

#include <stb_image_write.h>

/* The sRGB curve's two pieces meet here (IEC 61966-2-1). */
#define SRGB_LINEAR_BELOW 0.0031308

double path_image_display(double linear) {
    if (!(linear > 0.0))
        return 0.0;
    double v = fmin(linear, 1.0);
    return v < SRGB_LINEAR_BELOW ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

static void render_paths(const struct render_job *job, struct image *img, int left, int top, int right, int bottom) {
    const struct path_picture *picture = job->world;
    for (int j = top; j < bottom; j++)
        for (int i = left; i < right; i++) {
            uint64_t cost_before = render_thread_cost();
            vec3 variance;
            size_t pixel = (size_t)j * (size_t)picture->width + (size_t)i, at = 3 * pixel;
            vec3 c = picture->sums != NULL ? path_pixel_resume(picture->paths, i, j, &picture->sums[pixel], &variance)
                                           : path_pixel(picture->paths, i, j, &variance);
            for (int k = 0; k < 3; k++)
                picture->linear[at + k] = (float)vec3_axis(c, k);
            stats_thread.non_finite_pixels += !vec3_is_finite(c);
            for (int k = 0; picture->error != NULL && k < 3; k++)
                picture->error[at + k] = (float)sqrt(vec3_axis(variance, k) / picture->paths->settings.samples);
            image_set(img, i, j, vec3_make(path_image_display(c.x), path_image_display(c.y), path_image_display(c.z)));
            if (job->heatmap != NULL) {
                uint64_t cost = render_thread_cost() - cost_before;
                image_set(job->heatmap, i, j, heatmap_colour(cost > UINT32_MAX ? UINT32_MAX : (uint32_t)cost));
            }
        }
    stats_thread.pixels += (uint64_t)(right - left) * (uint64_t)(bottom - top);
    if ((uint64_t)picture->paths->settings.samples > stats_thread.camera_rays_max)
        stats_thread.camera_rays_max = (uint64_t)picture->paths->settings.samples;
}

double path_image_noise(const float *linear, const float *error, int width, int height) {
    double values = 0, errors = 0;
    for (size_t k = 0; k < 3 * (size_t)width * (size_t)height; k++) {
        values += linear[k];
        errors += error[k];
    }
    return values > 0 ? errors / values : 0.0;
}

void path_image_keep_window(float *linear, int width, struct render_window window) {
    for (int y = 0; y < window.height; y++) /* row y lands at or before where it was: memmove keeps it whole */
        memmove(&linear[3 * (size_t)y * (size_t)window.width],
                &linear[3 * ((size_t)(window.top + y) * (size_t)width + (size_t)window.left)],
                3 * (size_t)window.width * sizeof *linear);
}

const struct render_sampler path_sampler = {render_paths, &heatmap_cost_scale, NULL};

/* stb_image_write hands its output to this callback piece by piece; we append it to the file. */
static void write_to_file(void *context, void *data, int size) { outfile_write(context, data, (size_t)size); }

bool path_image_write_hdr(const float *linear, int width, int height, const char *path, char *err, size_t err_size) {
    struct outfile out;
    if (!outfile_open(&out, path, err, err_size))
        return false;
    if (stbi_write_hdr_to_func(write_to_file, &out, width, height, 3, linear) == 0) {
        outfile_abandon(&out);
        snprintf(err, err_size, "%s: cannot write: HDR encoding failed", path);
        return false;
    }
    return outfile_commit(&out, err, err_size);
}

bool path_image_write_pfm(const float *linear, int width, int height, const char *path, char *err, size_t err_size) {
    struct outfile out;
    if (!outfile_open(&out, path, err, err_size))
        return false;
    char header[64];
    int length = snprintf(header, sizeof header, "PF\n%d %d\n-1.0\n", width, height);
    bool ok = outfile_write(&out, header, (size_t)length);
    for (int j = height - 1; ok && j >= 0; j--) {
        const float *row = &linear[3 * (size_t)j * (size_t)width];
        for (size_t k = 0; ok && k < 3 * (size_t)width; k++) {
            uint32_t bits;
            memcpy(&bits, &row[k], sizeof bits);
            uint8_t bytes[4] = {(uint8_t)bits, (uint8_t)(bits >> 8), (uint8_t)(bits >> 16), (uint8_t)(bits >> 24)};
            ok = outfile_write(&out, bytes, sizeof bytes);
        }
    }
    return outfile_commit(&out, err, err_size);
}
