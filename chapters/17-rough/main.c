/* Chapter 17, rough surfaces: chapter 15's path tracer with glossy metal and frosted glass. A material
 * with a roughness above 0 is a field of tiny mirrors, the GGX (Trowbridge-Reitz) microfacet model with
 * Smith's masking (common/microfacet.c): a rough mirror of a colour or of a real metal's complex index,
 * or rough glass that reflects and refracts through its facets (Walter et al. 2007). It plugs into
 * chapter 15's estimator as a path_surface (common/rough_surface.c): next-event estimation asks it for
 * f cos and its density, scattering draws the visible normals (Heitz 2018), and multiple importance
 * sampling weighs the two with the density of the lobe a path would have drawn. Everything else, the
 * emitters, the sample streams, the paths line and its strategy, is chapter 15's; a scene without
 * roughness draws chapter 15's picture exactly. */
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
#include "rough_surface.h"
#include "plane.h"
#include "sphere.h"
#include "text_escape.h"
#include "texture.h"
#include "triangle.h"

static struct accel_choice choice = {ACCEL_BVH, true};
/* --form cycles-3.4: the lobes as Cycles 3.4 writes them, for the comparison with it only (rough_surface.h). */
static const struct path_surface *rough_hook = &rough_surface_hook;

static int parse_option(const char *option, const char *value) {
    if (strcmp(option, "--form") == 0) {
        if (value != NULL && (strcmp(value, "chapter") == 0 || strcmp(value, "cycles-3.4") == 0)) {
            rough_hook = strcmp(value, "cycles-3.4") == 0 ? &rough_surface_hook_cycles_3_4 : &rough_surface_hook;
            return 2;
        }
        char got[256];
        text_escape(value != NULL ? value : "", got, sizeof got); /* the value comes from the command line */
        fprintf(stderr, "--form needs 'chapter' (the default) or 'cycles-3.4' (to compare with it), got '%s'\n", got);
        return -1;
    }
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

int main(int argc, char **argv) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 17,
        .title = "rough surfaces",
        .default_scene = "scenes/17-rough.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --hdr FILE       also write the linear radiance: a Radiance .hdr file, or a Portable\n"
                        "                   Float Map when FILE ends in .pfm (every float kept whole); - for\n"
                        "                   standard output (the counters then go to standard error)\n"
                        "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule\n"
                        "  --form FORM      chapter (default): the chapter's lobes; cycles-3.4: masking by\n"
                        "                   G1(wo) G1(wi) and glass's Fresnel at the normal, as Blender 3.4's\n"
                        "                   Cycles has them, for comparing with it only\n",
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
    /* As chapter 15: the area lights made emitting rectangles before the world is built over
     * them, the emitters gathered, and every pixel the mean of its paths. */
    int point_lights = emitter_add_area_lights(s, run.err, sizeof run.err);
    if (point_lights < 0)
        return cli_fail(&run);
    if (point_lights > 0 && !run.options.quiet)
        fprintf(stderr, "%s: chapter 17 ignores %d point light%s (a point has no area to emit from)\n", s->path,
                point_lights, point_lights == 1 ? "" : "s");
    /* Each path picks its own point of the pixel, so the antialias line has nothing to say; the lens is
     * chapter 13's, which the paths do not sample. */
    if ((s->antialias.line != 0 || lens_is_open(&s->lens)) && !run.options.quiet)
        fprintf(stderr, "%s: chapter 17 ignores %s (each path samples the pixel itself, through a pinhole)\n", s->path,
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
                 "has an emission, no light has an area (chapter 17 ignores %d point light%s) and the background "
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
        paths.surface = rough_hook; /* what chapter 17 adds: the rough surfaces */
        struct path_picture picture = {&paths, linear, error, s->width};
        bool report = cli_render_sampled(&run, NULL, &picture, &path_sampler);
        const char *hdr_path = run.options.chapter_output; /* --hdr FILE, with -o's rules (cli.h) */
        if (run.status == CLI_OK && run.options.pov == NULL && hdr_path != NULL) {
            size_t length = strlen(hdr_path);
            bool pfm = length >= 4 && strcmp(hdr_path + length - 4, ".pfm") == 0;
            if (!(pfm ? path_image_write_pfm : path_image_write_hdr)(linear, s->width, s->height, hdr_path, run.err,
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
                   (unsigned)s->paths.seed, 100 * path_image_noise(linear, error, s->width, s->height),
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
