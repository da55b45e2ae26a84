/* scene_set.h: changing one value of a scene from the command line, `--set PATH=VALUE` (chapter 1).
 *
 * So that an exercise ("what if the glass had ior 1.45?") is one command, with no copy of the scene to
 * make and no mesh paths to fix: ./build/chapter-08 --set material.glass.ior=1.45 */
#ifndef WHITTED_SCENE_SET_H
#define WHITTED_SCENE_SET_H

#include <stdbool.h>
#include <stddef.h>

/* The most --set options one run takes. */
#define SCENE_SET_MAX 16

/* Applies one `PATH=VALUE` change (forms in scene_set.c and docs/scene-format.md) to the scene text
 * *text, which must be a malloc'd string: on success *text is replaced by a new malloc'd string (the
 * old one freed) and true is returned. Lines keep their numbers, so parse errors still point at the
 * scene file's line. On failure *text is unchanged, false is returned and err holds
 * "--set PATH=VALUE: what is wrong". The value itself is not checked here: the parser checks it. */
bool scene_set_apply(char **text, const char *spec, char *err, size_t err_size);

/* Loads the scene at `path` as scene_load does (with the kinds of shape `kinds`, ending with NULL), with
 * the `count` changes specs[] applied to its text first. Returns true on success (free *s with
 * scene_free). On failure returns false with the message in err, and sets *bad_spec when a change
 * itself was wrong (a command-line error), not the scene. A parse error at a line the changes made
 * (rewritten or added) ends "(the line as changed by --set)"; one at a line they left alone does not. */
struct scene;
struct shape_kind;
bool scene_load_changed(const char *path, const char *const *specs, int count, const struct shape_kind *const *kinds,
                        struct scene *s, bool *bad_spec, char *err, size_t err_size);

#endif
