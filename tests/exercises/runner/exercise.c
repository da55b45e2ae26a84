/* exercise.c: runs the check of one build exercise (★★★) on the student's own function. make exercises
 * (run.sh, beside this file) compiles it once for each exercise whose function common/ defines, naming
 * the exercise and what to check: EXERCISE_ID ("4.4"), EXERCISE_TITLE ("a cylinder"), EXERCISE_CHECK
 * (check_cylinder, exercises.h) and EXERCISE_FUNCTION (cylinder_intersect). Exits 0 when the check
 * passes, 1 with its message when not. */
#include <stdio.h>

#include "exercises.h"

int main(void) {
    char why[1024] = "";
    if (EXERCISE_CHECK(EXERCISE_FUNCTION, why, sizeof why)) {
        printf("  ok    exercise %s: %s\n", EXERCISE_ID, EXERCISE_TITLE);
        return 0;
    }
    printf("  FAIL  exercise %s: %s\n        %s\n", EXERCISE_ID, EXERCISE_TITLE, why);
    return 1;
}
