/* scene.c: the scene file parser, one directive per line (chapter 1; format in docs/scene-format.md).
 *
 * Each line is a directive name, perhaps a positional argument (a material's name, a mesh's file, the
 * image size, a colour), then `key value...` pairs in any order. Parsing is table-driven: every
 * directive lists its keys and how many numbers each takes, and one routine reads any line against its
 * table. Every error names the file and line, and nothing half-parsed escapes: on error the scene is
 * freed and left empty. */
#include "scene.h"

#include "box.h"
#include "camera.h"
#include "image.h"
#include "infile.h"
#include "name_index.h"
#include "plane.h"
#include "sphere.h"
#include "text_escape.h"
#include "triangle.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define LINE_MAX_TOKENS 48      /* the longest directive (a triangle with material) needs 13 */
#define SCENE_FILE_MAX_BYTES (64L * 1024 * 1024) /* scene files are small; meshes live elsewhere */
#define MAX_DEPTH_LIMIT 64      /* deeper recursion adds nothing visible and only costs time */
#define DEFAULT_MAX_DEPTH 5     /* POV-Ray's default max_trace_level */
#define DEFAULT_ADC_BAILOUT (1.0 / 255.0) /* POV-Ray's default: one level of an 8-bit pixel */

/* Where we are while parsing: for messages. */
struct parser {
    const char *name;
    int line;
    char *err;
    size_t err_size;
    struct name_index *materials; /* material name -> its index in scene.materials */
    struct name_index *pigments;  /* pigment name -> its index in scene.pigments */
    struct name_index *objects;   /* object name -> its index in scene.objects */
    struct name_index *ids;       /* instance id -> its index in scene.instances */
};

/* Writes "name:line: message" into the error buffer and returns false, so callers can
 * `return fail(p, ...)`. */
static bool fail(const struct parser *p, const char *format, ...) __attribute__((format(printf, 2, 3)));
static bool fail(const struct parser *p, const char *format, ...) {
    int used = snprintf(p->err, p->err_size, "%s:%d: ", p->name, p->line);
    if (used < 0 || (size_t)used >= p->err_size)
        return false;
    va_list args;
    va_start(args, format);
    vsnprintf(p->err + used, p->err_size - (size_t)used, format, args);
    va_end(args);
    return false;
}

/* ---- numbers ----------------------------------------------------------------------------------- */

/* A number is decimal, with an exponent or not (docs/scene-format.md), as POV-Ray reads it: strtod
 * would also take C's hexadecimal (0x28, 0x1p5), which a POV-Ray twin of the scene could not hold. */
static bool parse_number(const struct parser *p, const char *token, const char *what, double *out) {
    char *end = NULL;
    errno = 0;
    double value = strtod(token, &end);
    if (end == token || *end != '\0' || strpbrk(token, "xX") != NULL)
        return fail(p, "expected a number for '%s', got '%s'", what, token);
    if (!isfinite(value)) /* ERANGE alone may be a harmless underflow to a tiny number */
        return fail(p, "'%s' is not a finite number (for '%s')", token, what);
    *out = value;
    return true;
}

static bool parse_int(const struct parser *p, const char *token, const char *what, long lo, long hi,
                      int *out) {
    char *end = NULL;
    errno = 0;
    long value = strtol(token, &end, 10);
    if (end == token || *end != '\0' || errno == ERANGE)
        return fail(p, "expected a whole number for '%s', got '%s'", what, token);
    if (value < lo || value > hi)
        return fail(p, "'%s' must be between %ld and %ld, got %ld", what, lo, hi, value);
    *out = (int)value;
    return true;
}

/* ---- key tables -------------------------------------------------------------------------------- */

/* Reads tokens[0..count) as key/value pairs against `specs` (n_specs entries). Rejects unknown keys,
 * keys given twice and keys with too few values. */
static bool parse_keys(const struct parser *p, const char *directive, char **tokens, int count,
                       const struct key_spec *specs, int n_specs, struct key_values *kv) {
    memset(kv, 0, sizeof *kv);
    int k = 0;
    while (k < count) {
        int which = -1;
        for (int s = 0; s < n_specs; s++)
            if (strcmp(tokens[k], specs[s].name) == 0)
                which = s;
        if (which < 0) {
            if (strcmp(tokens[k], "color") == 0)
                return fail(p, "unknown key 'color' for %s (the format spells it 'colour')", directive);
            return fail(p, "unknown key '%s' for %s", tokens[k], directive);
        }
        if (kv->present[which])
            return fail(p, "'%s' given twice", specs[which].name);
        kv->present[which] = true;
        int needed = specs[which].count == 0 ? 1 : specs[which].count;
        if (k + needed > count - 1) { /* the values would be tokens k+1 .. k+needed */
            if (specs[which].count <= 1)
                return fail(p, "'%s' needs a value", specs[which].name);
            return fail(p, "'%s' needs %d numbers", specs[which].name, specs[which].count);
        }
        if (specs[which].count == 0) {
            kv->word[which] = tokens[k + 1];
        } else {
            for (int n = 0; n < specs[which].count; n++)
                if (!parse_number(p, tokens[k + 1 + n], specs[which].name, &kv->number[which][n]))
                    return false;
        }
        k += 1 + needed;
    }
    return true;
}

/* Fails unless every key named in `required` (indices into the table, ending with -1) is present. */
static bool require_keys(const struct parser *p, const char *directive, const struct key_spec *specs,
                         const struct key_values *kv, const int *required) {
    for (int r = 0; required[r] >= 0; r++)
        if (!kv->present[required[r]])
            return fail(p, "%s needs '%s'", directive, specs[required[r]].name);
    return true;
}

/* Copies the values of keys [first, first + count) of *kv into keys [0, count) of *out: the keys a
 * line borrows from another module's table (a light's area keys, the camera's lens keys), as that
 * module reads them. */
static void key_values_slice(const struct key_values *kv, int first, int count, struct key_values *out) {
    memset(out, 0, sizeof *out);
    for (int k = 0; k < count; k++) {
        out->present[k] = kv->present[first + k];
        memcpy(out->number[k], kv->number[first + k], sizeof out->number[k]);
        out->word[k] = kv->word[first + k];
    }
}

/* ---- growing arrays ---------------------------------------------------------------------------- */

/* Makes room for one more element of `size` bytes in *items (holding *count), doubling the capacity
 * when full. Returns the new, zeroed element, or NULL when memory runs out. */
