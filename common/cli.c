/* cli.c: the command line and the steps of reading, rendering and writing shared by all chapters
 * (chapter 1). */
#include "cli.h"

#include "clock.h"
#include "heatmap.h"
#include "instance_syntax.h"
#include "outfile.h"
#include "path_settings.h"
#include "ray_budget.h"
#include "scene_scale.h"
#include "scene_set.h"
#include "text_escape.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define CLI_MAX_THREADS 256  /* more threads than this is a typing mistake */

#ifdef __EMSCRIPTEN__
#include <emscripten.h>

#define HELD_ARGS_PATH "/held/args"   /* where web/worker.js writes the next render's command line */
#define HELD_ARGS_BYTES 65536         /* the longest command line a held render takes */
#define HELD_ARGS_MAX 1024            /* the most words in it */

/* Whether the page (web/worker.js) holds this instance for more renders of the same world. */
EM_JS(int, held_wanted, (void), { return Module.holdRenders ? 1 : 0; });
/* Hands the finished render's status to the page and waits (the instance's stack set aside by
 * Asyncify) until the page has written the next render's scene and command line. */
EM_ASYNC_JS(void, held_next_job, (int status), { await Module.nextJob(status); });
#endif

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
            "  --tile X Y W H   render only the W x H pixels from column X, row Y of the picture\n"
            "                   (0 0 at its top left), written as a W x H picture: a render\n"
            "                   farm's tile, the same pixels as the whole picture's\n"
            "  --threads N      render on N threads, and build on them where the chapter\n"
            "                   builds in parallel (chapter 11 on); default: all cores\n"
            "  --set PATH=VALUE change one value of the scene, e.g. max_depth=1, camera.fov=30,\n"
            "                   material.glass.ior=1.45, sphere.2.radius=0.5 (repeatable)\n"
            "  --stats          also print the details of what the chapter built\n"
            "  --quiet          print nothing but errors\n"
            "  --no-limit       render even a scene that asks for more than %.0e rays (the\n"
            "                   bound worked out from its keys before rendering)\n"
            "  -h, --help       show this help\n"
            "%s"
            "\n"
            "exit status: 0 done, 1 bad scene or mesh file, 2 bad command line, 3 cannot write output\n",
            program, ch->number, ch->title, ch->default_scene, ch->number, RAY_BUDGET_LIMIT,
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

/* Reads --tile's four numbers from the `count` words at `words`: X and Y from 0, W and H from 1. */
static bool option_tile(int count, char **words, struct render_window *tile) {
    if (count < 4) {
        complain("--tile needs four whole numbers X Y W H: the tile's left column, top row, width and height");
        return false;
    }
    return option_int("--tile X", words[0], 0, IMAGE_MAX_SIDE - 1, &tile->left) &&
           option_int("--tile Y", words[1], 0, IMAGE_MAX_SIDE - 1, &tile->top) &&
           option_int("--tile W", words[2], 1, IMAGE_MAX_SIDE, &tile->width) &&
           option_int("--tile H", words[3], 1, IMAGE_MAX_SIDE, &tile->height);
}

/* Fills *o from the command line. Returns CLI_OK, CLI_USAGE on an error (message printed), or -1 when
 * --help was printed and the program should stop successfully. */
