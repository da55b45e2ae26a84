/* cli.c: the command line and the load-render-write sequence shared by all chapters (chapter 1). */
#include "cli.h"

#include "clock.h"
#include "heatmap.h"
#include "outfile.h"
#include "scene_scale.h"
#include "scene_set.h"
#include "text_escape.h"

#include <errno.h>
#include <stdarg.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define CLI_ERROR_SIZE (PATH_MAX + 1024) /* longest error message kept: a whole path and the reason */
#define CLI_MAX_THREADS 256  /* more threads than this is a typing mistake */

struct options {
    const char *scene;
    const char *output;
    const char *pov;
    const char *heatmap;
    int width, height; /* 0 = as the scene says */
    int threads;       /* 0 = all cores */
    bool output_given; /* -o was used; otherwise the picture goes to out/ */
    bool quiet;
    bool stats;        /* --stats: the chapter's detailed report too */
    const char *sets[SCENE_SET_MAX]; /* --set PATH=VALUE changes to the scene, in order */
    int set_count;
};

/* Prints one error message and a newline to standard error, with every non-printable byte of it (which
 * can only have come from the input it quotes) escaped as \xNN. */
static void complain(const char *format, ...) __attribute__((format(printf, 1, 2)));
static void complain(const char *format, ...) {
    char raw[CLI_ERROR_SIZE], escaped[4 * CLI_ERROR_SIZE]; /* an escape is 4 bytes for 1 */
    va_list args;
    va_start(args, format);
    vsnprintf(raw, sizeof raw, format, args);
    va_end(args);
    text_escape(raw, escaped, sizeof escaped);
    fprintf(stderr, "%s\n", escaped);
}

static void print_usage(FILE *out, const struct chapter *ch, const char *program) {
    fprintf(out,
            "usage: %s [SCENE] [options]\n"
            "Chapter %d (%s) of the whitted ray tracer: renders SCENE (default %s).\n"
            "\n"
            "options:\n"
            "  -o FILE          write the picture to FILE (default out/chapter-%02d.png; - for\n"
            "                   standard output, the counters then go to standard error)\n"
            "  --width N        override the scene's image width\n"
            "  --height N       override the scene's image height\n"
            "  --pov FILE       write the scene's POV-Ray twin to FILE instead of rendering\n"
            "  --heatmap FILE   also write the work done per pixel as a picture\n"
            "  --threads N      render on N threads (default: all cores)\n"
            "  --set PATH=VALUE change one value of the scene, e.g. max_depth=1, camera.fov=30,\n"
            "                   material.glass.ior=1.45, sphere.2.radius=0.5 (repeatable)\n"
            "  --stats          also print the details of what the chapter built\n"
            "  --quiet          print nothing but errors\n"
            "  -h, --help       show this help\n"
            "%s"
            "\n"
            "exit status: 0 done, 1 bad scene or mesh file, 2 bad command line, 3 cannot write output\n",
            program, ch->number, ch->title, ch->default_scene, ch->number,
            ch->options_help != NULL ? ch->options_help : "");
}

/* Reads a whole number in [lo, hi] for option `name`. */
static bool option_int(const char *name, const char *text, int lo, int hi, int *out) {
    char *end = NULL;
    errno = 0;
    long value = text == NULL ? 0 : strtol(text, &end, 10);
    if (text == NULL || end == text || *end != '\0' || errno != 0 || value < lo || value > hi) {
        complain("%s needs a whole number from %d to %d, got '%s'", name, lo, hi,
                text == NULL ? "" : text);
        return false;
    }
    *out = (int)value;
    return true;
}

/* Fills *o from the command line. Returns CLI_OK, CLI_USAGE on an error (message printed), or -1 when
 * --help was printed and the program should stop successfully. */
