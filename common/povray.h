/* povray.h: writes a scene as POV-Ray 3.7 scene language, the independent oracle (chapter 1).
 *
 * Every chapter can write the POV-Ray "twin" of what it draws (`--pov FILE`): the same camera, the
 * same shapes, and lighting that makes POV-Ray compute exactly the chapter's shading formula. The
 * rules were measured against POV-Ray and are explained in docs/povray.md. Twins are generated,
 * never edited by hand, so they cannot drift from the scene files. */
#ifndef WHITTED_POVRAY_H
#define WHITTED_POVRAY_H

#include <stdbool.h>
#include <stddef.h>

#include "scene.h"

/* The lighting a chapter computes, from the simplest to the full Whitted model. */
enum pov_lighting {
    POV_RAY_DIRECTION,  /* chapter 1: colour = 0.5 + 0.5 * ray direction, no shapes */
    POV_HEADLIGHT,      /* chapters 2-5: white light at the eye, diffuse only */
    POV_PHONG,          /* chapter 6: ambient + diffuse + Phong highlight, no shadows */
    POV_PHONG_SHADOWS,  /* chapter 7: the same with opaque shadows */
    POV_WHITTED,        /* chapters 8-10: shadows filtered by glass, reflection, refraction */
};

/* The POV-Ray options that make its output comparable with ours: one ray per pixel centre (-A), linear
 * 8-bit output rounded like image_quantize (File_Gamma=1.0, Dither off, +FN8), no display, quiet. */
#define POVRAY_OPTIONS "-D -P -V -A +FN8 -UA File_Gamma=1.0 Dither=off +Q9 -GA +GF"

/* Returns true when POV-Ray can draw scene s as a chapter with `lighting` draws it. Otherwise writes
 * "scene: feature has no POV-Ray equivalent" into err and returns false (only `shadow_offset off`,
 * from chapter 7 on, has none). */
bool povray_can_express(const struct scene *s, enum pov_lighting lighting, char *err, size_t err_size);

/* Writes the twin of scene `s` as drawn under `lighting` to `path` (via a temporary file renamed into
 * place). Meshes must already be loaded if the chapter draws them. Returns false and writes
 * "path: reason" into err if the file cannot be written, or povray_can_express's message. */
bool povray_write_scene(const struct scene *s, enum pov_lighting lighting, const char *path, char *err,
                        size_t err_size);

#endif