static void *grow(void *items_ptr, size_t *count, size_t size) {
    void **items = items_ptr;
    size_t n = *count;
    /* The capacity is not stored: it is always the smallest power of two >= count (1 for an empty
     * array), so the array is full exactly when count is 0 or a power of two. */
    if ((n & (n - 1)) == 0) {
        size_t capacity = n == 0 ? 1 : 2 * n;
        void *bigger = realloc(*items, capacity * size);
        if (bigger == NULL)
            return NULL;
        *items = bigger;
    }
    char *slot = (char *)*items + n * size;
    memset(slot, 0, size);
    *count = n + 1;
    return slot;
}

/* ---- directives -------------------------------------------------------------------------------- */

const char *const scene_metal_names[SCENE_METAL_COUNT] = {"none", "colour", "gold", "silver", "copper",
                                                          "aluminium"};

static bool material_reference(const struct parser *p, const struct scene *s,
                               const struct key_values *kv, int key, int *material) {
    *material = 0;
    if (!kv->present[key])
        return true;
    (void)s;
    int found = name_index_find(p->materials, kv->word[key]);
    if (found < 0)
        return fail(p, "unknown material '%s' (define it with a material line first)", kv->word[key]);
    *material = found;
    return true;
}

static bool parse_camera(const struct parser *p, struct scene *s, char **tok, int n, bool *seen) {
    enum { EYE, TARGET, UP, FOV, LENS, SHUTTER = LENS + LENS_KEY_COUNT }; /* the lens keys (lens.h) */
    struct key_spec specs[SHUTTER + 1] = {{"eye", 3}, {"target", 3}, {"up", 3}, {"fov", 1}};
    memcpy(specs + LENS, lens_keys, sizeof lens_keys);
    specs[SHUTTER] = (struct key_spec){"shutter", 1};
    static const int required[] = {EYE, TARGET, FOV, -1};
    struct key_values kv, lens_kv;
    if (*seen)
        return fail(p, "a second camera (a scene has one)");
    if (!parse_keys(p, "camera", tok, n, specs, SHUTTER + 1, &kv) ||
        !require_keys(p, "camera", specs, &kv, required))
        return false;
    s->eye = key_vec3(&kv, EYE);
    s->target = key_vec3(&kv, TARGET);
    s->up = kv.present[UP] ? key_vec3(&kv, UP) : vec3_make(0, 1, 0);
    s->fov = kv.number[FOV][0];
    /* Points in range, so that the view direction and what is derived from it stay finite (an eye at
     * 1e200 would square to infinity and look like a zero up vector). */
    char why[256];
    if (!key_vec3_within(s->eye, KEY_MAX_COORD, "camera eye", why, sizeof why) ||
        !key_vec3_within(s->target, KEY_MAX_COORD, "camera target", why, sizeof why) ||
        !key_vec3_within(s->up, KEY_MAX_COORD, "camera up", why, sizeof why))
        return fail(p, "%s", why);
    /* The camera's own checks, so that a camera that loads is a camera that renders. */
    struct camera probe;
    if (!camera_init(&probe, s->eye, s->target, s->up, s->fov, 1, 1, why, sizeof why))
        return fail(p, "%s", why);
    key_values_slice(&kv, LENS, LENS_KEY_COUNT, &lens_kv);
    if (!lens_make(&lens_kv, s->eye, &s->lens, why, sizeof why))
        return fail(p, "%s", why);
    s->shutter = kv.present[SHUTTER] ? kv.number[SHUTTER][0] : 0.0;
    if (!instance_shutter_valid(s->shutter, why, sizeof why))
        return fail(p, "%s", why);
    *seen = true;
    return true;
}

/* Reads exactly three numbers (a colour) after the directive name. */
static bool parse_triple(const struct parser *p, const char *directive, char **tok, int n, vec3 *out) {
    double c[3];
    if (n != 3)
        return fail(p, "%s needs 3 numbers, got %d", directive, n);
    for (int k = 0; k < 3; k++)
        if (!parse_number(p, tok[k], directive, &c[k]))
            return false;
    *out = vec3_make(c[0], c[1], c[2]);
    return true;
}

