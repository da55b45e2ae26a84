/* bench_instances.c: times chapter 16's two-level BVH on a scene of instances against Embree's own
 * instances (make bench-instances, one row of make bench).
 *
 *     bench_instances [--repeats N] [--size WxH] [--only ours|embree] SCENE
 *
 * SCENE is read by the scene reader of every chapter; its object and instance lines are what is traced
 * (its other shapes, such as the forest's ground plane, are not), each instance in the pose it has at
 * clock 0. The frame is bench_accel's: the scene's camera (at its image size, or --size WxH), one
 * camera ray through the centre of each pixel and, from every hit, one shadow ray to the scene's first
 * light; one thread; the processor time of the process. Each tracer builds and traces --repeats times
 * (default 3) and the fastest of each is reported.
 *
 * Ours: chapter 16's instances (instances.h), a BVH per object (chapter 11's at its default rung) and
 * the top-level BVH over the instances' world boxes; its row also gives top- and bottom-level node
 * visits and triangle tests per ray (Embree does not count them). Embree: embree_instances.c, one
 * scene per object and one RTC_GEOMETRY_TYPE_INSTANCE per instance. Both report for every pixel the
 * instance hit first and whether it is in shadow; the two frames are compared pixel by pixel, and a
 * checksum of each (FNV-1a over the pixels' instance numbers and shadows) is printed, so that a reader
 * sees both traced the same scene. Embree works in float, so a few pixels on the edges of instances or
 * shadows may differ; the count is printed. On the forest nearly all of them are in shadow in Embree's
 * frame only: its hit point, computed from a float distance on an instance placed by a float transform
 * hundreds of units from the origin, lies some 1e-4 off the surface, and a shadow ray leaving it at a
 * grazing angle meets that same surface again beyond SHADOW_T_MIN (with a margin ten times larger for
 * Embree alone, they fall from about 650 to about 50 of 480,000 pixels). make bench-instances runs
 * each tracer alone (--only) under bench/peak_rss.c, on the forest and on a forest of two instances of
 * the same objects, to find the memory each holds per instance.
 *
 * Exit status: 0; 1 for a scene that cannot be read or traced; 2 for a bad command line. */
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "clock.h"
#include "embree_instances.h"
#include "instances.h"
#include "mesh_load.h"
#include "scene.h"
#include "stats.h"
#include "transform.h"

/* The largest side --size accepts, as bench_accel's. */
#define BENCH_MAX_SIDE 16384
#define BENCH_DEFAULT_REPEATS 3
#define BENCH_MAX_REPEATS 100
/* FNV-1a's 64-bit offset basis and prime. */
#define FNV_OFFSET 0xcbf29ce484222325ULL
#define FNV_PRIME 0x100000001b3ULL

static void usage(void) {
    fprintf(stderr, "usage: bench_instances [--repeats N] [--size WxH] [--only ours|embree] SCENE\n");
    exit(2);
}

/* The processor time of the process, in milliseconds (see bench_accel.c). */
static double processor_ms(void) { return 1e3 * clock_processor_seconds(); }

/* ---- the scene as both tracers take it --------------------------------------------------------- */

/* The scene's instances in the form embree_instances.h takes: the objects' meshes (loaded into the scene
 * by load_objects), each instance's object and its transform at clock 0 (the instance line's pose, or
 * the first key's when it has keys: before its first key an instance holds that pose). */
struct forest {
    const struct mesh **meshes;
    uint32_t *instance_object;
    struct transform *to_world;
    struct instance_scene view;
    double instanced_triangles;
};

static void forest_free(struct forest *f) {
    free(f->meshes);
    free(f->instance_object);
    free(f->to_world);
    memset(f, 0, sizeof *f);
}

