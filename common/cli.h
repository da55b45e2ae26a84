/* cli.h: what every chapter program shares: its options, reading the scene, rendering, writing the
 * picture and printing the counters (chapter 1).
 *
 * A chapter's main.c describes itself in a `struct chapter` (its number, default scene, which shapes it
 * draws, how it lights them, and its trace function) and hands over to cli_run. Exit codes:
 *   0  the picture (or POV-Ray twin) was written
 *   1  the scene or a mesh file is wrong (message: "file:line: what is wrong")
 *   2  the command line is wrong (message, then the usage): also an output name longer than the
 *      system takes, or -o and --heatmap naming one file
 *   3  the output file cannot be written (no such folder, disk or device full), or memory ran out
 *
 * `--heatmap FILE` works in every chapter: it writes how much work each pixel's camera ray cost
 * (node visits, box and shape tests, including those of its shadow and secondary rays) as a picture,
 * on one fixed colour scale so that pictures of different chapters can be set side by side. In
 * chapter 12 it shows how many camera rays each pixel took instead, on a scale of its own. */
#ifndef WHITTED_CLI_H
#define WHITTED_CLI_H

#include <stdbool.h>
#include <stddef.h>

#include "povray.h"
#include "render.h"
#include "scene.h"

enum cli_exit { CLI_OK = 0, CLI_BAD_INPUT = 1, CLI_USAGE = 2, CLI_OUTPUT_FAILED = 3 };

struct chapter {
    int number;                     /* 1 .. 10 */
    const char *title;              /* e.g. "camera" */
    const char *default_scene;      /* path used when no scene is given, relative to the repository */
    unsigned features;              /* the shapes drawn: a mask of enum scene_feature, or
                                       SCENE_EVERY_SHAPE for every kind introduced up to `number` */
    enum pov_lighting lighting;     /* what trace computes, for the POV-Ray twin */
    /* Optional: loads the mesh files of the scene (scene_load_meshes, from chapter 3 on). */
    bool (*load_meshes)(struct scene *s, char *err, size_t err_size);
    /* Optional: builds what trace needs from the scene (e.g. a BVH) and returns it as the `world`
     * given to trace; returns NULL and fills err on failure. Without it, the world is the scene. */
    void *(*prepare)(struct scene *s, char *err, size_t err_size);
    void (*release)(void *world);   /* frees what prepare returned; optional */
    render_trace_fn trace;          /* the colour seen along a primary ray */
    /* Optional (chapter 12): how the pixels are sampled with several rays each, as the scene's
     * antialias line says; NULL: one ray through each pixel centre. */
    const struct render_sampler *sampler;
    /* Optional: the chapter's own options. Called with an option the common parser does not know and
     * the word after it (NULL at the end); returns the number of words used (1 or 2), 0 when the
     * option is unknown, or -1 after printing why its value is wrong. */
    int (*parse_option)(const char *option, const char *value);
    const char *options_help;       /* lines describing those options for --help */
    /* Optional: prints what the chapter built (e.g. build time) after the counters; more with
     * `detailed` (the --stats option). */
    void (*report)(const void *world, const struct stats *total, double render_seconds, bool detailed);
};

/* Runs chapter `ch` with the command line argc/argv: parses the options (see --help), renders and
 * writes the picture, prints where it went and the counters. Returns an enum cli_exit code. */
int cli_run(const struct chapter *ch, int argc, char **argv);

#endif
