/* test_coursework_proof.c: the coursework kit's checks catch what they are for (docs/coursework.md, "How
 * the kit is proved"): each planted fault (the patches in tests/checks/faults/: a crash, an endless loop, a slab
 * test that lets a NaN win, a forgotten counter, forgotten slivers, a shadow ray without its end margin)
 * built into the grader makes the tasks it names fail, with the words the fault's Says line gives; so do
 * two gallery faults, with the messages docs/coursework.md quotes. And make exercises grades a started
 * build exercise: the model answers pass, the wrong answers fail with their messages.
 *
 * These need the model answers (the faults are wrong versions of reference bodies), so a student copy
 * leaves this file out. Each proof builds one patched file and the grader, from this build's objects. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

/* The limit for one check while proving the endless loop: short, so the proof is quick. */
#define PROOF_CHECK_SECONDS "2"

#define FAULTS_MAX 32

struct fault {
    char patch[128]; /* the patch, from the repository root */
    char says[160];  /* what the report must say, when the patch's own Says line does not */
};

static struct fault faults[FAULTS_MAX];

/* The planted faults, and the gallery's faults whose messages docs/coursework.md quotes. */
static size_t find_faults(void) {
    size_t count = 0;
    glob_t found;
    if (glob("tests/checks/faults/*.patch", 0, NULL, &found) == 0) {
        for (size_t k = 0; k < found.gl_pathc && count < FAULTS_MAX; k++)
            snprintf(faults[count++].patch, sizeof faults[0].patch, "%s", found.gl_pathv[k]);
        globfree(&found);
    }
    static const struct fault quoted[] = {
        {"tools/gallery/02-far-root-first.patch",
         "sphere_intersect: the hit is 4.0 along the ray for a sphere 5 away with radius 1; your code returned 6.0: "
         "the far root?"},
        {"tools/gallery/05-slab-without-swap.patch", "it said the ray misses: the slabs entered from the far side? "
                                                     "Moving towards minus, the ray meets the high plane first: swap t0 "
                                                     "and t1 when 1/d < 0"},
    };
    for (size_t k = 0; k < sizeof quoted / sizeof quoted[0] && count < FAULTS_MAX; k++)
        faults[count++] = quoted[k];
    return count;
}

ParameterizedTestParameters(coursework_proof, every_planted_fault_is_reported) {
    size_t count = find_faults();
    return cr_make_param_array(struct fault, faults, count);
}

ParameterizedTest(struct fault *f, coursework_proof, every_planted_fault_is_reported, .timeout = 300) {
    const char *build = getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build";
    char command[1024], log[256], name[128];
    snprintf(name, sizeof name, "%s", strrchr(f->patch, '/') + 1);
    snprintf(log, sizeof log, "out/test/coursework-proof-%s.log", name);
    remove(log);
    snprintf(command, sizeof command, "WHITTED_CHECK_SECONDS=%s tests/checks/prove_fault.sh %s %s '%s'",
             PROOF_CHECK_SECONDS, build, f->patch, f->says);
    int status = run_logged(command, log);
    cr_assert_eq(status, 0, "%s: %s (see %s)", f->patch,
                 status == 1 ? "a task it names is not reported, or the report lacks the words" : "it does not build",
                 log);
}

Test(coursework_proof, there_is_a_planted_fault_for_each_new_kind_of_check) {
    static const char *const kinds[] = {"crashes", "never-returns", "nan", "not-counted", "slivers", "end-margin", "window-closed", "warns"};
    size_t count = find_faults();
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        bool found = false;
        for (size_t f = 0; f < count; f++)
            found = found || strstr(faults[f].patch, kinds[k]) != NULL;
        cr_expect(found, "no fault in tests/checks/faults/ is named for \"%s\"", kinds[k]);
    }
}

/* common/exercise_answers.c for the proof below: each function a build exercise asks for, answered by the
 * model answer (prefix "solution") or the wrong one ("wrong") of tests/exercises/solutions.c. */