static int parse_options(const struct chapter *ch, int argc, char **argv, struct cli_options *o) {
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
        } else if (strcmp(arg, "--quiet") == 0 || strcmp(arg, "--stats") == 0 || strcmp(arg, "--no-limit") == 0) {
            o->quiet = o->quiet || strcmp(arg, "--quiet") == 0;
            o->stats = o->stats || strcmp(arg, "--stats") == 0;
            o->no_limit = o->no_limit || strcmp(arg, "--no-limit") == 0;
            takes_value = false;
        } else if (strcmp(arg, "-o") == 0 || strcmp(arg, "--pov") == 0 || strcmp(arg, "--heatmap") == 0 ||
                   (ch->output_option != NULL && strcmp(arg, ch->output_option) == 0)) {
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
            else if (strcmp(arg, "--heatmap") == 0)
                o->heatmap = value;
            else
                o->chapter_output = value;
        } else if (strcmp(arg, "--tile") == 0) {
            if (!option_tile(argc - k - 1, argv + k + 1, &o->tile))
                return CLI_USAGE;
            k += 4;
            takes_value = false;
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
    if (o->pov != NULL && o->tile.width > 0) {
        complain("--tile renders part of the picture, --pov writes the scene's POV-Ray twin instead of "
                 "rendering; give one of them");
        return CLI_USAGE;
    }
    /* A render's own outputs would be silently left unwritten under --pov. */
    const char *render_output = o->output_given ? "-o" : o->heatmap != NULL ? "--heatmap"
                                : o->chapter_output != NULL ? ch->output_option : NULL;
    if (o->pov != NULL && render_output != NULL) {
        complain("%s names an output of the render, and --pov writes the scene's POV-Ray twin instead of rendering; "
                 "give one of them", render_output);
        return CLI_USAGE;
    }
    if (o->pov == NULL) { /* with --pov nothing but the twin is written */
        const char *names[] = {"-o", "--heatmap", ch->output_option};
        const char *files[] = {o->output, o->heatmap, o->chapter_output};
        for (int a = 0; a < 3; a++)
            for (int b = a + 1; b < 3; b++)
                if (files[a] != NULL && files[b] != NULL && outfile_same_file(files[a], files[b])) {
                    complain("%s and %s name the same file ('%s' and '%s'); give two", names[a], names[b], files[a],
                             files[b]);
                    return CLI_USAGE;
                }
    }
    return CLI_OK;
}

/* How many files run may read, as input_file counts them: the scene file, then the meshes, the pigments
 * and the objects in the order of their lines. */
static size_t input_count(const struct cli_run *run) {
    const struct scene *s = &run->scene;
    return 1 + s->mesh_count + s->pigment_count + s->object_count;
}

/* The k-th file run may read (k < input_count), or NULL when it is a pigment without a file; with
 * what[size] not NULL, also what it is to the run, e.g. "the mesh of line 4". */
static const char *input_file(const struct cli_run *run, size_t k, char *what, size_t size) {
    const struct scene *s = &run->scene;
    if (k == 0) {
        if (what != NULL)
            snprintf(what, size, "the scene file");
        return run->options.scene;
    }
    k -= 1;
    if (k < s->mesh_count) {
        if (what != NULL)
            snprintf(what, size, "the mesh of line %d", s->meshes[k].line);
        return s->meshes[k].path;
    }
    k -= s->mesh_count;
    if (k < s->pigment_count) {
        if (what != NULL && s->pigments[k].file != NULL)
            snprintf(what, size, "the image of pigment '%s'", s->pigments[k].name);
        return s->pigments[k].file;
    }
    k -= s->pigment_count;
    if (what != NULL)
        snprintf(what, size, "the mesh of object '%s'", s->objects[k].name);
    return s->objects[k].path;
}

/* Says that option's file is run's input number k and returns true; returns false when k is
 * OUTFILE_INDEX_NONE. */
static bool refuse_written_input(const struct cli_run *run, const char *option, const char *file, size_t k) {
    if (k == OUTFILE_INDEX_NONE)
        return false;
    char what[SCENE_NAME_MAX + 64] = "";
    input_file(run, k, what, sizeof what);
    complain("%s names '%s', which the run reads (%s): writing it would destroy it; give another file", option, file,
             what);
    return true;
}

bool cli_output_is_an_input(const struct cli_run *run, const char *option, const char *file) {
    size_t found = OUTFILE_INDEX_NONE;
    for (size_t k = 0; found == OUTFILE_INDEX_NONE && k < input_count(run); k++) {
        const char *input = input_file(run, k, NULL, 0);
        if (input != NULL && outfile_same_file(file, input))
            found = k;
    }
    return refuse_written_input(run, option, file, found);
}

