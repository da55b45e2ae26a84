/* antialias.c: the scene's antialias line: its keys, its checks and its POV-Ray options (read from
 * chapter 1 on, drawn by chapter 12; docs/12-antialias.md). */
#include "antialias.h"

#include <math.h>
#include <string.h>

enum { KEY_METHOD, KEY_SAMPLES, KEY_THRESHOLD, KEY_SEED };

const struct key_spec antialias_keys[ANTIALIAS_KEY_COUNT] = {
    [KEY_METHOD] = {"method", 0}, [KEY_SAMPLES] = {"samples", 1}, [KEY_THRESHOLD] = {"threshold", 1},
    [KEY_SEED] = {"seed", 1}};

static const char *const method_names[] = {
    [ANTIALIAS_NONE] = "none",         [ANTIALIAS_GRID] = "grid",         [ANTIALIAS_JITTER] = "jitter",
    [ANTIALIAS_ADAPTIVE] = "adaptive", [ANTIALIAS_RECURSIVE] = "recursive",
};
#define METHOD_COUNT (sizeof method_names / sizeof method_names[0])

const char *antialias_method_name(enum antialias_method method) { return method_names[method]; }

/* True when x is a whole number in [lo, hi]. */
static bool whole_in(double x, double lo, double hi) { return x >= lo && x <= hi && x == floor(x); }

bool antialias_make(const struct key_values *kv, struct antialias *a, char *why, size_t why_size) {
    *a = (struct antialias){ANTIALIAS_GRID, ANTIALIAS_DEFAULT_SAMPLES, ANTIALIAS_DEFAULT_THRESHOLD, 0, 0};
    if (kv->present[KEY_METHOD]) {
        size_t m = 0;
        while (m < METHOD_COUNT && strcmp(kv->word[KEY_METHOD], method_names[m]) != 0)
            m++;
        if (m == METHOD_COUNT) {
            snprintf(why, why_size, "unknown antialias method '%s' (none, grid, jitter, adaptive or recursive)",
                     kv->word[KEY_METHOD]);
            return false;
        }
        a->method = (enum antialias_method)m;
    }
    int most = a->method == ANTIALIAS_RECURSIVE  ? ANTIALIAS_MAX_DEPTH
               : a->method == ANTIALIAS_ADAPTIVE ? ANTIALIAS_MAX_ADAPTIVE
                                                 : ANTIALIAS_MAX_SAMPLES;
    if (kv->present[KEY_SAMPLES]) {
        double n = kv->number[KEY_SAMPLES][0];
        if (!whole_in(n, 1, most)) {
            snprintf(why, why_size,
                     "antialias samples must be a whole number from 1 to %d for method %s, got " KEY_NUMBER_SHOWN,
                     most, method_names[a->method], KEY_NUMBER(n));
            return false;
        }
        a->samples = (int)n;
    }
    if (kv->present[KEY_THRESHOLD]) {
        double t = kv->number[KEY_THRESHOLD][0];
        if (!(t >= 0.0 && t <= ANTIALIAS_MAX_THRESHOLD)) {
            snprintf(why, why_size, "antialias threshold must be between 0 and %g, got " KEY_NUMBER_SHOWN,
                     ANTIALIAS_MAX_THRESHOLD, KEY_NUMBER(t));
            return false;
        }
        a->threshold = t;
    }
    if (kv->present[KEY_SEED]) {
        double seed = kv->number[KEY_SEED][0];
        if (!whole_in(seed, 0, UINT32_MAX)) {
            snprintf(why, why_size, "antialias seed must be a whole number from 0 to %u, got " KEY_NUMBER_SHOWN,
                     UINT32_MAX, KEY_NUMBER(seed));
            return false;
        }
        a->seed = (uint32_t)seed;
    }
    return true;
}

int antialias_box(const struct antialias *a) {
    return a->method == ANTIALIAS_GRID || a->method == ANTIALIAS_JITTER ? a->samples : 1;
}

void antialias_povray_options(const struct antialias *a, char *out, size_t out_size) {
    if (a->method != ANTIALIAS_ADAPTIVE && a->method != ANTIALIAS_RECURSIVE) {
        snprintf(out, out_size, "%s", "");
        return;
    }
    /* Every setting the rule depends on is spelled out, defaults included, so that a change of
     * POV-Ray's defaults cannot change the twin's picture unnoticed. */
    snprintf(out, out_size,
             "Antialias=on Sampling_Method=%d Antialias_Threshold=%.17g Antialias_Depth=%d Jitter=off "
             "Antialias_Gamma=%g Render_Block_Size=%d",
             a->method == ANTIALIAS_ADAPTIVE ? 1 : 2, a->threshold, a->samples, ANTIALIAS_GAMMA, ANTIALIAS_BLOCK);
}

void antialias_write_pov(FILE *out, const struct antialias *a) {
    char options[512];
    antialias_povray_options(a, options, sizeof options);
    if (options[0] != '\0')
        fprintf(out, "// Antialias options: %s\n", options);
    else if (a->method != ANTIALIAS_NONE)
        fprintf(out, "// Antialias box: %d (render %d times as wide and high with one ray a pixel, then average "
                "each %d x %d block)\n", a->samples, a->samples, a->samples, a->samples);
}