static void write_answers(const char *path, const char *prefix) {
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f, "cannot write %s", path);
    fprintf(f,
            "#include \"../tests/exercises/solutions.c\"\n"
            "void mesh_vertex_normals(const struct mesh *m, vec3 *normals) { %1$s_mesh_vertex_normals(m, normals); }\n"
            "bool cylinder_intersect(vec3 base, double radius, double height, const ray *r, double t_min, double t_max,\n"
            "                        double *t) { return %1$s_cylinder_intersect(base, radius, height, r, t_min, t_max, t); }\n"
            "void mesh_bounding_sphere(const struct mesh *m, vec3 *centre, double *radius) {\n"
            "    %1$s_mesh_bounding_sphere(m, centre, radius);\n}\n"
            "double phong_blinn_highlight(vec3 normal, vec3 to_light, vec3 to_eye, double exponent) {\n"
            "    return %1$s_phong_blinn_highlight(normal, to_light, to_eye, exponent);\n}\n"
            "double shadow_area_fraction(const void *world, vec3 point, vec3 corner, vec3 edge_u, vec3 edge_v, int n) {\n"
            "    return %1$s_shadow_area_fraction(world, point, corner, edge_u, edge_v, n);\n}\n"
            "double whitted_schlick(double c, double n1, double n2) { return %1$s_whitted_schlick(c, n1, n2); }\n"
            "int grid_walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max) {\n"
            "    return %1$s_grid_walk(lo, hi, cells, r, out, max);\n}\n"
            "double bvh_split_cost(const struct aabb *boxes, int n, int axis, double plane) {\n"
            "    return %1$s_bvh_split_cost(boxes, n, axis, plane);\n}\n"
            "int bvh4_collapse(const struct bvh2_node *tree, int root, struct bvh4_node *out, int max) {\n"
            "    return %1$s_bvh4_collapse(tree, root, out, max);\n}\n"
            "void supersample_rooks(int i, int j, int n, uint32_t seed, double *x, double *y) {\n"
            "    %1$s_supersample_rooks(i, j, n, seed, x, y);\n}\n"
            "void thin_lens_concentric(double u, double v, double *x, double *y) {\n"
            "    %1$s_thin_lens_concentric(u, v, x, y);\n}\n"
            "bool image_map_cylindrical(vec3 q, double *u, double *v) {\n"
            "    return %1$s_image_map_cylindrical(q, u, v);\n}\n"
            "bool sampling_sphere_cone(vec3 centre, double radius, vec3 point, double u1, double u2, vec3 *direction,\n"
            "                          double *density) {\n"
            "    return %1$s_sampling_sphere_cone(centre, radius, point, u1, u2, direction, density);\n}\n"
            "void keyframes_slerp(const double q0[4], const double q1[4], double t, double out[4]) {\n"
            "    %1$s_keyframes_slerp(q0, q1, t, out);\n}\n"
            "vec3 microfacet_ggx_sample_normal(double alpha, double u1, double u2) {\n"
            "    return %1$s_microfacet_ggx_sample_normal(alpha, u1, u2);\n}\n",
            prefix);
    fclose(f);
}

/* The number of build exercises: the rows of the table in tests/exercises/runner/run.sh. */
static int exercise_count(void) {
    char output[64];
    cr_assert_eq(run_capturing("sed -n \"/<<'TABLE'/,/^TABLE$/p\" tests/exercises/runner/run.sh | grep -c '|'", output,
                               sizeof output), 0);
    int n = atoi(output);
    cr_assert_geq(n, 12, "tests/exercises/runner/run.sh lists %d exercises", n);
    return n;
}

/* Makes work (a template for mkdtemp) a copy of what make exercises needs, with this build's objects, and
 * one more module, common/exercise_answers.c, for the answers. Returns whether the build is SAN's. */
static int exercise_copy(char *work) {
    const char *build = getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build";
    char command[2048];
    cr_assert_not_null(mkdtemp(work));
    snprintf(command, sizeof command,
             "cp -rp Makefile common chapters bench fuzz tools tests %1$s/ && mkdir -p %1$s/%2$s && "
             "cp -rp %2$s/common %2$s/tests %2$s/tools %1$s/%2$s/ && "
             "sed -i 's/^MODULES_12 := \\(.*\\)$/MODULES_12 := \\1 exercise_answers/' %1$s/Makefile && "
             "grep -q 'exercise_answers' %1$s/Makefile",
             work, build);
    cr_assert_eq(system(command), 0, "cannot make the copy in %s", work);
    return strstr(build, "san") != NULL;
}

/* Runs make exercises in the copy `work` (env: words put before make, such as a time limit), its output
 * into output[size]; stores the counts of its summary line in *done, *failing and *waiting (-1 when it
 * has none). Returns its exit status. */
static int run_exercises(const char *work, int san, const char *env, char *output, size_t size, int *done,
                         int *failing, int *waiting) {
    char command[2048];
    snprintf(command, sizeof command, "env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS %s make --no-print-directory -C %s "
             "SAN=%d exercises 2>&1", env, work, san);
    int status = run_capturing(command, output, size);
    *done = *failing = *waiting = -1;
    const char *summary = strstr(output, "exercises: ");
    if (summary != NULL)
        sscanf(summary, "exercises: %d done, %d failing, %d not started", done, failing, waiting);
    return status;
}