bool cli_inputs_open(struct cli_inputs *inputs, const struct cli_run *run) {
    size_t count = input_count(run);
    *inputs = (struct cli_inputs){.run = run, .names = malloc(count * sizeof *inputs->names)};
    for (size_t k = 0; inputs->names != NULL && k < count; k++)
        inputs->names[k] = input_file(run, k, NULL, 0);
    if (inputs->names == NULL || !outfile_index_build(&inputs->index, inputs->names, count)) {
        complain("out of memory for the list of the %zu files the run reads", count);
        return false;
    }
    return true;
}

bool cli_inputs_written(const struct cli_inputs *inputs, const char *option, const char *file) {
    return refuse_written_input(inputs->run, option, file, outfile_index_find(&inputs->index, file));
}

void cli_inputs_free(struct cli_inputs *inputs) {
    outfile_index_free(&inputs->index);
    free(inputs->names);
    *inputs = (struct cli_inputs){0};
}

/* Bounds the rays the run's scene asks for: a note above RAY_BUDGET_LARGE, a refusal above
 * RAY_BUDGET_LIMIT without --no-limit (run->status CLI_BAD_INPUT, returns false). */
static bool within_budget(struct cli_run *run) {
    const struct scene *s = &run->scene;
    struct ray_budget b;
    long pictures = run->chapter->pictures != NULL ? run->chapter->pictures() : 1;
    double rays = ray_budget_estimate(s, run->chapter->number, &b) * (double)pictures;
    double tests = b.tests * (double)pictures;
    bool many_rays = rays > RAY_BUDGET_LARGE, many_tests = tests > RAY_BUDGET_TEST_LARGE;
    bool over = (rays > RAY_BUDGET_LIMIT || tests > RAY_BUDGET_TEST_LIMIT) && !run->options.no_limit;
    if ((!many_rays && !many_tests) || (run->options.quiet && !over))
        return true;
    char where[PATH_MAX + 32], factors[1024];
    if (b.line > 0)
        snprintf(where, sizeof where, "%s:%d", s->path, b.line);
    else
        snprintf(where, sizeof where, "%s", s->path);
    ray_budget_describe(&b, s, run->chapter->number, factors, sizeof factors);
    if (pictures > 1) {
        size_t used = strlen(factors);
        snprintf(factors + used, sizeof factors - used, ", %ld pictures", pictures);
    }
    /* The shapes each ray tests make the scene long when the tests are many while the rays are within
     * their limit and either not many or outdone by tests over the tests' own limit; else the rays do. */
    bool tests_make_it_long = rays <= RAY_BUDGET_LIMIT && many_tests && (!many_rays || tests > RAY_BUDGET_TEST_LIMIT);
    if (tests_make_it_long) {
        if (!over) {
            complain("%s: note: the scene asks for up to about %.2g rays (%s), each testing %.0f shapes that no "
                     "structure holds: about %.2g tests; this may take a while", where, rays, factors, b.shapes_per_ray,
                     tests);
            return true;
        }
        complain("%s: the scene asks for up to about %.2g rays (%s), each testing %.0f shapes that no structure "
                 "holds: about %.2g tests, over the limit of %.0e; pass --no-limit to render it anyway", where, rays,
                 factors, b.shapes_per_ray, tests, RAY_BUDGET_TEST_LIMIT);
        run->status = CLI_BAD_INPUT;
        return false;
    }
    if (!over) {
        complain("%s: note: the scene asks for up to about %.2g rays (%s); this may take a while", where, rays,
                 factors);
        return true;
    }
    complain("%s: the scene asks for up to about %.2g rays (%s), over the limit of %.0e; pass --no-limit to "
             "render it anyway", where, rays, factors, RAY_BUDGET_LIMIT);
    run->status = CLI_BAD_INPUT;
    return false;
}

/* Whether some channel of c is above 0: a colour that can add light. (A negative one takes light away,
 * as POV-Ray's negative lights do, and a scene lit only by such colours is black.) */
static bool adds_light(vec3 c) { return c.x > 0.0 || c.y > 0.0 || c.z > 0.0; }

/* Whether a light line of s has a colour that adds light. */
static bool has_a_light_that_adds(const struct scene *s) {
    for (size_t k = 0; k < s->light_count; k++)
        if (adds_light(s->lights[k].colour))
            return true;
    return false;
}