static bool forest_make(const struct scene *s, struct forest *f, char *err, size_t err_size) {
    memset(f, 0, sizeof *f);
    f->meshes = malloc((s->object_count + 1) * sizeof *f->meshes);
    f->instance_object = malloc((s->instance_count + 1) * sizeof *f->instance_object);
    f->to_world = malloc((s->instance_count + 1) * sizeof *f->to_world);
    if (f->meshes == NULL || f->instance_object == NULL || f->to_world == NULL) {
        snprintf(err, err_size, "out of memory");
        forest_free(f);
        return false;
    }
    for (size_t k = 0; k < s->object_count; k++)
        f->meshes[k] = &s->objects[k].mesh;
    for (size_t k = 0; k < s->instance_count; k++) {
        const struct scene_instance *in = &s->instances[k];
        const struct scene_pose *pose = in->key_count > 0 ? &in->keys[0].pose : &in->pose;
        f->instance_object[k] = (uint32_t)in->object;
        f->to_world[k] = transform_from_pose(pose->scale, pose->rotate, pose->translate);
        f->instanced_triangles += (double)s->objects[in->object].mesh.face_count;
    }
    f->view = (struct instance_scene){f->meshes, s->object_count, f->instance_object, f->to_world, s->instance_count};
    return true;
}

/* Loads every object's mesh into the scene, as instances_create would on its first call (which then
 * keeps it): so that neither tracer's build times include reading files. */
static bool load_objects(struct scene *s, char *err, size_t err_size) {
    for (size_t k = 0; k < s->object_count; k++)
        if (!mesh_load(s->objects[k].path, &s->objects[k].mesh, err, err_size))
            return false;
    return true;
}

/* ---- the frames -------------------------------------------------------------------------------- */

/* FNV-1a over every pixel's instance number and shadow. */
static uint64_t checksum(const struct instance_pixel *pixels, size_t count) {
    uint64_t h = FNV_OFFSET;
    for (size_t k = 0; k < count; k++) {
        uint32_t instance = pixels[k].instance;
        unsigned char bytes[5] = {(unsigned char)instance, (unsigned char)(instance >> 8),
                                  (unsigned char)(instance >> 16), (unsigned char)(instance >> 24),
                                  (unsigned char)pixels[k].shadowed};
        for (int b = 0; b < 5; b++)
            h = (h ^ bytes[b]) * FNV_PRIME;
    }
    return h;
}

/* One tracer's results: the fastest build of each level and frame, and what the frame saw. */
struct result {
    bool done;
    double objects_ms, top_ms, frame_ms;
    double rays;                         /* camera and shadow rays */
    double top_visits, bottom_visits, triangle_tests; /* ours only: per frame */
    double instanced_triangles;          /* the triangles of every instance's object, summed */
    long hits, shadowed;
    uint64_t checksum;
};

static void summarise(const struct instance_pixel *pixels, size_t count, struct result *r) {
    r->hits = 0;
    r->shadowed = 0;
    for (size_t k = 0; k < count; k++) {
        r->hits += pixels[k].instance != INSTANCE_PIXEL_NONE;
        r->shadowed += pixels[k].shadowed;
    }
    r->rays = (double)count + (double)r->hits;
    r->checksum = checksum(pixels, count);
}

/* Prints a value, or "-" when it does not apply (NAN). */
static void print_number(int width, double x, int decimals) {
    if (isnan(x))
        printf(" %*s", width, "-");
    else
        printf(" %*.*f", width, decimals, x);
}

static void print_row(const char *label, const struct result *r, const struct result *embree) {
    bool ours = !isnan(r->top_visits);
    printf("  %-14s", label);
    print_number(10, r->objects_ms, 1);
    print_number(9, r->top_ms, 1);
    print_number(9, r->frame_ms, 1);
    print_number(7, r->rays / (r->frame_ms * 1e3), 2);
    print_number(7, ours ? r->top_visits / r->rays : NAN, 1);
    print_number(7, ours ? r->bottom_visits / r->rays : NAN, 1);
    print_number(7, ours ? r->triangle_tests / r->rays : NAN, 1);
    bool ratios = embree != NULL && embree->done && r != embree;
    print_number(7, ratios ? r->frame_ms / embree->frame_ms : NAN, 2);
    print_number(7, ratios ? (r->objects_ms + r->top_ms) / (embree->objects_ms + embree->top_ms) : NAN, 2);
    printf(" %7ld %7ld  %016" PRIx64 "\n", r->hits, r->shadowed, r->checksum);
}