static bool parse_material(const struct parser *p, struct scene *s, char **tok, int n) {
    enum { COLOUR, AMBIENT, DIFFUSE, PHONG, PHONG_SIZE, REFLECTION, FILTER, TRANSMIT, IOR, PIGMENT, EMISSION,
           ROUGHNESS, METAL, LOBE };
    static const struct key_spec specs[] = {
        {"colour", 3}, {"ambient", 1}, {"diffuse", 1},  {"phong", 1}, {"phong_size", 1},
        {"reflection", 1}, {"filter", 1}, {"transmit", 1}, {"ior", 1}, {"pigment", 0}, {"emission", 3},
        {"roughness", 1}, {"metal", 0}, {"lobe", 0}};
    struct key_values kv;
    if (n < 1)
        return fail(p, "material needs a name");
    if (strlen(tok[0]) >= SCENE_NAME_MAX)
        return fail(p, "material name longer than %d characters", SCENE_NAME_MAX - 1);
    if (name_index_find(p->materials, tok[0]) >= 0)
        return fail(p, "material '%s' is already defined", tok[0]);
    if (!parse_keys(p, "material", tok + 1, n - 1, specs, LOBE + 1, &kv))
        return false;
    struct material m = s->materials[0]; /* unspecified keys keep the defaults */
    snprintf(m.name, sizeof m.name, "%s", tok[0]);
    m.line = p->line;
    double *scalars[] = {NULL, &m.ambient, &m.diffuse, &m.phong, &m.phong_size, &m.reflection,
                         &m.filter, &m.transmit, &m.ior};
    for (int k = AMBIENT; k <= IOR; k++)
        if (kv.present[k])
            *scalars[k] = kv.number[k][0];
    if (kv.present[COLOUR])
        m.colour = key_vec3(&kv, COLOUR);
    if (kv.present[PIGMENT]) {
        m.pigment = name_index_find(p->pigments, kv.word[PIGMENT]);
        if (m.pigment < 0)
            return fail(p, "unknown pigment '%s' (define it with a pigment line first)", kv.word[PIGMENT]);
    }
    for (int k = AMBIENT; k <= TRANSMIT; k++)
        if (*scalars[k] < 0.0)
            return fail(p, "material '%s': %s must not be negative", m.name, specs[k].name);
    for (int k = AMBIENT; k <= REFLECTION; k++)
        if (k != PHONG_SIZE && *scalars[k] > KEY_MAX_SURFACE)
            return fail(p, "material '%s': %s must be at most %g, got " KEY_NUMBER_SHOWN, m.name, specs[k].name,
                        KEY_MAX_SURFACE, KEY_NUMBER(*scalars[k]));
    if (m.colour.x < 0.0 || m.colour.y < 0.0 || m.colour.z < 0.0)
        return fail(p, "material '%s': colour must not be negative", m.name);
    if (!(m.colour.x <= KEY_MAX_SURFACE && m.colour.y <= KEY_MAX_SURFACE && m.colour.z <= KEY_MAX_SURFACE))
        return fail(p, "material '%s': colour must be at most %g in each channel, got " KEY_NUMBER_SHOWN " "
                    KEY_NUMBER_SHOWN " " KEY_NUMBER_SHOWN, m.name, KEY_MAX_SURFACE, KEY_NUMBER(m.colour.x),
                    KEY_NUMBER(m.colour.y), KEY_NUMBER(m.colour.z));
    if (kv.present[EMISSION])
        m.emission = key_vec3(&kv, EMISSION);
    vec3 e = m.emission;
    if (!(e.x >= 0.0 && e.y >= 0.0 && e.z >= 0.0) || !vec3_is_finite(e))
        return fail(p, "material '%s': emission must be finite and not negative", m.name);
    if (!(e.x <= SCENE_MAX_LIGHT && e.y <= SCENE_MAX_LIGHT && e.z <= SCENE_MAX_LIGHT))
        return fail(p, "material '%s': emission must be at most %g in each channel, got " KEY_NUMBER_SHOWN " "
                    KEY_NUMBER_SHOWN " " KEY_NUMBER_SHOWN, m.name, SCENE_MAX_LIGHT, KEY_NUMBER(e.x), KEY_NUMBER(e.y),
                    KEY_NUMBER(e.z));
    if (m.filter + m.transmit > 1.0)
        return fail(p, "material '%s': filter + transmit must not exceed 1", m.name);
    if (kv.present[ROUGHNESS])
        m.roughness = kv.number[ROUGHNESS][0];
    if (!(m.roughness >= 0.0 && m.roughness <= 1.0))
        return fail(p, "material '%s': roughness must be between 0 and 1, got " KEY_NUMBER_SHOWN, m.name,
                    KEY_NUMBER(m.roughness));
    if (kv.present[METAL]) {
        int metal = 0;
        while (metal < SCENE_METAL_COUNT && strcmp(kv.word[METAL], scene_metal_names[metal]) != 0)
            metal++;
        if (metal == SCENE_METAL_COUNT)
            return fail(p, "material '%s': unknown metal '%s' (none, colour, gold, silver, copper or aluminium)",
                        m.name, kv.word[METAL]);
        m.metal = (enum scene_metal)metal;
    }
    if (kv.present[LOBE]) {
        if (strcmp(kv.word[LOBE], "ggx") == 0)
            m.lobe = SCENE_LOBE_GGX;
        else if (strcmp(kv.word[LOBE], "phong") == 0)
            m.lobe = SCENE_LOBE_PHONG;
        else
            return fail(p, "material '%s': unknown lobe '%s' (ggx or phong)", m.name, kv.word[LOBE]);
    }
    if (!(m.phong_size > 0.0))
        return fail(p, "material '%s': phong_size must be positive", m.name);
    if (!(m.ior > 0.0))
        return fail(p, "material '%s': ior must be positive", m.name);
    if (!(m.ior >= SCENE_MIN_IOR && m.ior <= SCENE_MAX_IOR))
        return fail(p, "material '%s': ior %g is out of range (from %g to %g)", m.name, m.ior, SCENE_MIN_IOR,
                    SCENE_MAX_IOR);
    struct material *slot = grow(&s->materials, &s->material_count, sizeof *slot);
    if (slot == NULL || !name_index_add(p->materials, m.name, (int)(s->material_count - 1)))
        return fail(p, "out of memory");
    *slot = m;
    return true;
}

static bool parse_light(const struct parser *p, struct scene *s, char **tok, int n) {
    enum { POSITION, COLOUR, AREA }; /* then the area keys (area_light.h) */
    struct key_spec specs[AREA + AREA_LIGHT_KEY_COUNT] = {{"position", 3}, {"colour", 3}};
    memcpy(specs + AREA, area_light_keys, sizeof area_light_keys);
    static const int required[] = {POSITION, -1};
    struct key_values kv, area_kv;
    char why[256];
    if (!parse_keys(p, "light", tok, n, specs, AREA + AREA_LIGHT_KEY_COUNT, &kv) ||
        !require_keys(p, "light", specs, &kv, required))
        return false;
    key_values_slice(&kv, AREA, AREA_LIGHT_KEY_COUNT, &area_kv);
    struct area_light area;
    if (!area_light_make(&area_kv, &area, why, sizeof why))
        return fail(p, "%s", why);
    struct light *light = grow(&s->lights, &s->light_count, sizeof *light);
    if (light == NULL)
        return fail(p, "out of memory");
    light->line = p->line;
    light->position = key_vec3(&kv, POSITION);
    light->colour = kv.present[COLOUR] ? key_vec3(&kv, COLOUR) : vec3_make(1, 1, 1);
    if (!key_vec3_within(light->colour, SCENE_MAX_LIGHT, "light colour", why, sizeof why))
        return fail(p, "%s", why);
    light->area = area;
    /* A light's position in range, so that the direction to it from any point stays finite; an area light
     * is besides a rectangle chapter 15 draws as two triangles, whose corners stay in range. */
    if (!key_vec3_within(light->position, KEY_MAX_COORD,
                         area_light_is_area(&area) ? "an area light's position" : "light position", why, sizeof why))
        return fail(p, "%s", why);
    return true;
}

/* Reads the line of a shape of the list's kind: its own keys and `material`, then the kind's make. */
static bool parse_shape(const struct parser *p, struct scene *s, struct shape_list *list, char **tok, int n) {
    const struct shape_syntax *syntax = list->syntax;
    struct key_spec specs[KEY_MAX];
    memcpy(specs, syntax->keys, (size_t)syntax->key_count * sizeof *specs);
    int material_key = syntax->key_count;
    specs[material_key] = (struct key_spec){"material", 0};
    struct key_values kv;
    int material;
    if (!parse_keys(p, syntax->keyword, tok, n, specs, material_key + 1, &kv) ||
        !require_keys(p, syntax->keyword, specs, &kv, syntax->required) ||
        !material_reference(p, s, &kv, material_key, &material))
        return false;
    char *item = grow(&list->items, &list->count, syntax->size);
    if (item == NULL)
        return fail(p, "out of memory");
    char why[256];
    if (!syntax->make(&kv, item, why, sizeof why))
        return fail(p, "%s", why);
    memcpy(item + syntax->material_offset, &material, sizeof material);
    return true;
}