/* Whether s has no shape, mesh or instance at all: it draws its background, as it says. */
static bool draws_nothing(const struct scene *s) {
    size_t drawn = s->mesh_count + s->instance_count;
    for (size_t k = 0; k < s->kind_count; k++)
        drawn += s->shapes[k].syntax != NULL ? s->shapes[k].count : 0;
    return drawn == 0;
}

/* Whether a shape, mesh or instance of s has a material with an ambient term (the default material has
 * one, 0.1, as POV-Ray's). */
static bool drawn_with_ambient(const struct scene *s) {
    for (size_t k = 0; k < s->kind_count; k++) {
        const struct shape_list *list = &s->shapes[k];
        for (size_t i = 0; list->syntax != NULL && i < list->count; i++)
            if (s->materials[shape_material(list->syntax, shape_item(list->syntax, list->items, i))].ambient > 0.0)
                return true;
    }
    for (size_t k = 0; k < s->mesh_count; k++)
        if (s->materials[s->meshes[k].material].ambient > 0.0)
            return true;
    for (size_t k = 0; k < s->instance_count; k++)
        if (s->materials[s->instances[k].material].ambient > 0.0)
            return true;
    return false;
}

/* Chapters 6 to 14 and 16 light a surface by the scene's lights and its ambient light, and what it
 * reflects or lets through ends at the background: with none of them the picture would be black, so it
 * is refused with the reason (`emitting`, the materials whose emission the chapter ignores, are named:
 * such a scene was written for chapters 15 and 17, whose path_program.c checks their own light).
 * Returns true when something lights the scene; chapters 1 to 5 light every surface from the eye. */
static bool lit_by_something(struct cli_run *run, size_t emitting) {
    const struct chapter *ch = run->chapter;
    const struct scene *s = &run->scene;
    bool by_lights = ch->lighting == POV_PHONG || ch->lighting == POV_PHONG_SHADOWS || ch->lighting == POV_WHITTED;
    if (!by_lights || instance_chapter_draws(ch->number, PATH_CHAPTER) || has_a_light_that_adds(s) ||
        adds_light(s->background) || draws_nothing(s) || (adds_light(s->ambient_light) && drawn_with_ambient(s)))
        return true;
    char ignored[160] = "";
    if (emitting > 0)
        snprintf(ignored, sizeof ignored, " (chapter %d ignores the emission of %zu material%s: chapters 15 and 17 "
                 "draw it)", ch->number, emitting, emitting == 1 ? "" : "s");
    complain("%s: nothing lights the scene, so the picture would be black: no light line with a colour above 0, no "
             "ambient light (ambient_light not above 0, or no material drawn with an ambient) and no background above "
             "0%s", s->path, ignored);
    run->status = CLI_BAD_INPUT;
    return false;
}

