/* Chapter 16, instances: many objects from a few meshes, some of them moving, on a two-level BVH, with
 * animation and motion blur.
 *
 * An object line defines a mesh once; each instance line places it with its own transform and material
 * (common/instances.h): one chapter-11 BVH per object, a BVH over the instances' boxes above them, and
 * each ray carried into an instance's object space and its hit carried back. Key lines move an instance
 * over the clock; --frames N renders N frames from clock 0 to 1, refitting or rebuilding the top level
 * between them, and the camera's shutter blurs what moves during a frame (common/shutter.h). Everything
 * else is chapter 13's: the antialias line, area lights and lens, chapter 11's fast BVH for the scene's
 * own triangles, the same threads. */
#include <errno.h>
#include <limits.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "accel_fast_bvh.h"
#include "box.h"
#include "cli.h"
#include "fast_bvh.h"
#include "instances.h"
#include "outfile.h"
#include "plane.h"
#include "ray_budget.h"
#include "shutter.h"
#include "soft_shadow.h"
#include "sphere.h"
#include "triangle.h"
#include "whitted.h"

#define FRAMES_MAX 100000     /* --frames: the most frames one run renders */
#define VIDEO_FRAME_RATE "24" /* frames a second of --video's film */

extern char **environ;

static struct {
    long frames;   /* --frames N: 0 without it (one picture at clock 0) */
    long frame;    /* --frame K: only frame K of the N; 0 for all */
    bool video;    /* --video */
    enum instances_update update;
    int update_options; /* how many of --refit and --rebuild were given */
} animation = {0, 0, false, INSTANCES_AUTO, 0};

/* Reads a whole number from lo to hi for `option`, or says why not. */
static bool read_count(const char *option, const char *value, long lo, long hi, long *out) {
    char *end = NULL;
    errno = 0;
    long n = value != NULL ? strtol(value, &end, 10) : 0;
    if (value == NULL || end == value || *end != '\0' || errno == ERANGE || n < lo || n > hi) {
        fprintf(stderr, "%s needs a whole number from %ld to %ld, got '%s'\n", option, lo, hi, value != NULL ? value : "");
        return false;
    }
    *out = n;
    return true;
}

static int parse_option(const char *option, const char *value) {
    if (strcmp(option, "--frames") == 0)
        return read_count(option, value, 1, FRAMES_MAX, &animation.frames) ? 2 : -1;
    if (strcmp(option, "--frame") == 0)
        return read_count(option, value, 1, FRAMES_MAX, &animation.frame) ? 2 : -1;
    if (strcmp(option, "--video") == 0)
        return animation.video = true, 1;
    if (strcmp(option, "--refit") == 0)
        return animation.update = INSTANCES_REFIT, animation.update_options++, 1;
    if (strcmp(option, "--rebuild") == 0)
        return animation.update = INSTANCES_REBUILD, animation.update_options++, 1;
    return 0;
}

/* What chapter 16 traces: chapter 13's tracer, soft shadows and all. */
static vec3 trace_soft(const void *world, const ray *r) {
    return whitted_trace_shadowed(world, r, soft_shadow_filtered);
}

/* True when name ends in .png (in any case). */
static bool names_png(const char *name) {
    size_t length = strlen(name);
    return length >= 4 && strcasecmp(name + length - 4, ".png") == 0;
}

/* True when `name` exists and is neither a regular file nor a folder (links followed): a device or a FIFO. */
static bool not_a_file(const char *name) {
    struct stat info;
    return strcmp(name, "-") != 0 && stat(name, &info) == 0 && !S_ISREG(info.st_mode) && !S_ISDIR(info.st_mode);
}

