/* cli.h: what every chapter program shares: its options, reading the scene, rendering, writing the
 * picture and printing the counters (chapter 1).
 *
 * A chapter's main.c describes itself in a `struct chapter` (its number, default scene, the kinds of
 * shape it draws, how it lights them) and then runs its own steps, e.g. chapter 5's:
 *     cli_start          the options and the scene, with the kinds of shape the chapter draws
 *     scene_load_meshes  the mesh files (chapter 3 on)
 *     world_init         what the chapter builds to search the scene (chapter 5 on)
 *     cli_render         the picture, or the POV-Ray twin with --pov, and the counters
 *     cli_finish         the exit status
 * A step of the chapter's own that fails hands its message to cli_fail. Exit codes:
 *   0  the picture (or POV-Ray twin) was written
 *   1  the scene or a mesh file is wrong (message: "file:line: what is wrong")
 *   2  the command line is wrong (message, then the usage): also an output name longer than the
 *      system takes, or two outputs (-o, --heatmap, the chapter's own output option) naming one file
 *   3  the output file cannot be written (no such folder, disk or device full), or memory ran out
 *
 * `--heatmap FILE` works in every chapter: it writes how much work each pixel's camera ray cost
 * (node visits, box and shape tests, including those of its shadow and secondary rays) as a picture,
 * on one fixed colour scale so that pictures of different chapters can be set side by side. In
 * chapter 12 it shows how many camera rays each pixel took instead, on a scale of its own.
 *
 * `--tile X Y W H` works in every chapter too: it renders only the rectangle [X, X + W) x [Y, Y + H) of
 * the picture, through the whole picture's camera, and writes it (and the heat-map) as a W x H picture:
 * the pixels the whole picture has there, so that tiles rendered apart (on the machines of a render
 * farm, tools/farm/) join into the very picture one machine draws. A rectangle outside the picture, or
 * one that cuts the blocks of a sampler whose blocks' edges matter (render.h), is a command-line error. */
#ifndef WHITTED_CLI_H
#define WHITTED_CLI_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>

#include "outfile.h"
#include "povray.h"
#include "render.h"
#include "scene.h"
#include "scene_set.h"
#include "stats.h"

enum cli_exit { CLI_OK = 0, CLI_BAD_INPUT = 1, CLI_USAGE = 2, CLI_OUTPUT_FAILED = 3 };

struct chapter {
    int number;                     /* 1 .. 11 */
    const char *title;              /* e.g. "camera" */
    const char *default_scene;      /* path used when no scene is given, relative to the repository */
    /* The kinds of shape the chapter draws, ending with NULL (NULL: none). The scene keeps only those;
     * the others are reported as ignored. */
    const struct shape_kind *const *kinds;
    enum pov_lighting lighting;     /* what the chapter computes, for the POV-Ray twin */
    /* Optional: the chapter's own options. Called with an option the common parser does not know and
     * the word after it (NULL at the end); returns the number of words used (1 or 2), 0 when the
     * option is unknown, or -1 after printing why its value is wrong. */
    int (*parse_option)(const char *option, const char *value);
    const char *options_help;       /* lines describing those options for --help */
    /* Optional: the name of one more output file option the chapter writes itself (chapter 15's
     * "--hdr"), or NULL. The common parser reads it with -o's rules: a name that fits, "-" for
     * standard output (the counters then go to standard error), never the file of another output. Its
     * value is in cli_options.chapter_output; the chapter describes it in options_help. */
    const char *output_option;
    /* Optional: how many pictures the run renders, given the chapter's options (chapter 16's --frames N,
     * or 1 with --frame K); NULL: one. The ray budget counts the rays of all of them. */
    long (*pictures)(void);
};

#define CLI_ERROR_SIZE (PATH_MAX + 1024) /* longest error message kept: a whole path and the reason */

/* The options every chapter takes (see --help). */
struct cli_options {
    const char *scene;
    const char *output;
    const char *pov;
    const char *heatmap;
    const char *chapter_output; /* the chapter's output_option's file, or NULL */
    int width, height; /* 0 = as the scene says */
    int threads;       /* 0 = all cores */
    bool output_given; /* -o was used; otherwise the picture goes to out/ */
    bool quiet;
    bool stats;        /* --stats: the chapter's detailed report too */
    bool no_limit;     /* --no-limit: render even a scene over RAY_BUDGET_LIMIT (ray_budget.h) */
    struct render_window tile; /* --tile X Y W H: render only that rectangle of the picture (width 0: all) */
    const char *sets[SCENE_SET_MAX]; /* --set PATH=VALUE changes to the scene, in order */
    int set_count;
};

