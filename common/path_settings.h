/* path_settings.h: the scene's `paths` line, how chapter 15 traces its paths (read from chapter 1 on,
 * drawn by chapter 15; docs/15-paths.md).
 *
 *   paths samples 64 seed 0 roulette 3 bounces 256 strategy mis sampler independent
 *
 * samples   paths per pixel (each through a random point of the pixel: a box filter of one pixel)
 * seed      chooses the random numbers; the same seed gives the same picture on any number of threads
 * roulette  the bounce from which Russian roulette may end a path (0: from the first)
 * bounces   the most bounces a path makes after the first surface (0: that surface's direct light only).
 *           The cap is a bias: it drops the light of longer paths, Le rho^(bounces + 2) / (1 - rho) in a
 *           white furnace of albedo rho, since roulette keeps a path with probability up to 0.95 and so
 *           cannot end the long paths of a bright room alone. The default 256 makes it under 2e-6 of the
 *           light for albedos up to 0.95 (docs/15-paths.md, "A path, not a tree")
 * strategy  how direct light is found: mis (next-event estimation and the scattered direction, weighed
 *           by the power heuristic), light (next-event estimation alone) or scatter (scattering alone)
 * sampler   how a pixel's paths draw their random numbers: independent (each path its own hashed
 *           stream) or sobol (the pixel's paths stratified together, a scrambled (0,2)-sequence,
 *           owen_sobol.h): both unbiased, sobol less noisy for the same paths (docs/15-paths.md)
 *
 * Like the antialias line (antialias.h) the settings are plain data read with every scene, so that any
 * chapter reads any scene; the chapters before 15 ignore them (scene_drop_unsupported). */
#ifndef WHITTED_PATH_SETTINGS_H
#define WHITTED_PATH_SETTINGS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "shape.h"

#define PATH_CHAPTER 15              /* the chapter that draws paths and emission */
#define PATH_DEFAULT_SAMPLES 16
#define PATH_DEFAULT_ROULETTE 3
#define PATH_DEFAULT_BOUNCES 256
#define PATH_MAX_SAMPLES 1048576     /* 2^20 paths a pixel: more than any picture here needs */
#define PATH_MAX_BOUNCES 4096

enum path_sampler {
    PATH_SAMPLER_INDEPENDENT, /* every number a hash of (pixel, sample, seed, its place in the path) */
    PATH_SAMPLER_SOBOL,       /* the pixel's samples stratified: Owen-scrambled (0,2)-sequences */
};

enum path_strategy {
    PATH_MIS,     /* next-event estimation and scattering, combined by the power heuristic */
    PATH_LIGHT,   /* next-event estimation only: emitters reached by scattering count only after a mirror */
    PATH_SCATTER, /* scattering only: no shadow rays towards the emitters */
};

struct path_settings {
    int samples;
    uint32_t seed;
    int roulette;
    int bounces;
    enum path_strategy strategy;
    enum path_sampler sampler;
    int line; /* the scene file's line, 0 when the scene has none (the defaults hold) */
};

/* The keys of the line: samples, seed, roulette, bounces, strategy and sampler (words). */
#define PATH_KEY_COUNT 6
extern const struct key_spec path_keys[PATH_KEY_COUNT];

/* Returns the settings a scene without a paths line has. */
struct path_settings path_settings_default(void);

/* Fills *p from the values read for path_keys (the parser's struct key_values); keys not given keep the
 * defaults. Returns false with the reason in why (without file and line: the parser adds them) for
 * samples not a whole number from 1 to PATH_MAX_SAMPLES, a seed not a whole number from 0 to 2^32 - 1,
 * roulette or bounces not a whole number from 0 to PATH_MAX_BOUNCES, or
 * an unknown strategy or sampler. */
bool path_settings_make(const struct key_values *kv, struct path_settings *p, char *why, size_t why_size);

/* Returns the strategy's name as the scene file spells it: "mis", "light" or "scatter". */
const char *path_strategy_name(enum path_strategy strategy);

/* Returns the sampler's name as the scene file spells it: "independent" or "sobol". */
const char *path_sampler_name(enum path_sampler sampler);

#endif
