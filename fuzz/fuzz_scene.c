/* fuzz_scene.c: libFuzzer harness for the scene parser, scene_parse on text in memory (make fuzz).
 *
 * Every input is a scene text. The parser must either refuse it with "fuzz.scene:LINE: what is wrong"
 * (or "fuzz.scene: what is wrong"), or accept it and give a scene that keeps the promises the
 * chapters rely on: a size within the limits, a depth of at least 1, finite numbers, positive radii,
 * boxes with min < max, and every material index naming a material; Part III's lines within
 * their limits (check_part_three); and Part IV's (check_part_four). Inputs holding a zero byte are
 * skipped: scene_read_text refuses those before the parser sees them, so no file could reach it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "box.h"
#include "instance_syntax.h"
#include "fuzz_support.h"
#include "plane.h"
#include "scene.h"
#include "sphere.h"
#include "triangle.h"

#define NAME "fuzz.scene"

/* A plane's normal is normalised by the parser; rounding leaves its length within a few units in the
 * last place of 1, far inside this. */
#define PLANE_NORMAL_TOLERANCE 1e-9

static void check_material(const struct scene *s, int material, const char *what, size_t k) {
    if (material < 0 || (size_t)material >= s->material_count)
        fuzz_abort("%s %zu has material %d of %zu", what, k, material, s->material_count);
}

static void check_finite(vec3 v, const char *what, size_t k) {
    if (!vec3_is_finite(v))
        fuzz_abort("%s %zu has a non-finite vector (%g %g %g)", what, k, v.x, v.y, v.z);
}

/* The promises of an accepted scene. */
static void check_scene(const struct scene *s) {
    if (s->width < 1 || s->height < 1 || s->max_depth < 1)
        fuzz_abort("accepted image %d x %d, max_depth %d", s->width, s->height, s->max_depth);
    if (!vec3_is_finite(s->eye) || !vec3_is_finite(s->target) || !vec3_is_finite(s->up) || !isfinite(s->fov))
        fuzz_abort("accepted a camera with a non-finite number");
    if (s->material_count == 0 || strcmp(s->materials[0].name, "default") != 0)
        fuzz_abort("materials[0] is not the default material");
    for (size_t k = 0; k < s->material_count; k++) {
        const struct material *m = &s->materials[k];
        double numbers[] = {m->ambient, m->diffuse, m->phong, m->phong_size, m->reflection, m->filter, m->transmit,
                            m->ior};
        for (size_t n = 0; n < sizeof numbers / sizeof *numbers; n++)
            if (!isfinite(numbers[n]))
                fuzz_abort("material %zu has a non-finite value", k);
        check_finite(m->colour, "material", k);
        if (memchr(m->name, '\0', sizeof m->name) == NULL)
            fuzz_abort("material %zu has an unterminated name", k);
    }
    for (size_t k = 0; k < s->light_count; k++) {
        check_finite(s->lights[k].position, "light", k);
        check_finite(s->lights[k].colour, "light", k);
    }
    const struct shape_list *spheres = scene_shapes(s, &sphere_syntax), *planes = scene_shapes(s, &plane_syntax),
                            *triangles = scene_shapes(s, &triangle_syntax), *boxes = scene_shapes(s, &box_syntax);
    for (size_t k = 0; k < spheres->count; k++) {
        const struct sphere *sphere = (const struct sphere *)spheres->items + k;
        check_finite(sphere->centre, "sphere", k);
        if (!(sphere->radius > 0.0) || !isfinite(sphere->radius))
            fuzz_abort("sphere %zu has radius %g", k, sphere->radius);
        check_material(s, sphere->material, "sphere", k);
    }
    for (size_t k = 0; k < planes->count; k++) {
        const struct plane *plane = (const struct plane *)planes->items + k;
        check_finite(plane->normal, "plane", k);
        double length = vec3_length(plane->normal);
        if (!isfinite(plane->distance) || !(fabs(length - 1.0) < PLANE_NORMAL_TOLERANCE))
            fuzz_abort("plane %zu has distance %g and a normal of length %g", k, plane->distance, length);
        check_material(s, plane->material, "plane", k);
    }
    for (size_t k = 0; k < triangles->count; k++) {
        const struct triangle *triangle = (const struct triangle *)triangles->items + k;
        check_finite(triangle->a, "triangle", k);
        check_finite(triangle->b, "triangle", k);
        check_finite(triangle->c, "triangle", k);
        check_material(s, triangle->material, "triangle", k);
    }
    for (size_t k = 0; k < boxes->count; k++) {
        const struct box *b = (const struct box *)boxes->items + k;
        check_finite(b->min, "box", k);
        check_finite(b->max, "box", k);
        if (!(b->min.x < b->max.x && b->min.y < b->max.y && b->min.z < b->max.z))
            fuzz_abort("box %zu does not have min < max", k);
        check_material(s, b->material, "box", k);
    }
    for (size_t k = 0; k < s->mesh_count; k++) {
        const struct scene_mesh *m = &s->meshes[k];
        if (m->path == NULL || !isfinite(m->scale))
            fuzz_abort("mesh %zu has no path or a non-finite scale", k);
        check_finite(m->rotate, "mesh", k);
        check_finite(m->translate, "mesh", k);
        check_material(s, m->material, "mesh", k);
    }
}