bool cli_start(struct cli_run *run, const struct chapter *ch, int argc, char **argv) {
    memset(run, 0, sizeof *run);
    run->chapter = ch;
    struct cli_options *o = &run->options;
    int status = parse_options(ch, argc, argv, o);
    if (status < 0)
        return false; /* --help */
    if (status != CLI_OK) {
        print_usage(stderr, ch, argv[0]);
        run->status = status;
        return false;
    }
    render_use_threads(o->threads); /* the build's threads too (chapter 11 on), not only the render's */
    bool to_stdout = false;
    const char *outputs[] = {o->output, o->heatmap, o->pov, o->chapter_output};
    for (int k = 0; k < 4; k++)
        to_stdout = to_stdout || (outputs[k] != NULL && strcmp(outputs[k], "-") == 0);
    if (to_stdout && !outfile_reserve_stdout()) {
        complain("cannot set standard output aside for the picture: %s", strerror(errno));
        run->status = CLI_OUTPUT_FAILED;
        return false;
    }
    /* The files the run will write, tried now rather than after the render: a folder that is not there. The
     * default output's folder is made first (if this fails, trying the output says why). */
    if (!o->output_given && o->pov == NULL)
        mkdir("out", 0755);
    const char *written[] = {o->pov, o->pov == NULL ? o->output : NULL,
                             o->pov == NULL ? o->heatmap : NULL, o->pov == NULL ? o->chapter_output : NULL};
    for (int k = 0; k < 4; k++)
        if (written[k] != NULL && !outfile_can_create(written[k], run->err, sizeof run->err)) {
            complain("%s", run->err);
            run->status = CLI_OUTPUT_FAILED;
            return false;
        }
    struct scene *s = &run->scene;
    bool bad_option = false;
    if (!scene_load_changed(o->scene, o->sets, o->set_count, ch->kinds, s, &bad_option, run->err, sizeof run->err)) {
        complain("%s", run->err);
        run->status = bad_option ? CLI_USAGE : CLI_BAD_INPUT;
        return false;
    }
    if (o->width > 0)
        s->width = o->width;
    if (o->height > 0)
        s->height = o->height;
    const struct render_window *t = &o->tile;
    if (t->width > 0 && (t->left + t->width > s->width || t->top + t->height > s->height)) {
        complain("--tile %d %d %d %d: the tile reaches past the %d x %d picture (its columns %d to %d, rows %d to "
                 "%d; the picture's 0 to %d, 0 to %d)", t->left, t->top, t->width, t->height, s->width, s->height,
                 t->left, t->left + t->width - 1, t->top, t->top + t->height - 1, s->width - 1, s->height - 1);
        run->status = CLI_USAGE;
        return false;
    }
    size_t emitting = 0;
    for (size_t k = 0; k < s->material_count; k++)
        emitting += adds_light(s->materials[k].emission);
    scene_drop_unsupported(s, ch->number, o->quiet ? NULL : stderr);
    /* An output that names an input would be written over it, after the render. */
    const char *written_names[] = {"--pov", "-o", "--heatmap", ch->output_option};
    for (int k = 0; k < 4; k++)
        if (written[k] != NULL && cli_output_is_an_input(run, written_names[k], written[k])) {
            run->status = CLI_USAGE;
            return false;
        }
    return o->pov != NULL || (lit_by_something(run, emitting) && within_budget(run));
}

int cli_fail(struct cli_run *run) {
    complain("%s", run->err);
    run->status = CLI_BAD_INPUT;
    return cli_finish(run);
}

int cli_finish(struct cli_run *run) {
    scene_free(&run->scene);
    return run->status;
}

/* Writes the POV-Ray twin to the --pov file. */
static void write_twin(struct cli_run *run) {
    const struct chapter *ch = run->chapter;
    const char *pov = run->options.pov;
    if (!povray_can_express(&run->scene, ch->lighting, run->err, sizeof run->err))
        run->status = CLI_BAD_INPUT;
    else if (!povray_write_scene(&run->scene, ch->lighting, pov, run->err, sizeof run->err))
        run->status = CLI_OUTPUT_FAILED;
    if (run->status != CLI_OK) {
        complain("%s", run->err);
    } else if (!run->options.quiet) {
        char shown[4 * PATH_MAX];
        text_escape(pov, shown, sizeof shown);
        printf("chapter %d (%s): wrote POV-Ray twin %s\n", ch->number, ch->title, shown);
    }
}

/* Writes `window` of img as a PNG at `path`, with the heat-map's colour bar of `bar` under it when bar is
 * not NULL: img itself when it is the window with room for the bar under it, else a copy. Returns false
 * with the reason in err. */
static bool write_window(struct image *img, struct render_window window, const struct heatmap_scale *bar,
                         const char *path, char *err, size_t err_size) {
    int bar_rows = bar != NULL ? heatmap_bar_height(window.width, window.height) : 0;
    if (window.left == 0 && window.top == 0 && window.width == img->width &&
        window.height + bar_rows == img->height) {
        if (bar != NULL)
            heatmap_draw_bar_on(img, window.height, bar);
        return image_write_png(img, path, err, err_size);
    }
    struct image out;
    if (!image_create(&out, window.width, window.height + bar_rows)) {
        snprintf(err, err_size, "out of memory for a %d x %d picture to write to %s", window.width,
                 window.height + bar_rows, path);
        return false;
    }
    image_copy_rect(&out, img, window.left, window.top, window.width, window.height);
    if (bar != NULL)
        heatmap_draw_bar_on(&out, window.height, bar);
    bool written = image_write_png(&out, path, err, err_size);
    image_free(&out);
    return written;
}

