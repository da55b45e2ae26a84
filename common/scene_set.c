/* scene_set.c: changing one value of a scene from the command line, `--set PATH=VALUE` (chapter 1).
 *
 * The change is made to the scene's text before it is parsed, so the value is checked by the parser
 * like any other and an error still names the scene file and line. PATH says which line and which
 * value:
 *   max_depth=1                     a directive with positional values: they are replaced
 *   camera.fov=30                   a key of the one line of that directive
 *   material.glass.ior=1.45         a key of the material with that name
 *   sphere.2.radius=0.5             a key of the 2nd line of that directive (lights and shapes)
 * VALUE's words replace the key's old value, all of it (its numbers, or its one word: eye=3 leaves
 * "eye 3", which the parser refuses, rather than eye 3 with the old y and z); a key the line does not
 * have is added to it, and
 * a positional directive the scene does not have (max_depth, say) is added as a new line, as is an
 * optional line with keys (antialias.samples=4 adds "antialias samples 4"). */
#include "scene_set.h"

#include "scene.h"
#include "shape.h"

#include <ctype.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SET_MAX_WORDS 64 /* words on the changed line; scene lines have at most 48 */

/* Writes the message into err; returns false. */
static bool set_fail(char *err, size_t err_size, const char *spec, const char *format, ...) {
    int used = snprintf(err, err_size, "--set %s: ", spec);
    if (used >= 0 && (size_t)used < err_size) {
        va_list args;
        va_start(args, format);
        vsnprintf(err + used, err_size - (size_t)used, format, args);
        va_end(args);
    }
    return false;
}

/* The characters that part words, as the scene's parser has them (scene.c): a line's words are found
 * here as the parser finds them, so that --set changes the line the parser reads as that line. */
#define SET_BLANKS " \t\r\v\f"

static bool is_blank(char c) { return c != '\0' && strchr(SET_BLANKS, c) != NULL; }

/* Splits `text` in place into words at blanks; returns the count (at most max), or -1 if more. */
static int split_words(char *text, char **words, int max) {
    int count = 0;
    for (char *cursor = strtok(text, SET_BLANKS); cursor != NULL; cursor = strtok(NULL, SET_BLANKS)) {
        if (count == max)
            return -1;
        words[count++] = cursor;
    }
    return count;
}

/* Where a line lies in a text: the offset of its first byte, and its length without the newline. */
struct line_span {
    size_t start, length;
};

/* Finds the line the path names. `directive`, then either nothing, a material's name or an ordinal.
 * Returns the line's span in *found, or false (with found->start = SIZE_MAX when there is none). */
static bool find_line(const char *text, const char *directive, const char *name, int ordinal,
                      struct line_span *found) {
    int seen = 0;
    size_t directive_length = strlen(directive);
    /* A byte-order mark before the first line is no part of it, as for the reader (scene.c). */
    size_t first = strncmp(text, SCENE_UTF8_BOM, strlen(SCENE_UTF8_BOM)) == 0 ? strlen(SCENE_UTF8_BOM) : 0;
    for (size_t start = first; text[start] != '\0';) {
        const char *line = text + start;
        const char *end = strchr(line, '\n');
        size_t length = end != NULL ? (size_t)(end - line) : strlen(line);
        const char *word = line;
        while (is_blank(*word))
            word++;
        bool match = strncmp(word, directive, directive_length) == 0 &&
                     (is_blank(word[directive_length]) || word[directive_length] == '#' ||
                      word + directive_length == line + length);
        if (match && name != NULL) {
            const char *second = word + directive_length;
            while (is_blank(*second))
                second++;
            size_t name_length = strlen(name);
            match = strncmp(second, name, name_length) == 0 &&
                    (is_blank(second[name_length]) || second[name_length] == '\n' || second[name_length] == '#' ||
                     second[name_length] == '\0');
        }
        if (match && ++seen == (ordinal > 0 ? ordinal : 1)) {
            *found = (struct line_span){start, length};
            return true;
        }
        start += length + (end != NULL ? 1 : 0);
    }
    found->start = (size_t)-1;
    return false;
}

/* Returns true when the whole of word reads as a number. */
static bool is_number_word(const char *word) {
    char *end;
    strtod(word, &end);
    return end != word && *end == '\0';
}

/* Returns how many of the words after words[key_at] are the key's old value: its numbers (a key has at
 * most KEY_MAX_NUMBERS), or else one word (a name such as a material's). */
