/* render_check.h: one scene text taken through the whole renderer of chapter 10, the sampled and path
 * tracers of chapters 12 to 15, chapter 16's instances and chapter 17's rough surfaces, and checked, for
 * the renderer fuzzer (fuzz/fuzz_render.c) and for its regression tests (tests/test_fuzz_regressions.c).
 *
 * Not part of any chapter: the chapters' programs never call it. */
#ifndef WHITTED_RENDER_CHECK_H
#define WHITTED_RENDER_CHECK_H

#include <stdbool.h>
#include <stddef.h>

/* Limits that keep one fuzz input cheap whatever the text asks for. The picture is cut to at most
 * RENDER_CHECK_MAX_WIDTH x RENDER_CHECK_MAX_HEIGHT pixels (12 camera rays) and max_depth to at most
 * RENDER_CHECK_MAX_DEPTH, so a ray tree has at most 2^(depth - 1) reflected and refracted rays per
 * pixel before shadow rays: a few thousand rays per input. */
#define RENDER_CHECK_MAX_WIDTH 4
#define RENDER_CHECK_MAX_HEIGHT 3
#define RENDER_CHECK_MAX_DEPTH 4

/* Parses `text` (zero-terminated) as a scene named `name`; gives every `mesh` directive one of a few
 * tiny meshes made in memory (chosen by its file name, so no file is opened) placed by its transform;
 * builds the brute-force world and the four structures (kd-tree with the seed's rule and the SAH, BVH
 * with the median and the SAH); traces the camera rays of the capped picture in every world. Checks:
 * a refused scene's message starts with "name:"; each structure keeps its invariants (kdtree_is_valid,
 * bvh_is_valid, on small scenes); every hit is at a finite t with a finite normal; on the camera rays
 * and the shadow rays of their hits, each structure's closest, occluded and for-each-hit queries give
 * exactly the brute-force loop's answer, and every world's nearest hit and crossings are the
 * brute-force world's; whitted_trace sees the same colour in every world (to
 * RENDER_CHECK_COLOUR_TOLERANCE, render_check.c says why not exactly). The exact checks take only rays
 * starting near the triangles, where exactness is promised (RENDER_CHECK_NEAR_SIZES). Every trace is
 * painted by chapter 14's textures (each image map's file replaced by a tiny image made in the same
 * folder as the meshes). Then, on a picture of at most 2 x 2 pixels with every count that multiplies
 * the work cut (render_check.c lists the limits), chapters 12 to 14's sampled tracer (the antialias
 * line, the lens, soft shadows of area lights) and chapter 15's path tracer (area lights made emitting
 * rectangles) must see the same colours in the brute-force world and one structure's, chosen by a
 * hash of the text; and every path-traced pixel must be finite; when a material is rough, the same
 * again with chapter 17's rough surfaces, in both their forms. When the scene has instance lines,
 * chapter 16's two-level structure (every object line's file replaced by a tiny mesh, placed over the
 * shutter, then refitted to the last frame) must give the nearest hit and the crossings that the same instances give with no top
 * level, every one tested by every ray, on the small picture's camera rays and on rays towards the
 * first instances, at the start, middle and end of each interval, when the eye lies near the instances;
 * a refusal of the instances must name the scene.
 * Returns RENDER_CHECK_PASSED when all hold (a cleanly refused scene passes); RENDER_CHECK_FAILED with
 * the first broken check described in why (why_size bytes); or RENDER_CHECK_KNOWN_DEFECT, without
 * building or tracing anything, when the scene has what triggers a defect being fixed (render_check.c
 * lists them), with the defect named in why. Frees everything it allocates. A crash or a hang inside
 * the renderer is not caught: that is for the sanitizers and the fuzzer's time limit to report. */
enum render_check_result { RENDER_CHECK_PASSED, RENDER_CHECK_FAILED, RENDER_CHECK_KNOWN_DEFECT };
enum render_check_result render_check_scene(const char *name, const char *text, char *why, size_t why_size);

#endif