/* Joins the scene file's folder and a relative mesh path; absolute paths are kept. */
static char *resolve_path(const char *scene_name, const char *path) {
    const char *slash = strrchr(scene_name, '/');
    size_t folder = (path[0] == '/' || slash == NULL) ? 0 : (size_t)(slash - scene_name) + 1;
    char *joined = malloc(folder + strlen(path) + 1);
    if (joined != NULL) {
        memcpy(joined, scene_name, folder);
        strcpy(joined + folder, path);
    }
    return joined;
}

/* The pigment line (pigment.h): a name, a pattern, the pattern's keys and the texture transform. */
static bool parse_pigment(const struct parser *p, struct scene *s, char **tok, int n) {
    if (n < 2)
        return fail(p, "pigment needs a name and a pattern");
    if (strlen(tok[0]) >= PIGMENT_NAME_MAX)
        return fail(p, "pigment name longer than %d characters", PIGMENT_NAME_MAX - 1);
    if (name_index_find(p->pigments, tok[0]) >= 0)
        return fail(p, "pigment '%s' is already defined", tok[0]);
    const struct pigment_syntax *syntax = NULL;
    for (size_t k = 0; pigment_syntaxes[k] != NULL; k++)
        if (strcmp(tok[1], pigment_syntaxes[k]->pattern) == 0)
            syntax = pigment_syntaxes[k];
    if (syntax == NULL)
        return fail(p, "unknown pattern '%s' (checker, gradient, brick, radial or image_map)", tok[1]);
    struct key_spec specs[KEY_MAX];
    memcpy(specs, syntax->keys, (size_t)syntax->key_count * sizeof *specs);
    memcpy(specs + syntax->key_count, pigment_transform_keys, sizeof pigment_transform_keys);
    struct key_values kv;
    if (!parse_keys(p, "pigment", tok + 2, n - 2, specs, syntax->key_count + PIGMENT_TRANSFORM_KEY_COUNT, &kv) ||
        !require_keys(p, "pigment", specs, &kv, syntax->required))
        return false;
    struct pigment pigment = {.line = p->line};
    snprintf(pigment.name, sizeof pigment.name, "%s", tok[0]);
    char why[256];
    if (!syntax->make(&kv, &pigment, why, sizeof why) ||
        !pigment_make_transform(&kv, syntax->key_count, &pigment, why, sizeof why))
        return fail(p, "%s", why);
    struct pigment *slot = grow(&s->pigments, &s->pigment_count, sizeof *slot);
    if (slot == NULL || !name_index_add(p->pigments, pigment.name, (int)(s->pigment_count - 1)))
        return fail(p, "out of memory");
    *slot = pigment;
    if (pigment.pattern == PIGMENT_IMAGE_MAP) { /* the file is read by chapter 14 (texture_load_images) */
        const char *file = kv.word[0];
        if (strpbrk(file, "\"\\") != NULL)
            return fail(p, "pigment '%s': the file name must not hold a quote or a backslash", pigment.name);
        slot->file = resolve_path(p->name, file);
        if (slot->file == NULL)
            return fail(p, "out of memory");
    }
    return true;
}

static bool parse_mesh(const struct parser *p, struct scene *s, char **tok, int n) {
    enum { SCALE, ROTATE, TRANSLATE, MATERIAL, SMOOTH };
    static const struct key_spec specs[] = {{"scale", 1}, {"rotate", 3}, {"translate", 3}, {"material", 0},
                                            {"smooth", 0}};
    struct key_values kv;
    int material;
    if (n < 1)
        return fail(p, "mesh needs a file name");
    if (!parse_keys(p, "mesh", tok + 1, n - 1, specs, 5, &kv) ||
        !material_reference(p, s, &kv, MATERIAL, &material))
        return false;
    int smooth = SCENE_SMOOTH_FILE;
    if (kv.present[SMOOTH]) {
        if (strcmp(kv.word[SMOOTH], "on") != 0 && strcmp(kv.word[SMOOTH], "off") != 0)
            return fail(p, "mesh smooth must be on or off, got '%s'", kv.word[SMOOTH]);
        smooth = strcmp(kv.word[SMOOTH], "on") == 0 ? SCENE_SMOOTH_ON : SCENE_SMOOTH_OFF;
    }
    double scale = kv.present[SCALE] ? kv.number[SCALE][0] : 1.0;
    if (!(scale > 0.0))
        return fail(p, "mesh scale must be positive, got " KEY_NUMBER_SHOWN, KEY_NUMBER(scale));
    struct scene_mesh *mesh = grow(&s->meshes, &s->mesh_count, sizeof *mesh);
    if (mesh == NULL)
        return fail(p, "out of memory");
    mesh->path = resolve_path(p->name, tok[0]);
    if (mesh->path == NULL)
        return fail(p, "out of memory");
    mesh->scale = scale;
    mesh->rotate = kv.present[ROTATE] ? key_vec3(&kv, ROTATE) : vec3_make(0, 0, 0);
    mesh->translate = kv.present[TRANSLATE] ? key_vec3(&kv, TRANSLATE) : vec3_make(0, 0, 0);
    mesh->material = material;
    mesh->smooth = smooth;
    mesh->line = p->line;
    return true;
}

/* Reads a name for an object or an instance's id: not empty, short enough, not taken in `index`. */
static bool parse_name(const struct parser *p, const char *what, const char *name, const struct name_index *index) {
    if (strlen(name) >= SCENE_NAME_MAX)
        return fail(p, "%s name longer than %d characters", what, SCENE_NAME_MAX - 1);
    if (name_index_find(index, name) >= 0)
        return fail(p, "%s '%s' is already defined", what, name);
    return true;
}