static int old_value_count(char **words, int count, int key_at) {
    int numbers = 0;
    while (numbers < KEY_MAX_NUMBERS && key_at + 1 + numbers < count && is_number_word(words[key_at + 1 + numbers]))
        numbers++;
    return numbers > 0 ? numbers : (key_at + 1 < count ? 1 : 0);
}

/* Whether word can be a key's name: a letter, then letters, digits or '_' (never a number, nor a value
 * such as a file's name). */
static bool is_key_name(const char *word) {
    if (!isalpha((unsigned char)word[0]))
        return false;
    for (const char *c = word; *c != '\0'; c++)
        if (!isalnum((unsigned char)*c) && *c != '_')
            return false;
    return true;
}

/* How many words open a line of `directive` before its keys: the directive itself, and its positional
 * words (a material's name; a pigment's name and pattern; a mesh's file; an object's name and file; an
 * instance's object; a key's instance label). */
static int words_before_keys(const char *directive) {
    if (strcmp(directive, "pigment") == 0 || strcmp(directive, "object") == 0)
        return 3;
    if (strcmp(directive, "material") == 0 || strcmp(directive, "mesh") == 0 || strcmp(directive, "instance") == 0 ||
        strcmp(directive, "key") == 0)
        return 2;
    return 1;
}

/* Rewrites one line: `words` (count of them, the comment in `comment`) with `key` given `values`. The
 * key is looked for only where keys stand: from words[fixed] on, each key followed by its old value,
 * so that a value (a number, a name) is never taken for the key. With key NULL, everything after the
 * first `fixed` words is replaced by the values. Returns a new string, or NULL when out of memory. */
static char *rewrite_line(char **words, int count, int fixed, const char *key, char **values, int value_count,
                          const char *comment) {
    size_t size = strlen(comment) + 2;
    for (int k = 0; k < count; k++)
        size += strlen(words[k]) + 1;
    for (int k = 0; k < value_count; k++)
        size += strlen(values[k]) + 1;
    size += key != NULL ? strlen(key) + 1 : 0;
    char *line = malloc(size), *o = line;
    if (line == NULL)
        return NULL;
    int key_at = -1;
    if (key != NULL)
        for (int k = fixed; k < count && key_at < 0; k += 1 + old_value_count(words, count, k))
            if (strcmp(words[k], key) == 0)
                key_at = k;
    int old_count = key_at >= 0 ? old_value_count(words, count, key_at) : 0;
    int keep = key == NULL ? fixed : count;
    for (int k = 0; k < keep; k++) {
        if (key_at >= 0 && k > key_at && k <= key_at + old_count)
            continue; /* an old value of the key */
        o += sprintf(o, "%s%s", o == line ? "" : " ", words[k]);
        if (k == key_at)
            for (int v = 0; v < value_count; v++)
                o += sprintf(o, " %s", values[v]);
    }
    if (key == NULL || key_at < 0) {
        if (key != NULL)
            o += sprintf(o, " %s", key);
        for (int v = 0; v < value_count; v++)
            o += sprintf(o, " %s", values[v]);
    }
    sprintf(o, "%s%s", comment[0] != '\0' ? "  " : "", comment);
    return line;
}

/* Directives with keys that a scene may leave out altogether (their defaults hold): --set on one of
 * their keys adds the line when the scene has none. */
static bool is_optional_line(const char *directive) {
    return strcmp(directive, "antialias") == 0 || strcmp(directive, "paths") == 0;
}

/* Directives whose values are positional (no keys). */
static bool is_positional(const char *directive) {
    static const char *const positional[] = {"image", "background", "ambient_light", "max_depth", "shadow_offset",
                                             "adc_bailout"};
    for (size_t k = 0; k < sizeof positional / sizeof positional[0]; k++)
        if (strcmp(directive, positional[k]) == 0)
            return true;
    return false;
}

/* Reads a line number: digits only (no sign, no spaces, nothing after them), at most INT_MAX. */
static bool parse_ordinal(const char *digits, int *ordinal) {
    long value = 0;
    for (const char *c = digits; *c != '\0'; c++) {
        if (!isdigit((unsigned char)*c) || value > (INT_MAX - (*c - '0')) / 10)
            return false;
        value = value * 10 + (*c - '0');
    }
    *ordinal = (int)value;
    return *digits != '\0';
}