/* One run of a chapter program, from its command line to its exit status. */
struct cli_run {
    const struct chapter *chapter;
    struct cli_options options;
    struct scene scene;         /* the scene, holding only the kinds of shape the chapter draws */
    struct stats total;         /* the counters of the whole render (cli_render) */
    double render_seconds;
    char err[CLI_ERROR_SIZE];   /* where the chapter's own steps write why they failed, for cli_fail */
    int status;                 /* an enum cli_exit */
    bool scale_checked;         /* cli_check_scale has looked at the scene (it warns once a run) */
    /* Only in the browser (web/worker.js holds a chapter's instance across renders of one world, see
     * cli_render): called before each render after the first with the new camera, size, samples and tile
     * in the run, to redo what the chapter derived from them (NULL: nothing); returns false with the
     * reason printed and run->status set. Natively never called. */
    bool (*held_refresh)(struct cli_run *run, void *context);
    void *held_context;
};

/* Starts chapter `ch` with the command line argc/argv: parses the options (--threads N then holds for
 * every parallel part of the run, render_use_threads), reads the scene with the
 * chapter's kinds of shape (printing one line about those it ignores) and applies --set, --width and
 * --height. Unless --pov is given, bounds the rays the scene asks for (ray_budget.h): above
 * RAY_BUDGET_LARGE it says so on standard error (unless --quiet), above RAY_BUDGET_LIMIT it refuses the
 * scene (exit 1) unless --no-limit is given. Returns true when the chapter goes on with its own steps; false when the run is over:
 * --help was printed, or an error was (run->status says which). Either way, end with cli_finish. */
bool cli_start(struct cli_run *run, const struct chapter *ch, int argc, char **argv);

/* Whether `file`, which the option `option` writes, is a file the run reads: the scene file, or a
 * file the scene names and the chapter reads (a mesh's, an image map's, an object's), compared by
 * outfile_same_file. When so, prints "OPTION names 'FILE', which the run reads (the scene file):
 * writing it would destroy it; give another file" and returns true. cli_start checks the options'
 * own files; a chapter that derives more names from them (chapter 16's frames) checks those. */
bool cli_output_is_an_input(const struct cli_run *run, const char *option, const char *file);

/* The files a run reads, each looked at once (outfile_index), for a chapter that checks many names
 * against them: chapter 16's frames, whose names compared one by one with thousands of object files
 * kept a run from drawing its first frame for minutes. */
struct cli_inputs {
    const struct cli_run *run;
    const char **names;         /* owned array; the run's inputs in cli_output_is_an_input's order */
    struct outfile_index index; /* over `names` */
};

/* Looks at each file `run` reads once (the run must outlive `inputs`). Returns false when memory runs
 * out, after printing so. Either way, end with cli_inputs_free. */
bool cli_inputs_open(struct cli_inputs *inputs, const struct cli_run *run);

/* cli_output_is_an_input's answer and message for `file`, the inputs taken as cli_inputs_open found
 * them, at the cost of one look at `file`. */
bool cli_inputs_written(const struct cli_inputs *inputs, const char *option, const char *file);

/* Frees what cli_inputs_open took and leaves `inputs` empty. */
void cli_inputs_free(struct cli_inputs *inputs);

/* Ends the run with a failure of the chapter's own step (loading meshes, building its world), whose
 * message is in run->err: prints it and returns cli_finish's status, CLI_BAD_INPUT. */
int cli_fail(struct cli_run *run);

/* Warns on standard error (unless --quiet) when the scene is too small for the tracer's margins
 * (scene_scale.h), once a run: later calls do nothing. cli_render calls it; a chapter that lets go of
 * the scene's meshes after gathering them (chapter 11's rung 7) calls it first, while they are there. */
void cli_check_scale(struct cli_run *run);

/* cli_check_scale, then: with --pov, writes the
 * POV-Ray twin of the scene as the chapter lights it and returns false. Otherwise renders the picture,
 * tracing each pixel's primary ray with trace(world, ray), writes it (and the heat-map), prints where
 * it went and the counters (into run->total), and returns true when the chapter may add its own
 * report: the picture was written and --quiet not given. On failure sets run->status.
 * In the browser only (compiled with Emscripten, and the page asking for it), the run is then held: it
 * waits for the page's next command line and scene of the same world (only the camera and image lines,
 * --width, --height, --tile and the samples may differ), takes those into the run, and renders again,
 * over and over, never returning; the page drops the instance when the world changes. */
bool cli_render(struct cli_run *run, render_trace_fn trace, const void *world);

/* True when this run may be held for more renders (in the browser, when the page asks for it; natively
 * never): a chapter may then keep state across renders for held_refresh. */
bool cli_held(const struct cli_run *run);

/* cli_render with the pixels sampled by `sampler` (chapter 12's anti-aliasing, as the scene's antialias
 * line says) instead of one ray through each pixel centre; its heat-map shows the sampler's scale. */
bool cli_render_sampled(struct cli_run *run, render_trace_fn trace, const void *world,
                        const struct render_sampler *sampler);

/* Frees the run's scene and returns its exit status (an enum cli_exit). */
int cli_finish(struct cli_run *run);

#endif