/* The object line (chapter 16): `object NAME FILE [smooth on|off]`. */
static bool parse_object(const struct parser *p, struct scene *s, char **tok, int n) {
    static const struct key_spec specs[] = {{"smooth", 0}};
    struct key_values kv;
    if (n < 2)
        return fail(p, "object needs a name and a file name");
    if (!parse_name(p, "object", tok[0], p->objects) || !parse_keys(p, "object", tok + 2, n - 2, specs, 1, &kv))
        return false;
    if (s->object_count == SCENE_OBJECT_MAX)
        return fail(p, "more than %d object lines", SCENE_OBJECT_MAX);
    int smooth = SCENE_SMOOTH_FILE;
    if (kv.present[0]) {
        if (strcmp(kv.word[0], "on") != 0 && strcmp(kv.word[0], "off") != 0)
            return fail(p, "object smooth must be on or off, got '%s'", kv.word[0]);
        smooth = strcmp(kv.word[0], "on") == 0 ? SCENE_SMOOTH_ON : SCENE_SMOOTH_OFF;
    }
    struct scene_object *object = grow(&s->objects, &s->object_count, sizeof *object);
    if (object == NULL || !name_index_add(p->objects, tok[0], (int)(s->object_count - 1)))
        return fail(p, "out of memory");
    snprintf(object->name, sizeof object->name, "%s", tok[0]);
    object->path = resolve_path(p->name, tok[1]);
    if (object->path == NULL)
        return fail(p, "out of memory");
    object->smooth = smooth;
    object->line = p->line;
    return true;
}

/* The instance line (chapter 16): `instance NAME [material M] [scale X Y Z] [rotate X Y Z]
 * [translate X Y Z] [id LABEL]`. */
static bool parse_instance(const struct parser *p, struct scene *s, char **tok, int n) {
    enum { MATERIAL = INSTANCE_POSE_KEY_COUNT, ID };
    struct key_spec specs[ID + 1];
    memcpy(specs, instance_pose_keys, sizeof instance_pose_keys);
    specs[MATERIAL] = (struct key_spec){"material", 0};
    specs[ID] = (struct key_spec){"id", 0};
    struct key_values kv;
    int material;
    if (n < 1)
        return fail(p, "instance needs the name of an object");
    int object = name_index_find(p->objects, tok[0]);
    if (object < 0)
        return fail(p, "unknown object '%s' (define it with an object line first)", tok[0]);
    if (!parse_keys(p, "instance", tok + 1, n - 1, specs, ID + 1, &kv) ||
        !material_reference(p, s, &kv, MATERIAL, &material) ||
        (kv.present[ID] && !parse_name(p, "instance id", kv.word[ID], p->ids)))
        return false;
    if (s->instance_count == SCENE_INSTANCE_MAX)
        return fail(p, "more than %d instance lines", SCENE_INSTANCE_MAX);
    struct scene_pose identity = instance_pose_identity(), pose;
    char why[256];
    if (!instance_pose_make(&kv, &identity, &pose, why, sizeof why))
        return fail(p, "instance of '%s': %s", tok[0], why);
    struct scene_instance *instance = grow(&s->instances, &s->instance_count, sizeof *instance);
    if (instance == NULL ||
        (kv.present[ID] && !name_index_add(p->ids, kv.word[ID], (int)(s->instance_count - 1))))
        return fail(p, "out of memory");
    instance->object = object;
    instance->material = material;
    if (kv.present[ID])
        snprintf(instance->id, sizeof instance->id, "%s", kv.word[ID]);
    instance->pose = pose;
    instance->line = p->line;
    return true;
}

/* The key line (chapter 16): `key LABEL time T [scale X Y Z] [rotate X Y Z] [translate X Y Z]`, a pose
 * of the instance with id LABEL; what it does not give is the instance line's. */
static bool parse_key(const struct parser *p, struct scene *s, char **tok, int n) {
    enum { TIME = INSTANCE_POSE_KEY_COUNT };
    struct key_spec specs[TIME + 1];
    memcpy(specs, instance_pose_keys, sizeof instance_pose_keys);
    specs[TIME] = (struct key_spec){"time", 1};
    static const int required[] = {TIME, -1};
    struct key_values kv;
    if (n < 1)
        return fail(p, "key needs the id of an instance");
    int found = name_index_find(p->ids, tok[0]);
    if (found < 0)
        return fail(p, "unknown instance id '%s' (give an instance line 'id %s' first)", tok[0], tok[0]);
    if (!parse_keys(p, "key", tok + 1, n - 1, specs, TIME + 1, &kv) || !require_keys(p, "key", specs, &kv, required))
        return false;
    struct scene_instance *instance = &s->instances[found];
    if (instance->key_count == SCENE_KEY_MAX)
        return fail(p, "more than %d keys for instance '%s'", SCENE_KEY_MAX, tok[0]);
    struct scene_key key = {kv.number[TIME][0], instance->pose, p->line};
    char why[256];
    bool has_previous = instance->key_count > 0;
    if (!instance_key_time_valid(key.time, has_previous ? instance->keys[instance->key_count - 1].time : 0.0,
                                 has_previous, why, sizeof why) ||
        !instance_pose_make(&kv, &instance->pose, &key.pose, why, sizeof why))
        return fail(p, "key of '%s': %s", tok[0], why);
    struct scene_key *slot = grow(&instance->keys, &instance->key_count, sizeof *slot);
    if (slot == NULL)
        return fail(p, "out of memory");
    *slot = key;
    return true;
}

/* The antialias line (antialias.h): a scene has at most one. */
static bool parse_antialias(const struct parser *p, struct scene *s, char **tok, int n) {
    struct key_values kv;
    char why[256];
    if (s->antialias.line != 0)
        return fail(p, "a second antialias line (a scene has one)");
    if (!parse_keys(p, "antialias", tok, n, antialias_keys, ANTIALIAS_KEY_COUNT, &kv))
        return false;
    if (!antialias_make(&kv, &s->antialias, why, sizeof why))
        return fail(p, "%s", why);
    s->antialias.line = p->line;
    return true;
}

/* The paths line (path_settings.h): a scene has at most one. */
static bool parse_paths(const struct parser *p, struct scene *s, char **tok, int n) {
    struct key_values kv;
    char why[256];
    if (s->paths.line != 0)
        return fail(p, "a second paths line (a scene has one)");
    if (!parse_keys(p, "paths", tok, n, path_keys, PATH_KEY_COUNT, &kv))
        return false;
    if (!path_settings_make(&kv, &s->paths, why, sizeof why))
        return fail(p, "%s", why);
    s->paths.line = p->line;
    return true;
}

/* ---- the kinds of shape ------------------------------------------------------------------------ */

const struct shape_syntax *const scene_syntaxes[] = {&sphere_syntax, &triangle_syntax, &plane_syntax, &box_syntax,
                                                     NULL};

