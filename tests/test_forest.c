/* test_forest.c: tools/models/forest.c, the generator of chapter 16's forest (make bench-instances),
 * writes the instances it is asked for, alternating the teapot and the bunny, in lines every chapter
 * reads, the same file on every run and machine; it refuses a bad command line and leaves no file when
 * it cannot write. When the benchmark bench/bench_instances.c has been built (make bench, with Embree),
 * it also checks that our instances and Embree's see the same instances on a small forest. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene.h"
#include "test_support.h"

#define FOREST_PROGRAM "build/forest" /* MODELS_FOREST in tools/models/models.mk */
#define FOREST_DIR "out/test/forest"
/* The forest's scenes live three folders below the top of the tree. */
#define FOREST_MODELS "../../../scenes/models"
/* The default forest's first instance, to the last digit: the hash of its index, the same on every machine. */
#define FOREST_FIRST_INSTANCE                                                                                      \
    "instance teapot material gold scale 0.8235 1.0436 1.0714 rotate 0.2679 281.6028 -5.7728 translate -395.5677 0 " \
    "-397.3181\n"

/* Runs the generator with `arguments`, its output in a log; returns its exit status. */
static int run_forest(const char *arguments) {
    char command[512], output[1024];
    cr_assert_eq(system("mkdir -p " FOREST_DIR), 0);
    snprintf(command, sizeof command, FOREST_PROGRAM " %s", arguments);
    return run_capturing(command, output, sizeof output);
}

Test(forest, writes_the_instances_asked_for_alternating_teapot_and_bunny) {
    cr_assert_eq(run_forest("--instances 5 --models " FOREST_MODELS " " FOREST_DIR "/five.scene"), 0);
    struct scene s;
    char err[256];
    cr_assert(scene_load(FOREST_DIR "/five.scene", NULL, &s, err, sizeof err), "%s", err);
    cr_assert_eq(s.object_count, 2);
    cr_assert_str_eq(s.objects[0].name, "teapot");
    cr_assert_str_eq(s.objects[1].name, "bunny");
    cr_assert(strstr(s.objects[0].path, "scenes/models/teapot-346k.ply") != NULL, "%s", s.objects[0].path);
    cr_assert_eq(s.instance_count, 5);
    for (size_t k = 0; k < s.instance_count; k++) {
        cr_assert_eq(s.instances[k].object, (int)(k % 2), "instance %zu", k);
        cr_assert_eq(s.instances[k].pose.translate.y, 0.0, "instance %zu stands on the ground", k);
    }
    cr_assert_eq(s.light_count, 1);
    scene_free(&s);
}

Test(forest, is_the_same_file_on_every_run) {
    cr_assert_eq(run_forest("--models " FOREST_MODELS " " FOREST_DIR "/a.scene"), 0);
    cr_assert_eq(run_forest("--models " FOREST_MODELS " " FOREST_DIR "/b.scene"), 0);
    char *a = read_text_file(FOREST_DIR "/a.scene"), *b = read_text_file(FOREST_DIR "/b.scene");
    cr_assert_str_eq(a, b);
    size_t instances = 0;
    for (const char *line = a; line != NULL; line = strchr(line, '\n'), line = line ? line + 1 : NULL)
        instances += strncmp(line, "instance ", 9) == 0;
    cr_assert_eq(instances, 10000, "the default forest has 10,000 instances, not %zu", instances);
    const char *first = strstr(a, "\ninstance ");
    cr_assert_not_null(first);
    cr_assert_eq(strncmp(first + 1, FOREST_FIRST_INSTANCE, strlen(FOREST_FIRST_INSTANCE)), 0, "%.200s", first + 1);
    free(a);
    free(b);
}

Test(forest, refuses_a_bad_command_line_and_leaves_no_file_it_cannot_write) {
    cr_assert_eq(run_forest("--instances 0 " FOREST_DIR "/bad.scene"), 2);
    cr_assert_eq(run_forest("--instances 1000001 " FOREST_DIR "/bad.scene"), 2);
    cr_assert_eq(run_forest("--instances 12x " FOREST_DIR "/bad.scene"), 2);
    cr_assert_eq(run_forest("--trees 5 " FOREST_DIR "/bad.scene"), 2);
    cr_assert_eq(run_forest(""), 2);
    cr_assert_eq(access(FOREST_DIR "/bad.scene", F_OK), -1, "a refused command line wrote a file");
    cr_assert_eq(run_forest(FOREST_DIR "/no-such-folder/x.scene"), 3);
    cr_assert_eq(access(FOREST_DIR "/no-such-folder", F_OK), -1);
}

/* The hits, shadows and differing pixels the benchmark printed, read from its table. */
Test(forest, our_instances_and_embrees_see_the_same_instances, .timeout = 120) {
    const char *build = getenv("WHITTED_BUILD");
    char program[256];
    snprintf(program, sizeof program, "%s/bench_instances", build != NULL ? build : "build");
    if (access(program, X_OK) != 0)
        cr_skip_test("%s is built by make bench-instances (with Embree)", program);
    cr_assert_eq(run_forest("--instances 100 --models " FOREST_MODELS " " FOREST_DIR "/hundred.scene"), 0);
    char command[512], output[4096];
    snprintf(command, sizeof command, "%s --repeats 1 --size 160x120 " FOREST_DIR "/hundred.scene", program);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    long ours_hits, embree_hits, another, pixels, embree_alone, ours_alone;
    const char *ours = strstr(output, "\n  ours "), *embree = strstr(output, "\n  Embree 3 ");
    const char *differ = strstr(output, "\n  of ");
    cr_assert(ours != NULL && embree != NULL && differ != NULL, "%s", output);
    /* hits: the tenth column of both rows (Embree's has "-" for the counters and ratios) */
    cr_assert_eq(sscanf(ours, " ours %*f %*f %*f %*f %*f %*f %*f %*f %*f %ld", &ours_hits), 1, "%s", output);
    cr_assert_eq(sscanf(embree, " Embree 3 %*f %*f %*f %*f - - - - - %ld", &embree_hits), 1, "%s", output);
    cr_assert_eq(sscanf(differ, " of %ld pixels, ours and Embree see another instance on %ld; the same, but in shadow "
                                "in Embree's frame alone on %ld, in ours alone on %ld",
                        &pixels, &another, &embree_alone, &ours_alone),
                 4, "%s", output);
    cr_assert_eq(pixels, 160 * 120);
    cr_assert_gt(ours_hits, pixels / 10, "the forest fills little of the frame: %s", output);
    /* float against double: a pixel on an instance's edge now and then, a shadow's edge more often */
    cr_assert_leq(labs(ours_hits - embree_hits), pixels / 1000, "%s", output);
    cr_assert_leq(another, pixels / 1000, "%s", output);
    cr_assert_leq(embree_alone + ours_alone, pixels / 100, "%s", output);
}