static int parse_options(const struct chapter *ch, int argc, char **argv, struct options *o) {
    static char default_output[32]; /* "out/chapter-NN.png" */
    memset(o, 0, sizeof *o);
    o->scene = ch->default_scene;
    snprintf(default_output, sizeof default_output, "out/chapter-%02d.png", ch->number);
    o->output = default_output;
    bool scene_given = false;
    for (int k = 1; k < argc; k++) {
        const char *arg = argv[k];
        const char *value = k + 1 < argc ? argv[k + 1] : NULL;
        bool takes_value = true;
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            print_usage(stdout, ch, argv[0]);
            return -1;
        } else if (strcmp(arg, "--quiet") == 0 || strcmp(arg, "--stats") == 0) {
            o->quiet = o->quiet || strcmp(arg, "--quiet") == 0;
            o->stats = o->stats || strcmp(arg, "--stats") == 0;
            takes_value = false;
        } else if (strcmp(arg, "-o") == 0 || strcmp(arg, "--pov") == 0 || strcmp(arg, "--heatmap") == 0) {
            if (value == NULL || value[0] == '\0') {
                complain("%s needs a file name", arg);
                return CLI_USAGE;
            }
            if (!outfile_name_fits(value)) {
                complain("%s: the file name is too long (%zu bytes; the system allows %d for a path, "
                         "%d for one name, less %zu for the temporary file)", arg, strlen(value), PATH_MAX - 1,
                        NAME_MAX, strlen(OUTFILE_TEMP_SUFFIX));
                return CLI_USAGE;
            }
            if (strcmp(arg, "-o") == 0) {
                o->output = value;
                o->output_given = true;
            }
            else if (strcmp(arg, "--pov") == 0)
                o->pov = value;
            else
                o->heatmap = value;
        } else if (strcmp(arg, "--set") == 0) {
            if (value == NULL || strchr(value, '=') == NULL) {
                complain("--set needs PATH=VALUE, e.g. --set max_depth=1");
                return CLI_USAGE;
            }
            if (o->set_count == SCENE_SET_MAX) {
                complain("at most %d --set options, please", SCENE_SET_MAX);
                return CLI_USAGE;
            }
            o->sets[o->set_count++] = value;
        } else if (strcmp(arg, "--width") == 0) {
            if (!option_int(arg, value, 1, IMAGE_MAX_SIDE, &o->width))
                return CLI_USAGE;
        } else if (strcmp(arg, "--height") == 0) {
            if (!option_int(arg, value, 1, IMAGE_MAX_SIDE, &o->height))
                return CLI_USAGE;
        } else if (strcmp(arg, "--threads") == 0) {
            if (!option_int(arg, value, 1, CLI_MAX_THREADS, &o->threads))
                return CLI_USAGE;
        } else if (arg[0] == '-' && arg[1] != '\0') {
            int used = ch->parse_option != NULL ? ch->parse_option(arg, value) : 0;
            if (used < 0)
                return CLI_USAGE;
            if (used == 0) {
                complain("unknown option '%s'", arg);
                return CLI_USAGE;
            }
            takes_value = used == 2;
        } else if (scene_given) {
            complain("only one scene file, please (got '%s' and '%s')", o->scene, arg);
            return CLI_USAGE;
        } else {
            o->scene = arg;
            scene_given = true;
            takes_value = false;
        }
        if (takes_value)
            k++;
    }
    if (o->pov == NULL && o->heatmap != NULL && outfile_same_file(o->output, o->heatmap)) {
        complain("-o and --heatmap name the same file ('%s' and '%s'); give two", o->output, o->heatmap);
        return CLI_USAGE;
    }
    return CLI_OK;
}

/* Loads the scene and everything the chapter needs; returns the world for trace, or NULL (with
 * *bad_option set when a --set change was at fault rather than the scene). */
static void *load_world(const struct chapter *ch, const struct options *o, struct scene *s, bool *bad_option,
                        char *err, size_t err_size) {
    if (!scene_load_changed(o->scene, o->sets, o->set_count, s, bad_option, err, err_size))
        return NULL;
    if (o->width > 0)
        s->width = o->width;
    if (o->height > 0)
        s->height = o->height;
    scene_drop_unsupported(s, ch->features, ch->number, o->quiet ? NULL : stderr);
    if (ch->load_meshes != NULL && !ch->load_meshes(s, err, err_size))
        return NULL;
    if (!o->quiet)
        scene_scale_warn(s, stderr);
    if (ch->prepare == NULL)
        return s;
    return ch->prepare(s, err, err_size);
}

