/* path_program.h: chapter 15's program after its command line, shared by chapter 17, which draws the
 * same paths with rough surfaces (docs/15-paths.md, docs/17-rough.md).
 *
 * The steps: chapter 14's textures and smooth meshes prepared, the area lights made emitting rectangles
 * (a point light, which has no area, is ignored with a note, as are the antialias line and a lens: each
 * path samples the pixel itself, through a pinhole), the world built at chapter 11's default rung, the
 * emitters gathered (a scene where nothing gives off light is refused: its picture would be black),
 * every pixel the mean of its paths (path_trace.h), the picture written tone-mapped, and with --hdr its
 * linear radiance (path_image.h); with --tile, only the tile. */
#ifndef WHITTED_PATH_PROGRAM_H
#define WHITTED_PATH_PROGRAM_H

#include "accel.h"
#include "cli.h"
#include "path_trace.h"

/* Runs the chapter started by cli_start(run, ...) (which returned true) with the world structure `choice`
 * asks for, and `surface` plugged into the path tracer (NULL: chapter 15's surfaces only). Returns the
 * program's exit status (cli_finish's, or cli_fail's when a step fails, its reason printed). */
int path_program_run(struct cli_run *run, const struct accel_choice *choice, const struct path_surface *surface);

#endif