/* The promises of Part III's lines (chapters 12 to 15): every count within the limit its header
 * states, the lens's numbers finite, every pigment's transform finite with no zero scale, every
 * material's pigment naming a pigment, emission finite and not negative. */
static void check_part_three(const struct scene *s) {
    const struct antialias *a = &s->antialias;
    int most = a->method == ANTIALIAS_RECURSIVE ? ANTIALIAS_MAX_DEPTH
               : a->method == ANTIALIAS_ADAPTIVE ? ANTIALIAS_MAX_ADAPTIVE : ANTIALIAS_MAX_SAMPLES;
    if (a->line != 0 && (a->samples < 1 || a->samples > most || !(a->threshold >= 0.0)))
        fuzz_abort("accepted antialias samples %d, threshold %g", a->samples, a->threshold);
    if (!isfinite(s->lens.aperture) || s->lens.aperture < 0.0 || !vec3_is_finite(s->lens.focal_point) ||
        (s->lens.blur_samples != 7 && s->lens.blur_samples != 19 && s->lens.blur_samples != 37))
        fuzz_abort("accepted a lens of aperture %g, %d blur samples", s->lens.aperture, s->lens.blur_samples);
    for (size_t k = 0; k < s->light_count; k++) {
        const struct area_light *area = &s->lights[k].area;
        if (area->size1 < 0 || area->size1 > AREA_LIGHT_MAX_SIZE || area->size2 < 0 ||
            area->size2 > AREA_LIGHT_MAX_SIZE || (area->size1 == 0) != (area->size2 == 0))
            fuzz_abort("light %zu has an area of %d x %d points", k, area->size1, area->size2);
        check_finite(area->axis1, "light", k);
        check_finite(area->axis2, "light", k);
    }
    for (size_t k = 0; k < s->pigment_count; k++) {
        const struct pigment *p = &s->pigments[k];
        check_finite(p->scale, "pigment", k);
        check_finite(p->rotate, "pigment", k);
        check_finite(p->translate, "pigment", k);
        if (p->scale.x == 0.0 || p->scale.y == 0.0 || p->scale.z == 0.0)
            fuzz_abort("pigment %zu has a zero scale", k);
        if ((p->pattern == PIGMENT_IMAGE_MAP) != (p->file != NULL))
            fuzz_abort("pigment %zu is%s an image map with%s a file", k, p->file != NULL ? " not" : "",
                       p->file != NULL ? "" : "out");
    }
    for (size_t k = 0; k < s->material_count; k++) {
        const struct material *m = &s->materials[k];
        if (m->pigment < -1 || m->pigment >= (int)s->pigment_count)
            fuzz_abort("material %zu has pigment %d of %zu", k, m->pigment, s->pigment_count);
        check_finite(m->emission, "material", k);
        if (m->emission.x < 0.0 || m->emission.y < 0.0 || m->emission.z < 0.0)
            fuzz_abort("material %zu has a negative emission", k);
    }
    const struct path_settings *paths = &s->paths;
    if (paths->samples < 1 || paths->samples > PATH_MAX_SAMPLES || paths->bounces < 0 ||
        paths->bounces > PATH_MAX_BOUNCES || paths->roulette < 0 || paths->roulette > PATH_MAX_BOUNCES)
        fuzz_abort("accepted paths samples %d, bounces %d, roulette %d", paths->samples, paths->bounces,
                   paths->roulette);
}