static int render_and_write(const struct chapter *ch, const struct options *o, const struct scene *s,
                            const void *world) {
    char err[CLI_ERROR_SIZE];
    struct camera cam;
    if (!camera_init(&cam, s->eye, s->target, s->up, s->fov, s->width, s->height, err, sizeof err)) {
        complain("%s: %s", s->path, err);
        return CLI_BAD_INPUT;
    }
    struct image img, heatmap = {0};
    if (!image_create(&img, s->width, s->height)) {
        complain("out of memory for a %d x %d image", s->width, s->height);
        return CLI_OUTPUT_FAILED;
    }
    if (o->heatmap != NULL &&
        !image_create(&heatmap, s->width, s->height + heatmap_bar_height(s->width, s->height))) {
        image_free(&img);
        complain("out of memory for the heat-map");
        return CLI_OUTPUT_FAILED;
    }
    if (!o->output_given)
        mkdir("out", 0755); /* the default folder; if this fails, writing the PNG says why */
    struct stats total = {0};
    struct render_job job = {.camera = &cam, .trace = ch->trace, .world = world, .threads = o->threads,
                             .progress = !o->quiet && isatty(STDERR_FILENO),
                             .heatmap = o->heatmap != NULL ? &heatmap : NULL};
    double started = clock_seconds();
    render_image(&job, &img, &total);
    double elapsed = clock_seconds() - started;
    bool written = image_write_png(&img, o->output, err, sizeof err);
    if (written && o->heatmap != NULL) {
        heatmap_draw_bar(&heatmap, s->height);
        written = image_write_png(&heatmap, o->heatmap, err, sizeof err);
    }
    image_free(&img);
    image_free(&heatmap);
    if (!written) {
        complain("%s", err);
        return CLI_OUTPUT_FAILED;
    }
    if (!o->quiet) {
        char shown[4 * PATH_MAX];
        text_escape(strcmp(o->output, "-") == 0 ? "standard output" : o->output, shown, sizeof shown);
        printf("chapter %d (%s): wrote %s (%d x %d) in %.3f s\n", ch->number, ch->title, shown, s->width,
               s->height, elapsed);
        if (o->heatmap != NULL) {
            text_escape(o->heatmap, shown, sizeof shown);
            printf("heat-map: %s\n", shown);
        }
        stats_print(stdout, &total);
        stats_warn_limits(stderr, &total);
        if (ch->report != NULL)
            ch->report(world, &total, elapsed, o->stats);
    }
    return CLI_OK;
}

int cli_run(const struct chapter *ch, int argc, char **argv) {
    struct options o;
    int status = parse_options(ch, argc, argv, &o);
    if (status < 0)
        return CLI_OK;
    if (status != CLI_OK) {
        print_usage(stderr, ch, argv[0]);
        return status;
    }
    bool to_stdout = strcmp(o.output, "-") == 0 || (o.heatmap != NULL && strcmp(o.heatmap, "-") == 0) ||
                     (o.pov != NULL && strcmp(o.pov, "-") == 0);
    if (to_stdout && !outfile_reserve_stdout()) {
        complain("cannot set standard output aside for the picture: %s", strerror(errno));
        return CLI_OUTPUT_FAILED;
    }
    char err[CLI_ERROR_SIZE];
    struct scene s;
    bool bad_option = false;
    void *world = load_world(ch, &o, &s, &bad_option, err, sizeof err);
    if (world == NULL) {
        complain("%s", err);
        scene_free(&s);
        return bad_option ? CLI_USAGE : CLI_BAD_INPUT;
    }
    if (o.pov != NULL) {
        if (!povray_can_express(&s, ch->lighting, err, sizeof err))
            status = CLI_BAD_INPUT;
        else if (!povray_write_scene(&s, ch->lighting, o.pov, err, sizeof err))
            status = CLI_OUTPUT_FAILED;
        if (status != CLI_OK)
            complain("%s", err);
        else if (!o.quiet) {
            char shown[4 * PATH_MAX];
            text_escape(o.pov, shown, sizeof shown);
            printf("chapter %d (%s): wrote POV-Ray twin %s\n", ch->number, ch->title, shown);
        }
    } else {
        status = render_and_write(ch, &o, &s, world);
    }
    if (ch->release != NULL && world != &s)
        ch->release(world);
    scene_free(&s);
    return status;
}
