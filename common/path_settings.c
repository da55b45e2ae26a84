/* path_settings.c: the scene's paths line: its keys and its checks (read from chapter 1 on, drawn by
 * chapter 15; docs/15-paths.md). */
#include "path_settings.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { KEY_SAMPLES, KEY_SEED, KEY_ROULETTE, KEY_BOUNCES, KEY_STRATEGY, KEY_SAMPLER };

const struct key_spec path_keys[PATH_KEY_COUNT] = {
    [KEY_SAMPLES] = {"samples", 1}, [KEY_SEED] = {"seed", 1}, [KEY_ROULETTE] = {"roulette", 1},
    [KEY_BOUNCES] = {"bounces", 1}, [KEY_STRATEGY] = {"strategy", 0}, [KEY_SAMPLER] = {"sampler", 0}};

static const char *const strategy_names[] = {[PATH_MIS] = "mis", [PATH_LIGHT] = "light", [PATH_SCATTER] = "scatter"};
#define STRATEGY_COUNT (sizeof strategy_names / sizeof strategy_names[0])
static const char *const sampler_names[] = {[PATH_SAMPLER_INDEPENDENT] = "independent", [PATH_SAMPLER_SOBOL] = "sobol"};
#define SAMPLER_COUNT (sizeof sampler_names / sizeof sampler_names[0])

const char *path_strategy_name(enum path_strategy strategy) { return strategy_names[strategy]; }

const char *path_sampler_name(enum path_sampler sampler) { return sampler_names[sampler]; }

struct path_settings path_settings_default(void) {
    return (struct path_settings){PATH_DEFAULT_SAMPLES, 0, PATH_DEFAULT_ROULETTE, PATH_DEFAULT_BOUNCES, PATH_MIS,
                                  PATH_SAMPLER_INDEPENDENT, 0};
}

/* Reads word key `key` as one of the count names into *index (left as it is when the key is absent); false
 * with the reason in why for another word ("unknown paths WHAT 'word' (choices)"). */
static bool word_key(const struct key_values *kv, int key, const char *const *names, size_t count, const char *what,
                     const char *choices, int *index, char *why, size_t why_size) {
    if (!kv->present[key])
        return true;
    size_t k = 0;
    while (k < count && strcmp(kv->word[key], names[k]) != 0)
        k++;
    if (k == count) {
        snprintf(why, why_size, "unknown paths %s '%s' (%s)", what, kv->word[key], choices);
        return false;
    }
    *index = (int)k;
    return true;
}

/* Reads key `key` as a whole number in [lo, hi] into *out; false with the reason in why otherwise. */
static bool whole_key(const struct key_values *kv, int key, double lo, double hi, double *out, char *why,
                      size_t why_size) {
    if (!kv->present[key])
        return true;
    double x = kv->number[key][0];
    if (!(x >= lo && x <= hi && x == floor(x))) {
        snprintf(why, why_size, "paths %s must be a whole number from %.0f to %.0f, got " KEY_NUMBER_SHOWN,
                 path_keys[key].name, lo, hi, KEY_NUMBER(x));
        return false;
    }
    *out = x;
    return true;
}

bool path_settings_make(const struct key_values *kv, struct path_settings *p, char *why, size_t why_size) {
    *p = path_settings_default();
    double samples = p->samples, seed = p->seed, roulette = p->roulette, bounces = p->bounces;
    if (!whole_key(kv, KEY_SAMPLES, 1, PATH_MAX_SAMPLES, &samples, why, why_size) ||
        !whole_key(kv, KEY_SEED, 0, UINT32_MAX, &seed, why, why_size) ||
        !whole_key(kv, KEY_ROULETTE, 0, PATH_MAX_BOUNCES, &roulette, why, why_size) ||
        !whole_key(kv, KEY_BOUNCES, 0, PATH_MAX_BOUNCES, &bounces, why, why_size))
        return false;
    p->samples = (int)samples;
    p->seed = (uint32_t)seed;
    p->roulette = (int)roulette;
    p->bounces = (int)bounces;
    int strategy = p->strategy, sampler = p->sampler;
    if (!word_key(kv, KEY_STRATEGY, strategy_names, STRATEGY_COUNT, "strategy", "mis, light or scatter", &strategy,
                  why, why_size) ||
        !word_key(kv, KEY_SAMPLER, sampler_names, SAMPLER_COUNT, "sampler", "independent or sobol", &sampler, why,
                  why_size))
        return false;
    p->strategy = (enum path_strategy)strategy;
    p->sampler = (enum path_sampler)sampler;
    return true;
}
