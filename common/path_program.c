/* path_program.c: what chapter 15's program does once its command line is read (path_program.h). */
#include "path_program.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "accel_fast_bvh.h"
#include "bsdf.h"
#include "emitter.h"
#include "fast_bvh.h"
#include "lens.h"
#include "mesh_surface.h"
#include "path_image.h"
#include "text_escape.h"
#include "texture.h"

/* The view a picture's pixels were drawn for: where the camera is and the picture's size. (Not the
 * tile: a pixel's sum holds for any tile it falls in.) */
struct path_view {
    vec3 eye, target, up;
    double fov;
    int width, height;
};

/* What a held run (cli_render's held loop, in the browser) redoes before each render after the first. */
struct held_paths {
    struct camera *cam;
    struct path_world *paths;
    struct path_picture *picture;
    const struct world *world;
    const struct emitter_list *emitters;
    const struct path_surface *surface;
    struct path_view view;         /* the view the pixels' sums were drawn for */
    struct path_settings settings; /* and the paths' settings */
    bool first;                    /* no frames made yet */
};

static struct path_view view_of(const struct cli_run *run) {
    const struct scene *s = &run->scene;
    return (struct path_view){s->eye, s->target, s->up, s->fov, s->width, s->height};
}

/* Makes the picture's frames (the linear radiance and its error, and when the run may be held each
 * pixel's running sums) for the run's picture size. Returns false with run->status set when memory
 * runs out. */
static bool frames_for(struct cli_run *run, struct held_paths *held) {
    const struct scene *s = &run->scene;
    struct path_picture *picture = held->picture;
    size_t pixels = (size_t)s->width * (size_t)s->height;
    free(picture->linear);
    free(picture->sums);
    picture->linear = calloc(pixels * 6, sizeof *picture->linear);
    picture->error = picture->linear == NULL ? NULL : picture->linear + pixels * 3;
    picture->sums = cli_held(run) ? calloc(pixels, sizeof *picture->sums) : NULL;
    picture->width = s->width;
    if (picture->linear == NULL || (cli_held(run) && picture->sums == NULL)) {
        fprintf(stderr, "out of memory for a %d x %d frame of radiance\n", s->width, s->height);
        run->status = CLI_OUTPUT_FAILED;
        return false;
    }
    held->first = false;
    return true;
}

/* The run's held_refresh: the camera, the frames and the paths' settings for the run's new view and
 * samples. The pixels' sums go on when only the samples grew or the tile moved (the view and the other
 * settings the same), so that passes of more and more samples each add only their new paths; else they
 * start again. */
static bool refresh_held_paths(struct cli_run *run, void *context) {
    struct held_paths *held = context;
    struct scene *s = &run->scene;
    if (!camera_init(held->cam, s->eye, s->target, s->up, s->fov, s->width, s->height, run->err, sizeof run->err))
        return true; /* cli_render_sampled reports the camera */
    struct path_view view = view_of(run);
    struct path_settings settings = s->paths;
    settings.samples = held->settings.samples;
    bool same = memcmp(&view, &held->view, sizeof view) == 0 && memcmp(&settings, &held->settings, sizeof settings) == 0 &&
                s->paths.samples >= held->settings.samples && !held->first;
    if (view.width != held->view.width || view.height != held->view.height || held->first) {
        if (!frames_for(run, held))
            return false;
    } else if (!same && held->picture->sums != NULL) {
        memset(held->picture->sums, 0, (size_t)s->width * (size_t)s->height * sizeof *held->picture->sums);
    }
    held->view = view;
    held->settings = s->paths;
    path_world_init(held->paths, held->world, held->emitters, held->cam, &s->paths);
    held->paths->surface = held->surface;
    return true;
}