Test(coursework_proof, make_exercises_grades_each_started_exercise, .timeout = 600) {
    char work[] = "out/test/exercises-XXXXXX", command[2048], path[256];
    int san = exercise_copy(work);
    static const char *const prefixes[] = {"solution", "wrong"};
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/common/exercise_answers.c", work);
        write_answers(path, prefixes[k]);
        char *output = malloc(1 << 16);
        int done, failing, waiting;
        int status = run_exercises(work, san, "", output, 1 << 16, &done, &failing, &waiting);
        /* The disc is a kind of shape, not a function: it stays not started here. */
        int functions = exercise_count() - 1;
        if (k == 0)
            cr_expect(status == 0 && done == functions && failing == 0 && waiting == 1,
                      "with the model answers, make exercises said (status %d):\n%s", status, output);
        else
            cr_expect(status != 0 && done == 0 && failing == functions && waiting == 1 && strstr(output, "  FAIL  exercise 4.4: "
                      "a cylinder\n") != NULL, "with the wrong answers, make exercises said (status %d):\n%s", status,
                      output);
        free(output);
    }
    snprintf(command, sizeof command, "rm -rf %s", work);
    cr_expect_eq(system(command), 0);
}

/* A student's function that never returns, crashes or ends the program gets its exercise named as failing,
 * with the reason, and never a pass (exit(0) once counted as one); so do a NaN bounding sphere and a grid
 * walk that writes past its room, which the checks once let through. */
Test(coursework_proof, make_exercises_names_a_check_that_hangs_crashes_or_is_cut_short, .timeout = 600) {
    static const struct {
        const char *answer, *says;
    } faults[] = {
        {"double whitted_schlick(double c, double n1, double n2) { volatile int on = 1; while (on) {} return c + n1 + n2; }",
         "  FAIL  exercise 8.4, Fresnel by Schlick: the check did not finish within " PROOF_CHECK_SECONDS
         " s (an endless loop in whitted_schlick?)\n"},
        {"double whitted_schlick(double c, double n1, double n2) { volatile int *p = NULL; return c + n1 + n2 + *p; }",
         "  FAIL  exercise 8.4, Fresnel by Schlick: the check crashed (signal SIGSEGV) in whitted_schlick or what it "
         "returned\n"}, /* under the sanitizers, which catch the crash: "the program stopped (exit status 1) ..." */
        {"double whitted_schlick(double c, double n1, double n2) { (void)c; (void)n1; (void)n2; exit(0); }",
         "  FAIL  exercise 8.4, Fresnel by Schlick: the program stopped (exit status 0) before the check finished: "
         "does whitted_schlick call exit?\n"},
        {"void mesh_bounding_sphere(const struct mesh *m, vec3 *centre, double *radius) {\n"
         "    (void)m; *centre = vec3_make(1, 0.5, 3); *radius = sqrt(-1.0); }",
         "  FAIL  exercise 5.4: a bounding sphere\n"},
        {"int grid_walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max) {\n"
         "    int n = solution_grid_walk(lo, hi, cells, r, out, 64); (void)max; return n; }",
         "with room for only 2 cells (max 2), entry 2 of the array was written"},
    };
    char work[] = "out/test/exercises-XXXXXX", command[2048], path[256];
    int san = exercise_copy(work);
    for (size_t k = 0; k < sizeof faults / sizeof faults[0]; k++) {
        snprintf(path, sizeof path, "%s/common/exercise_answers.c", work);
        FILE *f = fopen(path, "w");
        cr_assert_not_null(f, "cannot write %s", path);
        fprintf(f, "#include <math.h>\n#include <stdlib.h>\n#include \"../tests/exercises/solutions.c\"\n%s\n",
                faults[k].answer);
        fclose(f);
        char *output = malloc(1 << 16);
        int done, failing, waiting;
        int status = run_exercises(work, san, "WHITTED_CHECK_SECONDS=" PROOF_CHECK_SECONDS, output, 1 << 16, &done,
                                   &failing, &waiting);
        const char *says = san && k == 1 ? "  FAIL  exercise 8.4, Fresnel by Schlick: the program stopped (exit status 1) "
                                           "before the check finished: whitted_schlick called exit or crashed"
                                         : faults[k].says;
        cr_expect(status != 0 && done == 0 && failing == 1 && strstr(output, says) != NULL,
                  "fault %zu: make exercises said (status %d), not '%s':\n%s", k, status, says, output);
        free(output);
    }
    snprintf(command, sizeof command, "rm -rf %s", work);
    cr_expect_eq(system(command), 0);
}