/* A shadow ray's visitor: any crossing hides the light, so the walk stops at the first. */
static bool stop_at_first(void *context, double t, int material) {
    (void)context;
    (void)t;
    (void)material;
    return false;
}

/* Traces the frame through chapter 16's instances into pixels, counting into stats_thread; returns the
 * elapsed ms. */
static double ours_trace(const struct instances *in, const struct camera *cam, vec3 light,
                         struct instance_pixel *pixels) {
    const struct world_instances *q = &in->hook;
    stats_reset_thread();
    double start = processor_ms();
    for (int j = 0; j < cam->height; j++)
        for (int i = 0; i < cam->width; i++) {
            ray r = camera_ray(cam, i, j);
            struct hit h = hit_nothing(INFINITY);
            struct instance_pixel p = {INSTANCE_PIXEL_NONE, false};
            if (q->closest(q->structure, &r, RAY_T_MIN, 0.0, &h)) {
                p.instance = (uint32_t)(h.object - in->first_object);
                vec3 point = ray_at(r, h.t);
                vec3 to_light = vec3_sub(light, point);
                double distance = vec3_length(to_light);
                ray shadow = {point, vec3_scale(to_light, 1.0 / distance)};
                p.shadowed = !q->for_each_crossing(q->structure, &shadow, SHADOW_T_MIN, distance - SHADOW_T_MIN, 0.0,
                                                   stop_at_first, NULL);
            }
            pixels[(size_t)j * cam->width + i] = p;
        }
    return processor_ms() - start;
}

/* Builds chapter 16's instances of s and traces the frame, `repeats` times, into *r and pixels. The
 * top level's time is that of instances_set_interval rebuilding it (the instances' world boxes and the
 * tree over them); the objects' is the rest of instances_create (each object's BVH, and placing the
 * instances: their transforms and inverses). */
static bool ours_frame(struct scene *s, const struct camera *cam, vec3 light, int repeats, struct result *r,
                       struct instance_pixel *pixels, char *err, size_t err_size) {
    *r = (struct result){.done = true, .objects_ms = INFINITY, .top_ms = INFINITY, .frame_ms = INFINITY};
    for (int k = 0; k < repeats; k++) {
        double start = processor_ms();
        struct instances *in = instances_create(s, 0, 0.0, 0.0, err, err_size);
        if (in == NULL)
            return false;
        double created = processor_ms();
        if (!instances_set_interval(in, 0.0, 0.0, INSTANCES_REBUILD, err, err_size)) {
            instances_free(in);
            return false;
        }
        double top_ms = processor_ms() - created;
        double frame_ms = ours_trace(in, cam, light, pixels);
        r->objects_ms = fmin(r->objects_ms, created - start - top_ms);
        r->top_ms = fmin(r->top_ms, top_ms);
        if (frame_ms < r->frame_ms) {
            r->frame_ms = frame_ms;
            r->top_visits = (double)stats_thread.instance_node_visits;
            r->bottom_visits = (double)stats_thread.node_visits;
            r->triangle_tests = (double)stats_thread.triangle_tests;
        }
        r->instanced_triangles = in->info.instanced_triangles;
        instances_free(in);
    }
    return true;
}

