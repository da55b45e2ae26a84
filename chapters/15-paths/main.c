/* Chapter 15, path tracing: the rendering equation solved by Monte Carlo. Each pixel is the mean of the
 * scene's paths per pixel (its paths line, common/path_settings.h): a path leaves the camera through a
 * random point of the pixel and bounces through the scene, a cosine-weighted direction off a Lambertian
 * surface, the mirror direction off a mirror, reflected or refracted by Fresnel's share at glass
 * (common/bsdf.c); at each Lambertian point a shadow ray goes to a point chosen on the emitting surfaces
 * (common/emitter.c), weighed against scattering by multiple importance sampling, and Russian roulette
 * ends the path (common/path_trace.c). The picture is tone-mapped into the PNG and kept linear in an HDR
 * file with --hdr (common/path_image.c). The world is chapter 11's fast BVH, the surfaces may be
 * chapter 14's textures, and the random numbers chapter 12's counter-based hash: the picture is the same
 * for any number of threads. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel_fast_bvh.h"
#include "box.h"
#include "cli.h"
#include "emitter.h"
#include "fast_bvh.h"
#include "lens.h"
#include "mesh_surface.h"
#include "path_image.h"
#include "path_trace.h"
#include "plane.h"
#include "sphere.h"
#include "text_escape.h"
#include "texture.h"
#include "triangle.h"

static struct accel_choice choice = {ACCEL_BVH, true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

int main(int argc, char **argv) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 15,
        .title = "path tracing",
        .default_scene = "scenes/15-paths.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --hdr FILE       also write the linear radiance: a Radiance .hdr file, or a Portable\n"
                        "                   Float Map when FILE ends in .pfm (every float kept whole); - for\n"
                        "                   standard output (the counters then go to standard error)\n"
                        "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule\n",
        .output_option = "--hdr",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    struct scene *s = &run.scene;
    s->paint = texture_paint;
    if (!texture_load_images(s, run.err, sizeof run.err) || !scene_load_meshes(s, run.err, sizeof run.err) ||
        !mesh_surface_prepare(s, run.err, sizeof run.err))
        return cli_fail(&run);
    /* What chapter 15 adds: the area lights made emitting rectangles before the world is built over
     * them, the emitters gathered, and every pixel the mean of its paths. */
    int point_lights = emitter_add_area_lights(s, run.err, sizeof run.err);
    if (point_lights < 0)
        return cli_fail(&run);
    if (point_lights > 0 && !run.options.quiet)
        fprintf(stderr, "%s: chapter 15 ignores %d point light%s (a point has no area to emit from)\n", s->path,
                point_lights, point_lights == 1 ? "" : "s");
    /* Each path picks its own point of the pixel, so the antialias line has nothing to say; the lens is
     * chapter 13's, which the paths do not sample. */
    if ((s->antialias.line != 0 || lens_is_open(&s->lens)) && !run.options.quiet)
        fprintf(stderr, "%s: chapter 15 ignores %s (each path samples the pixel itself, through a pinhole)\n", s->path,
                s->antialias.line != 0 && lens_is_open(&s->lens) ? "the antialias line and the camera's lens"
                : s->antialias.line != 0                         ? "the antialias line"
                                                                 : "the camera's lens");
    struct accel_world *w = accel_world_create_at_rung(s, &choice, FAST_BVH_RUNG_DEFAULT, run.err, sizeof run.err);
    if (w == NULL)
        return cli_fail(&run);
    struct emitter_list emitters;
    if (!emitter_list_build(&emitters, w, run.err, sizeof run.err)) {
        accel_world_destroy(w);
        return cli_fail(&run);
    }
    /* A scene in which nothing gives off light would draw a black picture: say why instead. */
    if (emitters.count == 0 && s->background.x == 0.0 && s->background.y == 0.0 && s->background.z == 0.0) {
        snprintf(run.err, sizeof run.err, "%s: nothing gives off light, so the picture would be black: no material "
                 "has an emission, no light has an area (chapter 15 ignores %d point light%s) and the background "
                 "is black", s->path, point_lights, point_lights == 1 ? "" : "s");
        emitter_list_free(&emitters);
        accel_world_destroy(w);
        return cli_fail(&run);
    }
    struct camera cam;
    float *linear = NULL, *error = NULL;
    if (camera_init(&cam, s->eye, s->target, s->up, s->fov, s->width, s->height, run.err, sizeof run.err)) {
        linear = calloc((size_t)s->width * (size_t)s->height * 6, sizeof *linear);
        error = linear == NULL ? NULL : linear + (size_t)s->width * (size_t)s->height * 3;
        if (linear == NULL) {
            fprintf(stderr, "out of memory for a %d x %d frame of radiance\n", s->width, s->height);
            run.status = CLI_OUTPUT_FAILED;
        }
    } /* else cli_render_sampled reports the camera */
    if (run.status == CLI_OK) {
        struct path_world paths;
        path_world_init(&paths, &w->world, &emitters, &cam, &s->paths);
        struct path_picture picture = {&paths, linear, error, s->width};
        bool report = cli_render_sampled(&run, NULL, &picture, &path_sampler);
        const char *hdr_path = run.options.chapter_output; /* --hdr FILE, with -o's rules (cli.h) */
        /* With --tile, only the tile was rendered: its frame is written, and the noise is its own. */
        struct render_window tile = run.options.tile;
        if (tile.width == 0)
            tile = (struct render_window){0, 0, s->width, s->height};
        if (run.status == CLI_OK && run.options.pov == NULL) {
            path_image_keep_window(linear, s->width, tile);
            path_image_keep_window(error, s->width, tile);
        }
        if (run.status == CLI_OK && run.options.pov == NULL && hdr_path != NULL) {
            size_t length = strlen(hdr_path);
            bool pfm = length >= 4 && strcmp(hdr_path + length - 4, ".pfm") == 0;
            if (!(pfm ? path_image_write_pfm : path_image_write_hdr)(linear, tile.width, tile.height, hdr_path, run.err,
                                                                     sizeof run.err)) {
                fprintf(stderr, "%s\n", run.err);
                run.status = CLI_OUTPUT_FAILED;
            } else if (!run.options.quiet) {
                char shown[4 * PATH_MAX];
                text_escape(strcmp(hdr_path, "-") == 0 ? "standard output" : hdr_path, shown, sizeof shown);
                printf("linear radiance: %s\n", shown);
            }
        }
        if (report && run.status == CLI_OK) {
            printf("paths: %d a pixel (%s, seed %u); noise: a pixel's standard error is %.1f%% of the mean; "
                   "%.0f paths and %.0f rays a second\n", s->paths.samples, path_strategy_name(s->paths.strategy),
                   (unsigned)s->paths.seed, 100 * path_image_noise(linear, error, tile.width, tile.height),
                   run.total.primary_rays / run.render_seconds,
                   (run.total.primary_rays + run.total.shadow_rays + run.total.reflected_rays +
                    run.total.refracted_rays) / run.render_seconds);
            accel_report(w, &run.total, run.options.stats);
        }
    }
    free(linear);
    emitter_list_free(&emitters);
    accel_world_destroy(w);
    return cli_finish(&run);
}