bool scene_set_apply(char **text, const char *spec, char *err, size_t err_size) {
    char path[256], value[512];
    const char *equals = strchr(spec, '=');
    if (equals == NULL || equals == spec)
        return set_fail(err, err_size, spec, "expected PATH=VALUE, e.g. max_depth=1 or camera.fov=30");
    if ((size_t)(equals - spec) >= sizeof path)
        return set_fail(err, err_size, spec, "PATH is longer than %zu bytes", sizeof path - 1);
    if (strlen(equals + 1) >= sizeof value)
        return set_fail(err, err_size, spec, "VALUE is longer than %zu bytes", sizeof value - 1);
    snprintf(path, sizeof path, "%.*s", (int)(equals - spec), spec);
    for (const char *c = path; *c != '\0'; c++)
        if (isspace((unsigned char)*c) || *c == '#')
            return set_fail(err, err_size, spec, "PATH may not contain blanks, '#' or a line break");
    snprintf(value, sizeof value, "%s", equals + 1);
    char *values[SET_MAX_WORDS];
    int value_count = split_words(value, values, SET_MAX_WORDS);
    if (value_count < 0)
        return set_fail(err, err_size, spec, "VALUE has more than %d words", SET_MAX_WORDS);
    if (value_count == 0)
        return set_fail(err, err_size, spec, "no value after '='");
    for (int k = 0; k < value_count; k++)
        if (strchr(values[k], '#') != NULL || strchr(values[k], '\n') != NULL)
            return set_fail(err, err_size, spec, "a value may not contain '#' or a line break");

    /* PATH = directive [. name-or-ordinal] [. key]; strtok below would skip an empty part */
    size_t length = strlen(path);
    if (path[0] == '.' || path[length - 1] == '.' || strstr(path, "..") != NULL)
        return set_fail(err, err_size, spec, "PATH has an empty part (a dot at an end, or two together)");
    char *parts[3] = {NULL, NULL, NULL};
    int part_count = 0;
    for (char *part = strtok(path, "."); part != NULL; part = strtok(NULL, "."))
        if (part_count < 3)
            parts[part_count++] = part;
        else
            return set_fail(err, err_size, spec, "PATH has more than three parts");
    const char *directive = parts[0], *name = NULL, *key = NULL;
    int ordinal = 0;
    if (part_count == 3) {
        if (isdigit((unsigned char)parts[1][0])) {
            if (!parse_ordinal(parts[1], &ordinal))
                return set_fail(err, err_size, spec, "'%s' is not a line number (digits only, at most %d)", parts[1],
                                INT_MAX);
        } else {
            name = parts[1];
        }
        key = parts[2];
    } else if (part_count == 2) {
        key = parts[1];
    }
    bool positional = is_positional(directive);
    if (positional && key != NULL)
        return set_fail(err, err_size, spec, "%s takes its values directly: write %s=VALUE", directive, directive);
    if (!positional && key == NULL)
        return set_fail(err, err_size, spec, "say which key of the %s line, e.g. %s.KEY=VALUE", directive, directive);
    if (part_count == 3 && name == NULL && ordinal < 1)
        return set_fail(err, err_size, spec, "line numbers count from 1 (%s.1 is the first %s line)", directive,
                        directive);
    if (key != NULL && !is_key_name(key))
        return set_fail(err, err_size, spec, "'%s' is not a key's name (a letter, then letters, digits or '_')", key);
    if (name != NULL && strcmp(directive, "material") != 0)
        return set_fail(err, err_size, spec, "only materials have names; use %s.N for the Nth %s line", directive,
                        directive);

    struct line_span span;
    char *changed = NULL;
    if (!find_line(*text, directive, name, ordinal, &span)) {
        if (!positional && !(is_optional_line(directive) && part_count == 2)) {
            if (name != NULL)
                return set_fail(err, err_size, spec, "the scene has no material called '%s'", name);
            if (ordinal > 0)
                return set_fail(err, err_size, spec, "the scene has fewer than %d %s lines", ordinal, directive);
            return set_fail(err, err_size, spec, "the scene has no %s line", directive);
        }
        /* A directive the scene leaves at its defaults: add the line at the end (with the key, for an
         * optional line with keys). */
        size_t old = strlen(*text);
        changed = malloc(old + strlen(directive) + (key != NULL ? strlen(key) + 1 : 0) + strlen(equals + 1) + 4);
        if (changed == NULL)
            return set_fail(err, err_size, spec, "out of memory");
        sprintf(changed, "%s%s%s%s%s %s\n", *text, old > 0 && (*text)[old - 1] != '\n' ? "\n" : "", directive,
                key != NULL ? " " : "", key != NULL ? key : "", equals + 1);
    } else {
        char *line = malloc(span.length + 1);
        if (line == NULL)
            return set_fail(err, err_size, spec, "out of memory");
        memcpy(line, *text + span.start, span.length);
        line[span.length] = '\0';
        char *hash = strchr(line, '#');
        char comment[512] = "";
        if (hash != NULL) {
            snprintf(comment, sizeof comment, "%s", hash);
            *hash = '\0';
        }
        char *words[SET_MAX_WORDS];
        int count = split_words(line, words, SET_MAX_WORDS);
        if (count < 0) {
            free(line);
            return set_fail(err, err_size, spec, "the %s line it changes has more than %d words", directive,
                            SET_MAX_WORDS);
        }
        char *rewritten = rewrite_line(words, count, positional ? 1 : words_before_keys(directive), key, values,
                                       value_count, comment);
        free(line);
        if (rewritten == NULL)
            return set_fail(err, err_size, spec, "out of memory");
        size_t old = strlen(*text), new_length = strlen(rewritten);
        changed = malloc(old - span.length + new_length + 1);
        if (changed != NULL) {
            memcpy(changed, *text, span.start);
            memcpy(changed + span.start, rewritten, new_length);
            strcpy(changed + span.start + new_length, *text + span.start + span.length);
        }
        free(rewritten);
        if (changed == NULL)
            return set_fail(err, err_size, spec, "out of memory");
    }
    free(*text);
    *text = changed;
    return true;
}