/* Returns the kind in `kinds` (ending with NULL; NULL for none) whose line is `syntax`, or NULL. */
static const struct shape_kind *kind_with_syntax(const struct shape_kind *const *kinds,
                                                 const struct shape_syntax *syntax) {
    for (size_t k = 0; kinds != NULL && kinds[k] != NULL; k++)
        if (kinds[k]->syntax == syntax)
            return kinds[k];
    return NULL;
}

/* Gives s an empty list for every kind of scene_syntaxes[], with its kind when the program draws it,
 * then one for every other kind it draws. Returns false when there are more than SCENE_KIND_MAX. */
static bool make_shape_lists(struct scene *s, const struct shape_kind *const *kinds) {
    s->kind_count = 0;
    for (size_t k = 0; scene_syntaxes[k] != NULL; k++) {
        const struct shape_syntax *syntax = scene_syntaxes[k];
        s->shapes[s->kind_count++] = (struct shape_list){syntax, kind_with_syntax(kinds, syntax), NULL, 0};
    }
    for (size_t k = 0; kinds != NULL && kinds[k] != NULL; k++) {
        if (scene_shapes(s, kinds[k]->syntax) != NULL)
            continue;
        if (s->kind_count == SCENE_KIND_MAX)
            return false;
        s->shapes[s->kind_count++] = (struct shape_list){kinds[k]->syntax, kinds[k], NULL, 0};
    }
    return true;
}

const struct shape_list *scene_shapes(const struct scene *s, const struct shape_syntax *syntax) {
    for (size_t k = 0; k < s->kind_count; k++)
        if (s->shapes[k].syntax == syntax)
            return &s->shapes[k];
    return NULL;
}

/* ---- lines and files --------------------------------------------------------------------------- */

/* Whether `line` holds a carriage return with a word after it: a line break of a file whose lines end in
 * carriage returns alone, which the reader, splitting at line feeds, takes for one line (then
 * "camera ...<CR>image 8 6" said "unknown key 'image' for camera"). A carriage return at the end of a line
 * is a CRLF file's, and one in a comment changes nothing. The first one decides: after it, either a word
 * follows, or only white space to the end or the comment. */
static bool lone_carriage_return(const char *line) {
    size_t before = strcspn(line, "\r#");
    if (line[before] != '\r')
        return false;
    const char *after = line + before + strspn(line + before, " \t\r\v\f");
    return *after != '\0' && *after != '#';
}

/* Splits `line` in place at white space, stopping at '#'. Returns the token count, or -1 if there are
 * more than `max`. */
static int split_tokens(char *line, char **tokens, int max) {
    int count = 0;
    char *cursor = line;
    for (;;) {
        while (*cursor == ' ' || *cursor == '\t' || *cursor == '\r' || *cursor == '\v' || *cursor == '\f')
            cursor++;
        if (*cursor == '\0' || *cursor == '#')
            return count;
        if (count == max)
            return -1;
        tokens[count++] = cursor;
        while (*cursor != '\0' && *cursor != '#' && *cursor != ' ' && *cursor != '\t' && *cursor != '\r' &&
               *cursor != '\v' && *cursor != '\f')
            cursor++;
        if (*cursor == '#') {
            *cursor = '\0';
            return count;
        }
        if (*cursor != '\0')
            *cursor++ = '\0';
    }
}

static bool parse_line(const struct parser *p, struct scene *s, char **tok, int n, bool *camera_seen,
                       bool *image_seen) {
    const char *directive = tok[0];
    char **args = tok + 1;
    int count = n - 1;
    if (strcmp(directive, "camera") == 0)
        return parse_camera(p, s, args, count, camera_seen);
    if (strcmp(directive, "image") == 0) {
        if (*image_seen)
            return fail(p, "a second image line");
        if (count != 2)
            return fail(p, "image needs a width and a height");
        *image_seen = true;
        return parse_int(p, args[0], "image width", 1, IMAGE_MAX_SIDE, &s->width) &&
               parse_int(p, args[1], "image height", 1, IMAGE_MAX_SIDE, &s->height);
    }
    if (strcmp(directive, "background") == 0 || strcmp(directive, "ambient_light") == 0) {
        /* Both are light, held to a light's range: a background of 1e300 was infinite in a float HDR file. */
        bool background = strcmp(directive, "background") == 0;
        vec3 *colour = background ? &s->background : &s->ambient_light;
        char why[256];
        if (!parse_triple(p, directive, args, count, colour))
            return false;
        if (!key_vec3_within(*colour, SCENE_MAX_LIGHT, directive, why, sizeof why))
            return fail(p, "%s", why);
        if (background)
            s->background_line = p->line;
        return true;
    }
    if (strcmp(directive, "max_depth") == 0) {
        if (count != 1)
            return fail(p, "max_depth needs one whole number");
        return parse_int(p, args[0], "max_depth", 1, MAX_DEPTH_LIMIT, &s->max_depth);
    }
    if (strcmp(directive, "adc_bailout") == 0) {
        if (count != 1)
            return fail(p, "adc_bailout needs one number");
        if (!parse_number(p, args[0], "adc_bailout", &s->adc_bailout))
            return false;
        if (s->adc_bailout < 0.0 || s->adc_bailout > 1.0)
            return fail(p, "'adc_bailout' must be between 0 and 1, got %s", args[0]);
        return true;
    }
    if (strcmp(directive, "shadow_offset") == 0) {
        if (count != 1 || (strcmp(args[0], "on") != 0 && strcmp(args[0], "off") != 0))
            return fail(p, "shadow_offset needs 'on' or 'off'");
        s->shadow_offset = strcmp(args[0], "on") == 0;
        return true;
    }
    if (strcmp(directive, "material") == 0)
        return parse_material(p, s, args, count);
    if (strcmp(directive, "light") == 0)
        return parse_light(p, s, args, count);
    if (strcmp(directive, "pigment") == 0)
        return parse_pigment(p, s, args, count);
    if (strcmp(directive, "mesh") == 0)
        return parse_mesh(p, s, args, count);
    if (strcmp(directive, "antialias") == 0)
        return parse_antialias(p, s, args, count);
    if (strcmp(directive, "object") == 0)
        return parse_object(p, s, args, count);
    if (strcmp(directive, "instance") == 0)
        return parse_instance(p, s, args, count);
    if (strcmp(directive, "key") == 0)
        return parse_key(p, s, args, count);
    if (strcmp(directive, "paths") == 0)
        return parse_paths(p, s, args, count);
    for (size_t k = 0; k < s->kind_count; k++)
        if (strcmp(directive, s->shapes[k].syntax->keyword) == 0)
            return parse_shape(p, s, &s->shapes[k], args, count);
    return fail(p, "unknown directive '%s'", directive);
}