/* Checks the animation options against each other; prints why not and returns false. */
static bool animation_options_valid(const struct cli_options *o) {
    const char *problem = NULL;
    if (o->pov != NULL && (animation.frames > 0 || animation.video || animation.update_options > 0))
        problem = "--frames, --frame, --video, --refit and --rebuild are for rendering frames, and --pov writes the "
                  "scene's POV-Ray twin instead (its clock runs over POV-Ray's own frames); give one or the other";
    else if (animation.frame > 0 && animation.frames == 0)
        problem = "--frame K needs --frames N";
    else if (animation.frame > animation.frames)
        problem = "--frame K must be at most --frames N";
    else if (animation.video && (animation.frames < 2 || animation.frame > 0))
        problem = "--video needs --frames N (at least 2) and all of them (no --frame)";
    else if (animation.frames > 0 && strcmp(o->output, "-") == 0)
        problem = "--frames writes one file a frame: -o - (standard output) cannot take them";
    else if (animation.frames > 0 && (not_a_file(o->output) || (o->heatmap != NULL && not_a_file(o->heatmap))))
        problem = "--frames writes one file a frame, named after -o (and --heatmap): a device or a FIFO (such as "
                  "/dev/null) is not a file whose name can be numbered, and its frames would be new files beside it";
    else if (animation.frames > 0 && o->heatmap != NULL && strcmp(o->heatmap, "-") == 0)
        problem = "--frames writes one heat-map a frame: --heatmap - (standard output) cannot take them";
    else if (animation.video && !names_png(o->output))
        problem = "--video makes its film from the frames' PNG files: -o must name a .png file";
    else if (animation.update_options > 1)
        problem = "--refit and --rebuild say opposite things: give one of them (or neither, for the default rule)";
    else if (animation.update_options > 0 && animation.frames < 2)
        problem = "--refit and --rebuild choose what happens between frames: they need --frames N (at least 2)";
    if (problem != NULL)
        fprintf(stderr, "%s\n", problem);
    return problem == NULL;
}

/* Writes into name[size] the file of frame k (1-based): `output` with "-kkkk" before its ".png" (or at
 * its end). Returns false when it does not fit. */
static bool frame_file(const char *output, long k, char *name, size_t size) {
    size_t stem = strlen(output) - (names_png(output) ? 4 : 0);
    int written = snprintf(name, size, "%.*s-%04ld%s", (int)stem, output, k, output + stem);
    return written > 0 && (size_t)written < size;
}

/* Checks, before anything is rendered, the files the frames first..last will be written to (the
 * picture's, and the heat-map's with --heatmap): each name fits, none is a file the run reads
 * (cli_output_is_an_input's rule; the inputs are looked at once, cli_inputs_open, and each frame's
 * name once, so that thousands of frames against thousands of object files take a moment), a frame's
 * picture and heat-map are two files, and each can be created; with --video, the film too. Prints why
 * not and returns the exit status, or CLI_OK. */
static int frame_files_valid(const struct cli_run *run, const struct cli_inputs *inputs, long first, long last) {
    const char *const options[] = {"-o", "--heatmap"};
    const char *const outputs[] = {run->options.output, run->options.heatmap};
    for (long k = first; k <= last; k++) {
        char names[2][PATH_MAX];
        for (int o = 0; o < 2 && outputs[o] != NULL; o++) {
            char option[64], err[PATH_MAX + 128];
            if (!frame_file(outputs[o], k, names[o], sizeof names[o])) {
                fprintf(stderr, "%s: the name of frame %ld is too long\n", outputs[o], k);
                return CLI_USAGE;
            }
            snprintf(option, sizeof option, "%s (its frame %ld)", options[o], k);
            if (cli_inputs_written(inputs, option, names[o]))
                return CLI_USAGE;
            /* The first and the last (the longest name) are tried in full; every other one only when it
             * exists already (a folder of that name, a link that loops), so that thousands of frames cost
             * one look each. */
            struct stat info;
            bool tried = k == first || k == last || lstat(names[o], &info) == 0;
            if (tried && !outfile_can_create(names[o], err, sizeof err)) {
                fprintf(stderr, "%s\n", err);
                return CLI_OUTPUT_FAILED;
            }
        }
        if (outputs[1] != NULL && outfile_same_file(names[0], names[1])) {
            fprintf(stderr, "-o and --heatmap name the same file for frame %ld ('%s' and '%s'); give two\n", k,
                    names[0], names[1]);
            return CLI_USAGE;
        }
    }
    char film[PATH_MAX], err[PATH_MAX + 128];
    size_t stem = strlen(run->options.output) - 4; /* with --video, -o ends in .png (animation_options_valid) */
    if (!animation.video)
        return CLI_OK;
    if (snprintf(film, sizeof film, "%.*s.mp4", (int)stem, run->options.output) >= (int)sizeof film) {
        fprintf(stderr, "%s: the film's name is too long\n", run->options.output);
        return CLI_USAGE;
    }
    if (cli_inputs_written(inputs, "--video (its film)", film))
        return CLI_USAGE;
    if (!outfile_can_create(film, err, sizeof err)) { /* found now, not after every frame is drawn */
        fprintf(stderr, "--video: %s\n", err);
        return CLI_OUTPUT_FAILED;
    }
    return CLI_OK;
}