/* Renders and writes the picture (and the heat-map), its pixels sampled by `sampler` (NULL: one ray
 * through each centre), only the --tile rectangle of them when one is given; prints where they went and
 * the counters. Returns false with run->status set when the camera, the tile or an output fails. */
static bool render_and_write(struct cli_run *run, render_trace_fn trace, const void *world,
                             const struct render_sampler *sampler) {
    const struct chapter *ch = run->chapter;
    const struct cli_options *o = &run->options;
    const struct scene *s = &run->scene;
    char err[CLI_ERROR_SIZE];
    struct camera cam;
    if (!camera_init(&cam, s->eye, s->target, s->up, s->fov, s->width, s->height, err, sizeof err)) {
        complain("%s: %s", s->path, err);
        run->status = CLI_BAD_INPUT;
        return false;
    }
    bool tiled = o->tile.width > 0;
    struct render_window window = tiled ? o->tile : (struct render_window){0, 0, s->width, s->height};
    struct image img, heatmap = {0};
    struct render_job job = {.camera = &cam, .trace = trace, .world = world, .threads = o->threads,
                             .progress = !o->quiet,
                             .heatmap = o->heatmap != NULL ? &heatmap : NULL, .sampler = sampler,
                             .antialias = &s->antialias, .lens = &s->lens, .window = window};
    if (!render_window_is_exact(&job, window, s->width, s->height)) {
        complain("--tile %d %d %d %d: the scene's antialias method compares each pixel with its neighbours in "
                 "its block of %d x %d pixels, so a tile must be made of whole blocks: X and Y multiples of %d, "
                 "X + W and Y + H too or the picture's edge (%d, %d)", window.left, window.top, window.width,
                 window.height, ANTIALIAS_BLOCK, ANTIALIAS_BLOCK, ANTIALIAS_BLOCK, s->width, s->height);
        run->status = CLI_USAGE;
        return false;
    }
    if (!image_create(&img, s->width, s->height)) {
        complain("out of memory for a %d x %d image", s->width, s->height);
        run->status = CLI_OUTPUT_FAILED;
        return false;
    }
    /* The heat-map of the whole picture has room for its bar; a tile's is copied out with its own. */
    int bar_rows = tiled ? 0 : heatmap_bar_height(s->width, s->height);
    if (o->heatmap != NULL && !image_create(&heatmap, s->width, s->height + bar_rows)) {
        image_free(&img);
        complain("out of memory for the heat-map");
        run->status = CLI_OUTPUT_FAILED;
        return false;
    }
    double started = clock_seconds();
    render_image(&job, &img, &run->total);
    run->render_seconds = clock_seconds() - started;
    if (run->total.non_finite_pixels > 0) {
        complain("%s: %" PRIu64 " pixel%s came out not a number or infinite, a fault of chapter %d's renderer that "
                 "this scene brings out; nothing written", s->path, run->total.non_finite_pixels,
                 run->total.non_finite_pixels == 1 ? "" : "s", ch->number);
        image_free(&img);
        image_free(&heatmap);
        run->status = CLI_BAD_INPUT;
        return false;
    }
    bool written = write_window(&img, window, NULL, o->output, err, sizeof err);
    if (written && o->heatmap != NULL)
        written = write_window(&heatmap, window, sampler != NULL ? sampler->heatmap : &heatmap_cost_scale,
                               o->heatmap, err, sizeof err);
    image_free(&img);
    image_free(&heatmap);
    if (!written) {
        complain("%s", err);
        run->status = CLI_OUTPUT_FAILED;
        return false;
    }
    if (!o->quiet) {
        char shown[4 * PATH_MAX], size[128];
        text_escape(strcmp(o->output, "-") == 0 ? "standard output" : o->output, shown, sizeof shown);
        if (tiled)
            snprintf(size, sizeof size, "the %d x %d tile at column %d, row %d of the %d x %d picture", window.width,
                     window.height, window.left, window.top, s->width, s->height);
        else
            snprintf(size, sizeof size, "%d x %d", s->width, s->height);
        printf("chapter %d (%s): wrote %s (%s) in %.3f s\n", ch->number, ch->title, shown, size, run->render_seconds);
        if (o->heatmap != NULL) {
            text_escape(o->heatmap, shown, sizeof shown);
            printf("heat-map: %s\n", shown);
        }
        stats_print(stdout, &run->total);
        stats_warn_limits(stderr, &run->total);
    }
    return true;
}

