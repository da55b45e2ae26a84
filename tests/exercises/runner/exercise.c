/* exercise.c: runs the check of one build exercise (★★★) on the student's own function. make exercises
 * (run.sh, beside this file) compiles it once for each exercise whose function common/ defines, naming
 * the exercise and what to check: EXERCISE_ID ("4.4"), EXERCISE_TITLE ("a cylinder"), EXERCISE_CHECK
 * (check_cylinder, exercises.h) and EXERCISE_FUNCTION (cylinder_intersect). Run with the name of a
 * file, into which it writes its verdict, "ok" or "FAIL", once the check has run: run.sh trusts that, not
 * the exit status, which a student's function could set by ending the program. Exits 0 when the check
 * passes, 1 with its message when not. */
#include <stdio.h>

#include "exercises.h"

/* Writes the verdict into the file `path`; false when it cannot. */
static bool write_verdict(const char *path, const char *verdict) {
    FILE *f = fopen(path, "w");
    if (f == NULL)
        return false;
    bool written = fputs(verdict, f) >= 0;
    return fclose(f) == 0 && written;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s VERDICT-FILE (run by tests/exercises/runner/run.sh)\n", argv[0]);
        return 2;
    }
    char why[1024] = "";
    bool passed = EXERCISE_CHECK(EXERCISE_FUNCTION, why, sizeof why);
    if (!write_verdict(argv[1], passed ? "ok" : "FAIL")) {
        fprintf(stderr, "%s: cannot write the verdict\n", argv[1]);
        return 2;
    }
    if (passed) {
        printf("  ok    exercise %s: %s\n", EXERCISE_ID, EXERCISE_TITLE);
        return 0;
    }
    printf("  FAIL  exercise %s: %s\n        %s\n", EXERCISE_ID, EXERCISE_TITLE, why);
    return 1;
}