/* The pictures the run renders, for the ray budget (cli.h): --frames N of them, or one (--frame K, or
 * no --frames). */
static long pictures(void) { return animation.frames > 0 && animation.frame == 0 ? animation.frames : 1; }

/* Returns true when `program` is an executable file in a folder of the PATH, so that --video can say it
 * is missing before the frames are rendered rather than after. */
static bool on_path(const char *program) {
#ifdef __EMSCRIPTEN__ /* the browser's build runs no other program */
    (void)program;
    return false;
#else
    const char *path = getenv("PATH");
    while (path != NULL && *path != '\0') {
        const char *end = strchr(path, ':');
        size_t length = end != NULL ? (size_t)(end - path) : strlen(path);
        char file[PATH_MAX];
        int written = snprintf(file, sizeof file, "%.*s/%s", (int)length, length > 0 ? path : ".", program);
        if (written > 0 && (size_t)written < sizeof file && access(file, X_OK) == 0)
            return true;
        path = end != NULL ? end + 1 : NULL;
    }
    return false;
#endif
}

/* Runs ffmpeg over this run's `frames` frames (the output's name with -%04d) into the output's name with
 * .mp4 for .png. Both names go to ffmpeg after "file:", so that it reads them as files whatever they hold:
 * a name starting with '-' is not an option, and "x:y.png" is not the protocol x. ffmpeg is told how many
 * frames to take (it reads a numbered pattern until a number is missing, and took in the frames a longer
 * run had left after these), and writes the film into outfile's temporary file, renamed over the film
 * only when ffmpeg succeeded: a failed film is never left half-written. Says the film's name on standard
 * output unless quiet. Returns false with the reason in err. */
