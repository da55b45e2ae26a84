/* stats.c: per-thread ray and intersection-test counters, summed and printed (chapter 1). */
#include "stats.h"

#include <inttypes.h>
#include <string.h>

#include "ray.h"

_Thread_local struct stats stats_thread;

void stats_add(struct stats *into, const struct stats *from) {
    into->primary_rays += from->primary_rays;
    into->pixels += from->pixels;
    if (from->camera_rays_max > into->camera_rays_max)
        into->camera_rays_max = from->camera_rays_max;
    into->shadow_rays += from->shadow_rays;
    into->reflected_rays += from->reflected_rays;
    into->refracted_rays += from->refracted_rays;
    into->sphere_tests += from->sphere_tests;
    into->triangle_tests += from->triangle_tests;
    into->triangle_tests_culled += from->triangle_tests_culled;
    into->plane_tests += from->plane_tests;
    into->box_tests += from->box_tests;
    into->node_visits += from->node_visits;
    into->instance_node_visits += from->instance_node_visits;
    into->adc_saves += from->adc_saves;
    into->crossings_capped += from->crossings_capped;
    into->budget_cut += from->budget_cut;
    into->interior_overflows += from->interior_overflows;
    into->non_finite_pixels += from->non_finite_pixels;
}

void stats_reset_thread(void) { memset(&stats_thread, 0, sizeof stats_thread); }

static void print_counter(FILE *out, const char *name, uint64_t value) {
    if (value != 0)
        fprintf(out, "  %-16s %15" PRIu64 "\n", name, value);
}

static void print_ratio(FILE *out, const char *name, uint64_t value, uint64_t per) {
    if (value != 0)
        fprintf(out, "  %-16s %15.2f\n", name, (double)value / (double)per);
}

void stats_print(FILE *out, const struct stats *s) {
    uint64_t rays = s->primary_rays + s->shadow_rays + s->reflected_rays + s->refracted_rays;
    fprintf(out, "counters:\n");
    print_counter(out, "rays (all)", rays);
    print_counter(out, "primary rays", s->primary_rays);
    print_counter(out, "shadow rays", s->shadow_rays);
    print_counter(out, "reflected rays", s->reflected_rays);
    print_counter(out, "refracted rays", s->refracted_rays);
    print_counter(out, "sphere tests", s->sphere_tests);
    print_counter(out, "triangle tests", s->triangle_tests);
    print_counter(out, "triangles culled", s->triangle_tests_culled);
    print_counter(out, "plane tests", s->plane_tests);
    print_counter(out, "box tests", s->box_tests);
    print_counter(out, "node visits", s->node_visits);
    print_counter(out, "instance nodes", s->instance_node_visits); /* the top level (chapter 16) */
    print_counter(out, "adc saves", s->adc_saves);
    print_counter(out, "crossings capped", s->crossings_capped);
    print_counter(out, "budget cuts", s->budget_cut);
    print_counter(out, "interior full", s->interior_overflows);
    uint64_t pixels = s->pixels != 0 ? s->pixels : s->primary_rays;
    if (pixels == 0)
        return;
    fprintf(out, "per pixel (with its shadow and secondary rays):\n");
    if (s->primary_rays != pixels || s->camera_rays_max > 1) {
        print_ratio(out, "camera rays", s->primary_rays, pixels);
        print_counter(out, "most camera rays", s->camera_rays_max);
    }
    print_ratio(out, "rays", rays, pixels);
    print_ratio(out, "sphere tests", s->sphere_tests, pixels);
    print_ratio(out, "triangle tests", s->triangle_tests, pixels);
    print_ratio(out, "triangles culled", s->triangle_tests_culled, pixels);
    print_ratio(out, "plane tests", s->plane_tests, pixels);
    print_ratio(out, "box tests", s->box_tests, pixels);
    print_ratio(out, "node visits", s->node_visits, pixels);
    print_ratio(out, "instance nodes", s->instance_node_visits, pixels);
}

void stats_warn_limits(FILE *out, const struct stats *s) {
    if (s->crossings_capped != 0)
        fprintf(out, "warning: %" PRIu64 " rays passed through %d surfaces without bending and were stopped there "
                "(RAY_MAX_CROSSINGS); those pixels are darker than POV-Ray's\n",
                s->crossings_capped, RAY_MAX_CROSSINGS);
    if (s->budget_cut != 0)
        fprintf(out, "warning: %" PRIu64 " secondary rays were not traced: their camera ray had spent %d already "
                "(RAY_TREE_BUDGET: secondary rays and area-light shadow rays); raise adc_bailout or lower "
                "max_depth\n",
                s->budget_cut, RAY_TREE_BUDGET);
    if (s->interior_overflows != 0)
        fprintf(out, "warning: %" PRIu64 " times a ray entered an object while already inside %d "
                "(RAY_INTERIOR_CAPACITY); those objects were not remembered\n",
                s->interior_overflows, RAY_INTERIOR_CAPACITY);
}