bool cli_render(struct cli_run *run, render_trace_fn trace, const void *world) {
    return cli_render_sampled(run, trace, world, NULL);
}

#ifdef __EMSCRIPTEN__
bool cli_held(const struct cli_run *run) { return run->options.pov == NULL && held_wanted(); }

/* Reads the held render's command line (words ending in zero bytes) into argv, the words kept in a
 * static buffer until the next call. Returns the number of words (with the program's name), or 0 when
 * the file cannot be read or is too long. */
static int held_read_args(char **argv) {
    static char text[HELD_ARGS_BYTES + 1];
    FILE *f = fopen(HELD_ARGS_PATH, "rb");
    size_t n = f != NULL ? fread(text, 1, HELD_ARGS_BYTES + 1, f) : 0;
    if (f != NULL)
        fclose(f);
    if (n == 0 || n > HELD_ARGS_BYTES || text[n - 1] != '\0')
        return 0;
    int argc = 0;
    for (size_t at = 0; at < n && argc < HELD_ARGS_MAX; at += strlen(text + at) + 1)
        argv[argc++] = text + at;
    return argc;
}

/* The held loop (cli_render): the next render's command line and scene read as cli_start reads them,
 * their camera, size, samples and tile taken into the run (the world, built over the rest, is the
 * same), and the picture drawn again. Never returns. */
static __attribute__((noinline)) void held_renders(struct cli_run *run, render_trace_fn trace, const void *world,
                                                   const struct render_sampler *sampler) {
    for (;;) {
        fflush(stdout);
        fflush(stderr);
        held_next_job(run->status);
        static char *argv[HELD_ARGS_MAX + 1];
        int argc = held_read_args(argv);
        argv[argc] = NULL;
        struct cli_run next;
        bool go = argc > 0 && cli_start(&next, run->chapter, argc, argv);
        run->status = argc > 0 ? next.status : CLI_USAGE;
        if (argc > 0) {
            struct scene *s = &run->scene, *n = &next.scene;
            if (go) {
                run->options = next.options;
                s->eye = n->eye, s->target = n->target, s->up = n->up, s->fov = n->fov, s->lens = n->lens;
                s->width = n->width, s->height = n->height;
                s->antialias = n->antialias, s->paths = n->paths;
            }
            cli_finish(&next);
        }
        if (!go || run->status != CLI_OK)
            continue;
        run->total = (struct stats){0};
        if (run->held_refresh != NULL && !run->held_refresh(run, run->held_context))
            continue;
        render_and_write(run, trace, world, sampler);
    }
}
#else
bool cli_held(const struct cli_run *run) {
    (void)run;
    return false;
}
#endif

void cli_check_scale(struct cli_run *run) {
    if (!run->scale_checked && !run->options.quiet)
        scene_scale_warn(&run->scene, stderr);
    run->scale_checked = true;
}

bool cli_render_sampled(struct cli_run *run, render_trace_fn trace, const void *world,
                        const struct render_sampler *sampler) {
    cli_check_scale(run);
    if (run->options.pov != NULL) {
        write_twin(run);
        return false;
    }
    bool written = render_and_write(run, trace, world, sampler);
#ifdef __EMSCRIPTEN__
    if (cli_held(run))
        held_renders(run, trace, world, sampler);
#endif
    return written && !run->options.quiet;
}