static bool make_video(const char *output, long frames, bool quiet, char *err, size_t err_size) {
    char pattern[2 * PATH_MAX], film[PATH_MAX], film_file[PATH_MAX + 8], frame_count[32];
    size_t stem = strlen(output) - 4; /* the output ends in .png (animation_options_valid) */
    /* ffmpeg reads the frames' names as a pattern, in which a % of the output's own name is written %% */
    size_t used = (size_t)snprintf(pattern, sizeof pattern, "file:");
    for (size_t k = 0; k < stem && used + 2 < sizeof pattern; k++) {
        if (output[k] == '%')
            pattern[used++] = '%';
        pattern[used++] = output[k];
    }
    if (used + 2 >= sizeof pattern ||
        snprintf(pattern + used, sizeof pattern - used, "-%%04d%s", output + stem) >= (int)(sizeof pattern - used) ||
        snprintf(film, sizeof film, "%.*s.mp4", (int)stem, output) >= (int)sizeof film)
        return (snprintf(err, err_size, "%s: the film's name is too long", output), false);
#ifdef __EMSCRIPTEN__ /* the browser's build runs no other program */
    (void)frames, (void)quiet, (void)film_file, (void)frame_count;
    return (snprintf(err, err_size, "--video: the browser cannot run ffmpeg"), false);
#else
    struct outfile f;
    char why[PATH_MAX + 128];
    if (!outfile_open(&f, film, why, sizeof why))
        return (snprintf(err, err_size, "--video: %s", why), false);
    /* ffmpeg writes the file outfile made (its temporary one, or a FIFO or device written directly) */
    const char *written = f.temp_path != NULL ? f.temp_path : f.target;
    if (snprintf(film_file, sizeof film_file, "file:%s", written) >= (int)sizeof film_file) {
        outfile_abandon(&f);
        return (snprintf(err, err_size, "%s: the film's name is too long", output), false);
    }
    snprintf(frame_count, sizeof frame_count, "%ld", frames);
    /* -f mp4: the temporary file's name does not end in .mp4, from which ffmpeg would take the format */
    char *args[] = {"ffmpeg", "-y", "-loglevel", "error", "-framerate", VIDEO_FRAME_RATE, "-i", pattern,
                    "-frames:v", frame_count, "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                    "-f", "mp4", film_file, NULL};
    pid_t child;
    int status = 0;
    if (posix_spawnp(&child, "ffmpeg", NULL, NULL, args, environ) != 0) {
        outfile_abandon(&f);
        return (snprintf(err, err_size, "--video: cannot run ffmpeg (install it with tools/build/install-deps.sh video)"),
                false);
    }
    if (waitpid(child, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        outfile_abandon(&f);
        return (snprintf(err, err_size, "--video: ffmpeg failed making %s", film), false);
    }
    if (!outfile_commit(&f, why, sizeof why)) /* outfile's handle holds nothing: this closes and renames */
        return (snprintf(err, err_size, "--video: %s", why), false);
    if (!quiet)
        printf("chapter 16 (instances): wrote %s\n", film);
    return true;
#endif
}

/* The scene's rays (ray_budget.h, every frame's) times the instances each is expected to be carried into:
 * more than INSTANCES_TEST_LIMIT is refused without --no-limit, more than INSTANCES_TEST_LARGE noted
 * (instances.h). The ray budget, worked out before the instances are placed, counts them as a tree's
 * logarithm; instances on top of one another are each met by every ray. */
static bool instances_within_budget(struct cli_run *run, const struct instances *in) {
    struct ray_budget b;
    double rays = ray_budget_estimate(&run->scene, run->chapter->number, &b) * (double)pictures();
    int line = 0;
    bool outside = false;
    double per_ray = instances_expected_tests(in, &line, &outside), tests = rays * per_ray;
    bool over = tests > INSTANCES_TEST_LIMIT && !run->options.no_limit;
    if (tests <= INSTANCES_TEST_LARGE || (run->options.quiet && !over))
        return true;
    fprintf(stderr, "%s:%d: %sa ray is carried into about %.0f instances, ", run->scene.path, line, over ? "" : "note: ",
            per_ray);
    if (outside)
        fprintf(stderr, "%zu of them met by every ray (their objects have sliver faces, which no box can be trusted "
                        "to hold): ", in->outside_count);
    else
        fprintf(stderr, "their boxes lying over each other here: ");
    fprintf(stderr, "about %.2g for the scene's %.2g rays, ", tests, rays);
    if (over)
        fprintf(stderr, "over the limit of %.0e; pass --no-limit to render it anyway\n", INSTANCES_TEST_LIMIT);
    else
        fprintf(stderr, "which may take a while\n");
    if (over)
        run->status = CLI_BAD_INPUT;
    return !over;
}

/* Renders the frames asked for: frame k of N at clock (k - 1) / (N - 1), its top level moved there. */
static int render_frames(struct cli_run *run, struct accel_world *w, struct instances *in) {
    const char *output = run->options.output, *heatmap = run->options.heatmap;
    long first = animation.frame > 0 ? animation.frame : 1, last = animation.frame > 0 ? animation.frame : animation.frames;
    static char name[PATH_MAX], heat_name[PATH_MAX];
    for (long k = first; k <= last && run->status == CLI_OK; k++) {
        double clock = animation.frames == 1 ? 0.0 : (double)(k - 1) / (double)(animation.frames - 1);
        bool fits = frame_file(output, k, name, sizeof name);
        if (!fits || (heatmap != NULL && !frame_file(heatmap, k, heat_name, sizeof heat_name))) {
            fprintf(stderr, "%s: the name of frame %ld is too long\n", fits ? heatmap : output, k);
            return CLI_USAGE;
        }
        if (in != NULL && !instances_set_interval(in, clock, clock + run->scene.shutter, animation.update, run->err,
                                                  sizeof run->err)) {
            fprintf(stderr, "%s\n", run->err);
            return CLI_OUTPUT_FAILED;
        }
        w->world.time = clock;
        run->options.output = name;
        if (heatmap != NULL)
            run->options.heatmap = heat_name; /* each frame's heat-map beside it, numbered as it is */
        run->total = (struct stats){0};
        if (cli_render_sampled(run, trace_soft, &w->world, &shutter_sampler) && run->options.stats && in != NULL)
            instances_report(in, stdout, true);
    }
    if (run->status == CLI_OK && animation.video && !make_video(output, animation.frames, run->options.quiet, run->err, sizeof run->err)) {
        fprintf(stderr, "%s\n", run->err);
        return CLI_OUTPUT_FAILED;
    }
    return run->status;
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 16 draws: every kind so far (chapter 5's), and the instances beside them. */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 16,
        .title = "instances",
        .default_scene = "scenes/16-instances.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .pictures = pictures,
        .options_help = "  --frames N       render N frames (1 to 100000) at clock 0 .. 1, to the output's\n"
                        "                   name with -0001, -0002, ... before .png\n"
                        "  --frame K        only frame K (1 .. N) of the N\n"
                        "  --video          with --frames: also make a film of them with ffmpeg (.mp4)\n"
                        "  --refit          between frames, refit the top level's boxes (keep its tree)\n"
                        "  --rebuild        between frames, build the top level anew\n"
                        "                   (default: refit until the tree's SAH cost has grown by a\n"
                        "                   quarter over a fresh build's, then rebuild)\n"
                        "  (the camera's shutter key blurs what moves, e.g. --set camera.shutter=0)\n",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!animation_options_valid(&run.options)) {
        run.status = CLI_USAGE;
        return cli_finish(&run);
    }
    if (animation.frames > 0 && run.options.pov == NULL) {
        long first = animation.frame > 0 ? animation.frame : 1;
        struct cli_inputs inputs;
        run.status = !cli_inputs_open(&inputs, &run) ? CLI_OUTPUT_FAILED
                     : frame_files_valid(&run, &inputs, first, animation.frame > 0 ? animation.frame : animation.frames);
        cli_inputs_free(&inputs);
        if (run.status != CLI_OK)
            return cli_finish(&run);
    }
    if (animation.video && !on_path("ffmpeg")) {
        fprintf(stderr, "--video: cannot find ffmpeg, which makes the film (install it with "
                        "tools/build/install-deps.sh video)\n");
        run.status = CLI_OUTPUT_FAILED;
        return cli_finish(&run);
    }
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err) ||
        !instances_objects_open(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    static const struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};
    struct accel_world *w =
        accel_world_create_at_rung(&run.scene, &choice, FAST_BVH_RUNG_DEFAULT, run.err, sizeof run.err);
    if (w == NULL)
        return cli_fail(&run);
    struct instances *in = NULL;
    if (run.scene.instance_count > 0) {
        in = instances_create(&run.scene, world_mesh_object_number(&run.scene, run.scene.mesh_count), 0.0,
                              run.scene.shutter, run.err, sizeof run.err);
        if (in == NULL) {
            accel_world_destroy(w);
            return cli_fail(&run);
        }
        w->world.instances = &in->hook;
        run.scene.instance_bounds = instances_bounds; /* the scale warning measures them too */
        run.scene.placed_instances = in;
        if (run.options.pov == NULL && !instances_within_budget(&run, in)) {
            instances_free(in);
            accel_world_destroy(w);
            return cli_finish(&run);
        }
    }
    if (animation.frames > 0 && run.options.pov == NULL) {
        run.status = render_frames(&run, w, in);
    } else if (cli_render_sampled(&run, trace_soft, &w->world, &shutter_sampler)) {
        if (w->triangles.face_count > 0 || in == NULL) /* else the instances hold every triangle */
            accel_report(w, &run.total, run.options.stats);
        if (in != NULL)
            instances_report(in, stdout, run.options.stats);
    }
    run.scene.instance_bounds = NULL;
    instances_free(in);
    accel_world_destroy(w);
    return cli_finish(&run);
}