/* Sets the values a scene has before its first line. */
static bool scene_defaults(struct scene *s, const char *name) {
    s->path = malloc(strlen(name) + 1);
    struct material *fallback = grow(&s->materials, &s->material_count, sizeof *fallback);
    if (s->path == NULL || fallback == NULL)
        return false;
    strcpy(s->path, name);
    /* POV-Ray's finish defaults, but a white pigment (POV-Ray's default pigment is black). */
    *fallback = (struct material){.name = "default", .colour = {1, 1, 1}, .ambient = 0.1, .diffuse = 0.6,
                                  .phong = 0.0, .phong_size = 40.0, .ior = 1.0, .pigment = -1};
    s->up = vec3_make(0, 1, 0);
    s->ambient_light = vec3_make(1, 1, 1);
    s->max_depth = DEFAULT_MAX_DEPTH;
    s->adc_bailout = DEFAULT_ADC_BAILOUT;
    s->shadow_offset = true;
    s->paths = path_settings_default();
    return true;
}

bool scene_parse(const char *name, const char *text, const struct shape_kind *const *kinds, struct scene *s,
                 char *err, size_t err_size) {
    memset(s, 0, sizeof *s);
    if (!make_shape_lists(s, kinds)) {
        scene_free(s);
        snprintf(err, err_size, "%s: more than %d kinds of shape", name, SCENE_KIND_MAX);
        return false;
    }
    struct name_index materials, pigments, objects, ids;
    name_index_init(&materials);
    name_index_init(&pigments);
    name_index_init(&objects);
    name_index_init(&ids);
    struct parser p = {name, 0, err, err_size, &materials, &pigments, &objects, &ids};
    char *copy = malloc(strlen(text) + 1);
    if (copy == NULL || !scene_defaults(s, name) || !name_index_add(&materials, "default", 0)) {
        free(copy);
        name_index_free(&materials);
        name_index_free(&pigments);
        name_index_free(&objects);
        name_index_free(&ids);
        scene_free(s);
        snprintf(err, err_size, "%s: out of memory", name);
        return false;
    }
    strcpy(copy, text);
    bool ok = true, camera_seen = false, image_seen = false;
    char *line = copy;
    if (strncmp(line, SCENE_UTF8_BOM, strlen(SCENE_UTF8_BOM)) == 0)
        line += strlen(SCENE_UTF8_BOM); /* some editors start a UTF-8 file with it; it is no part of a word */
    while (ok && line != NULL) {
        char *newline = strchr(line, '\n');
        if (newline != NULL)
            *newline = '\0';
        p.line++;
        char *tokens[LINE_MAX_TOKENS];
        bool lone_return = lone_carriage_return(line);
        int n = split_tokens(line, tokens, LINE_MAX_TOKENS);
        if (lone_return)
            ok = fail(&p, "a carriage return inside the line: its lines end in carriage returns alone (old Mac "
                          "OS), and they are read as one; save it with line feeds");
        else if (n < 0)
            ok = fail(&p, "too many words on one line (at most %d)", LINE_MAX_TOKENS);
        else if (n > 0)
            ok = parse_line(&p, s, tokens, n, &camera_seen, &image_seen);
        line = newline != NULL ? newline + 1 : NULL;
    }
    free(copy);
    name_index_free(&materials);
    name_index_free(&pigments);
    name_index_free(&objects);
    name_index_free(&ids);
    if (ok && !camera_seen)
        ok = (snprintf(err, err_size, "%s: no camera line (a scene needs one)", name), false);
    if (ok && !image_seen)
        ok = (snprintf(err, err_size, "%s: no image line (a scene needs its size, e.g. 'image 320 240')", name),
              false);
    if (!ok)
        scene_free(s);
    return ok;
}

char *scene_read_text(const char *path, char *err, size_t err_size) {
    FILE *file = infile_open(path, err, err_size); /* a regular file, or refused without waiting */
    if (file == NULL)
        return NULL;
    long size = -1;
    struct stat info;
    if (fstat(fileno(file), &info) == 0 && S_ISREG(info.st_mode) && fseek(file, 0, SEEK_END) == 0)
        size = ftell(file);
    rewind(file);
    if (size < 0 || size > SCENE_FILE_MAX_BYTES) {
        snprintf(err, err_size, "%s: %s", path, size < 0 ? "cannot read (not a regular file?)" :
                                                "larger than 64 MiB; not a scene file");
        fclose(file);
        return NULL;
    }
    char *text = malloc((size_t)size + 1);
    size_t length = text == NULL ? 0 : fread(text, 1, (size_t)size, file);
    bool read_error = text == NULL || ferror(file) || length != (size_t)size;
    fclose(file);
    if (read_error) {
        snprintf(err, err_size, "%s: cannot read", path);
        free(text);
        return NULL;
    }
    text[length] = '\0';
    if (strlen(text) != length) {
        int line = 1;
        for (const char *c = text; *c != '\0'; c++)
            line += *c == '\n';
        snprintf(err, err_size, "%s:%d: contains a zero byte; not a text file", path, line);
        free(text);
        return NULL;
    }
    return text;
}

bool scene_load(const char *path, const struct shape_kind *const *kinds, struct scene *s, char *err,
                size_t err_size) {
    memset(s, 0, sizeof *s);
    char *text = scene_read_text(path, err, err_size);
    if (text == NULL)
        return false;
    bool ok = scene_parse(path, text, kinds, s, err, err_size);
    free(text);
    return ok;
}

/* Frees the pigments of s (their files' names and pixels) and forgets them. */
static void drop_pigments(struct scene *s) {
    for (size_t k = 0; k < s->pigment_count; k++) {
        free(s->pigments[k].file);
        if (!s->pigments[k].image.borrowed)
            free(s->pigments[k].image.texels);
    }
    free(s->pigments);
    s->pigments = NULL;
    s->pigment_count = 0;
}