int main(int argc, char **argv) {
    int repeats = BENCH_DEFAULT_REPEATS, width = 0, height = 0;
    bool run_ours = true, run_embree = true;
    int a = 1;
    for (; a + 1 < argc && strncmp(argv[a], "--", 2) == 0; a += 2) {
        char *end;
        if (strcmp(argv[a], "--repeats") == 0) {
            long n = strtol(argv[a + 1], &end, 10);
            if (*end != '\0' || n < 1 || n > BENCH_MAX_REPEATS)
                usage();
            repeats = (int)n;
        } else if (strcmp(argv[a], "--size") == 0) {
            int used = 0;
            if (sscanf(argv[a + 1], "%dx%d%n", &width, &height, &used) != 2 || argv[a + 1][used] != '\0' ||
                width < 1 || height < 1 || width > BENCH_MAX_SIDE || height > BENCH_MAX_SIDE)
                usage();
        } else if (strcmp(argv[a], "--only") == 0) {
            run_ours = strcmp(argv[a + 1], "ours") == 0;
            run_embree = strcmp(argv[a + 1], "embree") == 0;
            if (!run_ours && !run_embree)
                usage();
        } else {
            usage();
        }
    }
    if (a + 1 != argc)
        usage();

    char err[512];
    struct scene s;
    if (!scene_load(argv[a], NULL, &s, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    struct camera cam;
    if (s.instance_count == 0 || s.light_count == 0) {
        fprintf(stderr, "%s: no instances or no light to trace\n", argv[a]);
        scene_free(&s);
        return 1;
    }
    if (!camera_init(&cam, s.eye, s.target, s.up, s.fov, width ? width : s.width, height ? height : s.height, err,
                     sizeof err)) {
        fprintf(stderr, "%s: %s\n", argv[a], err);
        scene_free(&s);
        return 1;
    }
    vec3 light = s.lights[0].position;
    if (!load_objects(&s, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        scene_free(&s);
        return 1;
    }
    size_t pixel_count = (size_t)cam.width * (size_t)cam.height;
    struct instance_pixel *ours_pixels = malloc(pixel_count * sizeof *ours_pixels);
    struct instance_pixel *embree_pixels = malloc(pixel_count * sizeof *embree_pixels);
    struct result ours = {0}, embree = {0};
    struct forest forest = {0};
    bool ok = ours_pixels != NULL && embree_pixels != NULL;
    if (!ok)
        snprintf(err, sizeof err, "out of memory");
    if (ok && run_ours) {
        ok = ours_frame(&s, &cam, light, repeats, &ours, ours_pixels, err, sizeof err);
        if (ok)
            summarise(ours_pixels, pixel_count, &ours);
    }
    if (ok && run_embree) {
        struct embree_instance_times times;
        ok = forest_make(&s, &forest, err, sizeof err) &&
             embree_instances_frame(&forest.view, &cam, light, repeats, &times, embree_pixels, err, sizeof err);
        if (ok) {
            embree = (struct result){.done = true, .objects_ms = times.objects_ms, .top_ms = times.top_ms,
                                     .frame_ms = times.frame_ms, .top_visits = NAN, .bottom_visits = NAN,
                                     .triangle_tests = NAN,
                                     .instanced_triangles = forest.instanced_triangles};
            summarise(embree_pixels, pixel_count, &embree);
        }
    }
    if (!ok) {
        fprintf(stderr, "%s\n", err);
        free(ours_pixels);
        free(embree_pixels);
        forest_free(&forest);
        scene_free(&s);
        return 1;
    }

    printf("%s: %zu instances of %zu objects (%.0f triangles instanced), %dx%d, 1 thread, best of %d:\n", argv[a],
           s.instance_count, s.object_count, ours.done ? ours.instanced_triangles : embree.instanced_triangles,
           cam.width, cam.height, repeats);
    printf("  %-14s %10s %9s %9s %7s %7s %7s %7s %7s %7s %7s %7s  %-16s\n", "tracer", "objects ms", "top ms",
           "frame ms", "Mrays/s", "top/ray", "bot/ray", "tri/ray", "frame/E", "build/E", "hits", "shadow",
           "checksum");
    if (ours.done)
        print_row("ours", &ours, &embree);
    if (embree.done)
        print_row("Embree 3", &embree, NULL);
    if (ours.done && embree.done) {
        long instance_differs = 0, embree_shadow_only = 0, ours_shadow_only = 0;
        for (size_t k = 0; k < pixel_count; k++) {
            const struct instance_pixel *o = &ours_pixels[k], *e = &embree_pixels[k];
            instance_differs += o->instance != e->instance;
            embree_shadow_only += o->instance == e->instance && e->shadowed && !o->shadowed;
            ours_shadow_only += o->instance == e->instance && o->shadowed && !e->shadowed;
        }
        printf("  of %zu pixels, ours and Embree see another instance on %ld; the same, but in shadow in Embree's "
               "frame alone on %ld, in ours alone on %ld\n", pixel_count, instance_differs, embree_shadow_only,
               ours_shadow_only);
    }
    free(ours_pixels);
    free(embree_pixels);
    forest_free(&forest);
    scene_free(&s);
    return 0;
}