/* Line `number` of text (1 for the first), without its newline, in *found. Returns false when text has
 * fewer lines. */
static bool line_of_text(const char *text, long number, struct line_span *found) {
    const char *line = text;
    for (long at = 1; at < number; at++) {
        line = strchr(line, '\n');
        if (line == NULL)
            return false;
        line++;
    }
    if (*line == '\0')
        return false;
    *found = (struct line_span){(size_t)(line - text), strcspn(line, "\n")};
    return true;
}

/* Whether err, a parse error of the scene at `path` ("path:LINE: what is wrong"), points at a line that
 * the changes made: a line whose text differs between before and after, or one added after the
 * scene's last. An error that names no line of this file is at none. */
static bool error_at_changed_line(const char *err, const char *path, const char *before, const char *after) {
    size_t n = strlen(path);
    if (strncmp(err, path, n) != 0 || err[n] != ':' || !isdigit((unsigned char)err[n + 1]))
        return false;
    char *end;
    long line = strtol(err + n + 1, &end, 10);
    if (*end != ':')
        return false;
    struct line_span old_line, new_line;
    if (!line_of_text(after, line, &new_line))
        return false;
    if (!line_of_text(before, line, &old_line))
        return true; /* a line the changes added */
    return old_line.length != new_line.length ||
           memcmp(before + old_line.start, after + new_line.start, old_line.length) != 0;
}

bool scene_load_changed(const char *path, const char *const *specs, int count, const struct shape_kind *const *kinds,
                        struct scene *s, bool *bad_spec, char *err, size_t err_size) {
    memset(s, 0, sizeof *s);
    *bad_spec = false;
    char *text = scene_read_text(path, err, err_size);
    if (text == NULL)
        return false;
    char *original = count > 0 ? strdup(text) : NULL;
    if (count > 0 && original == NULL) {
        free(text);
        snprintf(err, err_size, "%s: out of memory", path);
        return false;
    }
    for (int k = 0; k < count; k++)
        if (!scene_set_apply(&text, specs[k], err, err_size)) {
            free(text);
            free(original);
            *bad_spec = true;
            return false;
        }
    bool ok = scene_parse(path, text, kinds, s, err, err_size);
    size_t used = strlen(err);
    /* The file's own line may not show the bad value: say so where the error is at a changed line. */
    if (!ok && count > 0 && used + 1 < err_size && error_at_changed_line(err, path, original, text))
        snprintf(err + used, err_size - used, " (the line as changed by --set)");
    free(text);
    free(original);
    return ok;
}