/* Frees the meshes of s and forgets them. */
static void drop_meshes(struct scene *s) {
    for (size_t k = 0; k < s->mesh_count; k++) {
        free(s->meshes[k].path);
        free(s->meshes[k].mesh.vertices);
        free(s->meshes[k].mesh.faces);
        free(s->meshes[k].corners.normals);
        free(s->meshes[k].corners.uvs);
        free(s->meshes[k].corners.normal_faces);
        free(s->meshes[k].corners.uv_faces);
    }
    s->mesh_count = 0;
}

/* Frees the objects and instances of s (with their keys) and forgets them. */
static void drop_instances(struct scene *s) {
    for (size_t k = 0; k < s->object_count; k++) {
        free(s->objects[k].path);
        free(s->objects[k].mesh.vertices);
        free(s->objects[k].mesh.faces);
    }
    for (size_t k = 0; k < s->instance_count; k++)
        free(s->instances[k].keys);
    free(s->objects);
    free(s->instances);
    s->objects = NULL;
    s->instances = NULL;
    s->object_count = s->instance_count = 0;
}

void scene_free(struct scene *s) {
    drop_meshes(s);
    drop_instances(s);
    drop_pigments(s);
    free(s->path);
    free(s->materials);
    free(s->lights);
    for (size_t k = 0; k < s->kind_count; k++)
        free(s->shapes[k].items);
    free(s->meshes);
    memset(s, 0, sizeof *s);
}

int scene_find_material(const struct scene *s, const char *name) {
    for (size_t k = 0; k < s->material_count; k++)
        if (strcmp(s->materials[k].name, name) == 0)
            return (int)k;
    return -1;
}

/* Appends ", N thing(s)" to the note being built. */
static void note_count(char *note, size_t size, size_t count, const char *one, const char *many) {
    if (count == 0)
        return;
    size_t used = strlen(note);
    snprintf(note + used, size - used, "%s%zu %s", used == 0 ? "" : ", ", count, count == 1 ? one : many);
}

void scene_drop_unsupported(struct scene *s, int chapter, FILE *note) {
    char what[256] = "";
    for (size_t k = 0; k < s->kind_count; k++) {
        struct shape_list *list = &s->shapes[k];
        if (list->kind != NULL)
            continue;
        note_count(what, sizeof what, list->count, list->syntax->keyword, list->syntax->plural);
        list->count = 0;
        if (list->syntax == &triangle_syntax) { /* meshes are triangles too */
            note_count(what, sizeof what, s->mesh_count, "mesh", "meshes");
            drop_meshes(s);
        }
    }
    if (chapter < ANTIALIAS_CHAPTER && s->antialias.line != 0) {
        size_t used = strlen(what);
        snprintf(what + used, sizeof what - used, "%sthe antialias line", used == 0 ? "" : ", ");
        s->antialias = (struct antialias){0};
    }
    if (chapter < LENS_CHAPTER && lens_is_open(&s->lens)) {
        size_t used = strlen(what);
        snprintf(what + used, sizeof what - used, "%sthe camera's lens", used == 0 ? "" : ", ");
        s->lens.aperture = 0.0;
    }
    size_t areas = 0;
    for (size_t k = 0; chapter < AREA_LIGHT_CHAPTER && k < s->light_count; k++)
        if (area_light_is_area(&s->lights[k].area)) {
            s->lights[k].area = (struct area_light){.adaptive = AREA_LIGHT_NOT_ADAPTIVE};
            areas++;
        }
    if (areas > 0) {
        size_t used = strlen(what);
        snprintf(what + used, sizeof what - used, "%sthe area of %zu light%s", used == 0 ? "" : ", ", areas,
                 areas == 1 ? "" : "s");
    }
    if (!instance_chapter_draws(chapter, TEXTURE_CHAPTER) && s->pigment_count > 0) {
        note_count(what, sizeof what, s->pigment_count, "pigment", "pigments");
        drop_pigments(s);
        for (size_t k = 0; k < s->material_count; k++)
            s->materials[k].pigment = -1;
    }
    size_t emitting = 0;
    for (size_t k = 0; !instance_chapter_draws(chapter, PATH_CHAPTER) && k < s->material_count; k++)
        if (s->materials[k].emission.x > 0.0 || s->materials[k].emission.y > 0.0 || s->materials[k].emission.z > 0.0) {
            s->materials[k].emission = vec3_make(0, 0, 0);
            emitting++;
        }
    if (emitting > 0) {
        size_t used = strlen(what);
        snprintf(what + used, sizeof what - used, "%sthe emission of %zu material%s", used == 0 ? "" : ", ", emitting,
                 emitting == 1 ? "" : "s");
    }
    size_t rough = 0;
    for (size_t k = 0; chapter < ROUGH_CHAPTER && k < s->material_count; k++) {
        struct material *m = &s->materials[k];
        if (m->roughness > 0.0 || m->metal != SCENE_METAL_NONE || m->lobe != SCENE_LOBE_GGX) {
            m->roughness = 0.0;
            m->metal = SCENE_METAL_NONE;
            m->lobe = SCENE_LOBE_GGX;
            rough++;
        }
    }
    if (rough > 0) {
        size_t used = strlen(what);
        snprintf(what + used, sizeof what - used, "%sthe roughness of %zu material%s", used == 0 ? "" : ", ", rough,
                 rough == 1 ? "" : "s");
    }
    if (!instance_chapter_draws(chapter, PATH_CHAPTER) && s->paths.line != 0) {
        size_t used = strlen(what);
        snprintf(what + used, sizeof what - used, "%sthe paths line", used == 0 ? "" : ", ");
        s->paths = path_settings_default();
    }
    if (chapter != INSTANCE_CHAPTER) { /* chapter 17 is chapter 15's path tracer: no instances either */
        note_count(what, sizeof what, s->object_count, "object", "objects");
        note_count(what, sizeof what, s->instance_count, "instance", "instances");
        drop_instances(s);
        if (s->shutter > 0.0) {
            size_t used = strlen(what);
            snprintf(what + used, sizeof what - used, "%sthe camera's shutter", used == 0 ? "" : ", ");
            s->shutter = 0.0;
        }
    }
    if (what[0] != '\0' && note != NULL) {
        char path[4 * 1024];
        text_escape(s->path, path, sizeof path); /* the path comes from the command line */
        fprintf(note, "%s: chapter %d ignores %s (%s)\n", path, chapter, what,
                chapter == INSTANCE_CHAPTER  ? "chapter 16 is built on chapter 13's tracer"
                : chapter > INSTANCE_CHAPTER ? "chapter 17 is built on chapter 15's tracer"
                                             : "not introduced yet");
    }
}