/* A pose the instance reader accepted: every scale factor's size within INSTANCE_SCALE_MIN ..
 * INSTANCE_SCALE_MAX, every angle within INSTANCE_ANGLE_MAX degrees, the translation within
 * KEY_MAX_COORD (instance_syntax.h). */
static void check_pose(const struct scene_pose *pose, const char *what, size_t k) {
    double scale[] = {pose->scale.x, pose->scale.y, pose->scale.z};
    double rotate[] = {pose->rotate.x, pose->rotate.y, pose->rotate.z};
    double translate[] = {pose->translate.x, pose->translate.y, pose->translate.z};
    for (int a = 0; a < 3; a++)
        if (!(fabs(scale[a]) >= INSTANCE_SCALE_MIN && fabs(scale[a]) <= INSTANCE_SCALE_MAX) ||
            !(fabs(rotate[a]) <= INSTANCE_ANGLE_MAX) || !(fabs(translate[a]) <= KEY_MAX_COORD))
            fuzz_abort("%s %zu has scale %g, rotate %g, translate %g on axis %d", what, k, scale[a], rotate[a],
                       translate[a], a);
}

/* The promises of Part IV's lines (chapters 16 and 17): the shutter within 0 .. 1; at most
 * SCENE_OBJECT_MAX objects, each with a file and a terminated name; at most SCENE_INSTANCE_MAX
 * instances, each placing an object and naming a material, with at most SCENE_KEY_MAX keys in strictly
 * increasing time within 0 .. 1, and every pose within its limits; every material's roughness within
 * 0 .. 1, its metal and lobe one of their words. */
static void check_part_four(const struct scene *s) {
    if (!(s->shutter >= 0.0 && s->shutter <= 1.0))
        fuzz_abort("accepted a shutter of %g", s->shutter);
    if (s->object_count > SCENE_OBJECT_MAX || s->instance_count > SCENE_INSTANCE_MAX)
        fuzz_abort("accepted %zu objects and %zu instances", s->object_count, s->instance_count);
    for (size_t k = 0; k < s->object_count; k++)
        if (s->objects[k].path == NULL || memchr(s->objects[k].name, '\0', sizeof s->objects[k].name) == NULL)
            fuzz_abort("object %zu has no path or an unterminated name", k);
    for (size_t k = 0; k < s->instance_count; k++) {
        const struct scene_instance *in = &s->instances[k];
        if (in->object < 0 || (size_t)in->object >= s->object_count)
            fuzz_abort("instance %zu places object %d of %zu", k, in->object, s->object_count);
        check_material(s, in->material, "instance", k);
        if (memchr(in->id, '\0', sizeof in->id) == NULL)
            fuzz_abort("instance %zu has an unterminated id", k);
        check_pose(&in->pose, "instance", k);
        if (in->key_count > SCENE_KEY_MAX || (in->keys == NULL) != (in->key_count == 0))
            fuzz_abort("instance %zu has %zu keys", k, in->key_count);
        for (size_t j = 0; j < in->key_count; j++) {
            const struct scene_key *key = &in->keys[j];
            if (!(key->time >= 0.0 && key->time <= 1.0) || (j > 0 && !(key->time > in->keys[j - 1].time)))
                fuzz_abort("instance %zu's key %zu has time %g", k, j, key->time);
            check_pose(&key->pose, "key", j);
        }
    }
    for (size_t k = 0; k < s->material_count; k++) {
        const struct material *m = &s->materials[k];
        if (!(m->roughness >= 0.0 && m->roughness <= 1.0) || m->metal < 0 || m->metal >= SCENE_METAL_COUNT ||
            (m->lobe != SCENE_LOBE_GGX && m->lobe != SCENE_LOBE_PHONG))
            fuzz_abort("material %zu has roughness %g, metal %d, lobe %d", k, m->roughness, (int)m->metal,
                       (int)m->lobe);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (memchr(data, '\0', size) != NULL)
        return 0;
    char *text = fuzz_copy_with_nul(data, size);
    struct scene s;
    char err[512] = "";
    if (scene_parse(NAME, text, NULL, &s, err, sizeof err)) {
        check_scene(&s);
        check_part_three(&s);
        check_part_four(&s);
        scene_free(&s);
    } else if (!fuzz_message_names(err, NAME)) {
        fuzz_abort("refused with a message that does not start with '" NAME ":': '%s'", err);
    }
    free(text);
    return 0;
}