int path_program_run(struct cli_run *run, const struct accel_choice *choice, const struct path_surface *surface) {
    int chapter = run->chapter->number;
    struct scene *s = &run->scene;
    s->paint = texture_paint;
    /* Every surface gives back at most the light that reaches it, or the paths' light adds up without bound. */
    for (size_t k = 0; k < s->material_count; k++) {
        char why[sizeof run->err - 64];
        if (!bsdf_conserves_energy(s, &s->materials[k], why, sizeof why)) {
            snprintf(run->err, sizeof run->err, "%s:%d: %s", s->path, s->materials[k].line, why);
            return cli_fail(run);
        }
    }
    if (!texture_load_images(s, run->err, sizeof run->err) || !scene_load_meshes(s, run->err, sizeof run->err) ||
        !mesh_surface_prepare(s, run->err, sizeof run->err))
        return cli_fail(run);
    /* An area light becomes a surface that gives off light, and no surface gives off less than none (a
     * material's negative emission is refused too): a negative channel, which the Whitted chapters take
     * as light taken away (POV-Ray's rule), has no meaning for a path. */
    for (size_t k = 0; k < s->light_count; k++) {
        const struct light *l = &s->lights[k];
        if (area_light_is_area(&l->area) && (l->colour.x < 0.0 || l->colour.y < 0.0 || l->colour.z < 0.0)) {
            snprintf(run->err, sizeof run->err, "%s:%d: light colour must not be negative in chapter %d, got %g %g %g: "
                     "an area light is a surface that gives off light here, and none gives off less than none",
                     s->path, l->line, chapter, l->colour.x, l->colour.y, l->colour.z);
            return cli_fail(run);
        }
    }
    /* The background is light from every direction here, held to the same rule. */
    vec3 sky = s->background;
    if (sky.x < 0.0 || sky.y < 0.0 || sky.z < 0.0) {
        snprintf(run->err, sizeof run->err, "%s:%d: background must not be negative in chapter %d, got %g %g %g: it "
                 "is light that comes from every direction here, and none gives off less than none", s->path,
                 s->background_line, chapter, sky.x, sky.y, sky.z);
        return cli_fail(run);
    }
    /* The area lights made emitting rectangles before the world is built over
     * them, the emitters gathered, and every pixel the mean of its paths. */
    int point_lights = emitter_add_area_lights(s, run->err, sizeof run->err);
    if (point_lights < 0)
        return cli_fail(run);
    if (point_lights > 0 && !run->options.quiet)
        fprintf(stderr, "%s: chapter %d ignores %d point light%s (a point has no area to emit from)\n", s->path, chapter,
                point_lights, point_lights == 1 ? "" : "s");
    /* Each path picks its own point of the pixel, so the antialias line has nothing to say; the lens is
     * chapter 13's, which the paths do not sample. */
    if ((s->antialias.line != 0 || lens_is_open(&s->lens)) && !run->options.quiet)
        fprintf(stderr, "%s: chapter %d ignores %s (each path samples the pixel itself, through a pinhole)\n", s->path, chapter,
                s->antialias.line != 0 && lens_is_open(&s->lens) ? "the antialias line and the camera's lens"
                : s->antialias.line != 0                         ? "the antialias line"
                                                                 : "the camera's lens");
    struct accel_world *w = accel_world_create_at_rung(s, choice, FAST_BVH_RUNG_DEFAULT, run->err, sizeof run->err);
    if (w == NULL)
        return cli_fail(run);
    struct emitter_list emitters;
    if (!emitter_list_build(&emitters, w, run->err, sizeof run->err)) {
        accel_world_destroy(w);
        return cli_fail(run);
    }
    /* A scene in which nothing gives off light would draw a black picture: say why instead. Emitters whose
     * power (emission times area) adds up to nothing, triangles with their corners in a line, give none:
     * no ray can hit them, and the light sampler cannot pick them. */
    bool black_background = s->background.x == 0.0 && s->background.y == 0.0 && s->background.z == 0.0;
    if (black_background && !(emitters.total_power > 0.0)) {
        size_t areas = s->light_count - (size_t)point_lights; /* area lights, their colours not above 0 here */
        char lights[128];
        if (areas > 0)
            snprintf(lights, sizeof lights, "the area light%s give%s off nothing (%s colour not above 0)",
                     areas == 1 ? "" : "s", areas == 1 ? "s" : "", areas == 1 ? "its" : "their");
        else
            snprintf(lights, sizeof lights, "no light has an area");
        if (emitters.count == 0)
            snprintf(run->err, sizeof run->err, "%s: nothing gives off light, so the picture would be black: no "
                     "material has an emission, %s (chapter %d ignores %d point light%s) and the "
                     "background is black", s->path, lights, chapter, point_lights, point_lights == 1 ? "" : "s");
        else
            snprintf(run->err, sizeof run->err, "%s: nothing gives off light, so the picture would be black: the "
                     "%zu emissive surface%s give%s no power (no area, its corners in a line, or an emission times "
                     "area below double's range) and the background is black", s->path, emitters.count,
                     emitters.count == 1 ? "" : "s", emitters.count == 1 ? "s" : "");
        emitter_list_free(&emitters);
        accel_world_destroy(w);
        return cli_fail(run);
    }
    struct camera cam;
    struct path_world paths;
    struct path_picture picture = {&paths, NULL, NULL, s->width, NULL};
    struct held_paths held = {.cam = &cam, .paths = &paths, .picture = &picture, .world = &w->world,
                              .emitters = &emitters, .surface = surface, .first = true};
    if (camera_init(&cam, s->eye, s->target, s->up, s->fov, s->width, s->height, run->err, sizeof run->err))
        frames_for(run, &held);
    /* else cli_render_sampled reports the camera */
    float *linear = picture.linear, *error = picture.error;
    if (run->status == CLI_OK) {
        path_world_init(&paths, &w->world, &emitters, &cam, &s->paths);
        paths.surface = surface; /* NULL in chapter 15; chapter 17's rough surfaces */
        held.settings = s->paths;
        held.view = view_of(run);
        run->held_refresh = refresh_held_paths;
        run->held_context = &held;
        bool report = cli_render_sampled(run, NULL, &picture, &path_sampler);
        const char *hdr_path = run->options.chapter_output; /* --hdr FILE, with -o's rules (cli.h) */
        /* With --tile, only the tile was rendered: its frame is written, and the noise is its own. */
        struct render_window tile = run->options.tile;
        if (tile.width == 0)
            tile = (struct render_window){0, 0, s->width, s->height};
        if (run->status == CLI_OK && run->options.pov == NULL) {
            path_image_keep_window(linear, s->width, tile);
            path_image_keep_window(error, s->width, tile);
        }
        if (run->status == CLI_OK && run->options.pov == NULL && hdr_path != NULL) {
            size_t length = strlen(hdr_path);
            bool pfm = length >= 4 && strcasecmp(hdr_path + length - 4, ".pfm") == 0; /* .PFM too */
            if (!(pfm ? path_image_write_pfm : path_image_write_hdr)(linear, tile.width, tile.height, hdr_path, run->err,
                                                                     sizeof run->err)) {
                fprintf(stderr, "%s\n", run->err);
                run->status = CLI_OUTPUT_FAILED;
            } else if (!run->options.quiet) {
                char shown[4 * PATH_MAX];
                text_escape(strcmp(hdr_path, "-") == 0 ? "standard output" : hdr_path, shown, sizeof shown);
                printf("linear radiance: %s\n", shown);
            }
        }
        if (report && run->status == CLI_OK) {
            bool stratified = s->paths.sampler == PATH_SAMPLER_SOBOL;
            printf("paths: %d a pixel (%s%s, seed %u); %.0f paths and %.0f rays a second\n", s->paths.samples,
                   path_strategy_name(s->paths.strategy), stratified ? ", sampler sobol" : "", (unsigned)s->paths.seed,
                   run->total.primary_rays / run->render_seconds,
                   (run->total.primary_rays + run->total.shadow_rays + run->total.reflected_rays +
                    run->total.refracted_rays) / run->render_seconds);
            /* The spread of a pixel's own paths, over their count, is the error of independent paths; the
             * strata of sobol's paths cancel part of that spread, so for them it overstates the error. */
            printf("noise: a pixel's standard error is %.1f%% of the mean%s\n",
                   100 * path_image_noise(linear, error, tile.width, tile.height),
                   stratified ? " for independent paths; these stratified ones have less" : "");
            accel_report(w, &run->total, run->options.stats);
        }
    }
    free(linear);
    free(picture.sums);
    emitter_list_free(&emitters);
    accel_world_destroy(w);
    return cli_finish(run);
}
