# task_trace.awk: adds to the body of every function marked "/* TASK N.K: what */" (or tied to task N.K by
# "/* TASK N.K ALSO: what */", blanked with it) a first statement that
# records, once per process, that the task ran: a line "N.K" appended to the file named by the
# environment variable WHITTED_TASK_TRACE. For the test that each picture check needs exactly the tasks
# its chapter's program runs (tests/test_coursework_copy.c); the code is otherwise unchanged.
#
#   awk -f tests/checks/task_trace.awk common/sphere.c > copy/common/sphere.c
FNR == 1 { includes = 0 }
/^#include / && !includes++ { print "#include <stdio.h>"; print "#include <stdlib.h>" }
match($0, /^\/\* TASK [0-9]+\.[0-9]+( ALSO)?: .* \*\/$/) { id = $3; sub(/:$/, "", id); pending = 1; print; next }
pending && /\{[ \t]*$/ {
    print
    print "    { static int traced; const char *trace = getenv(\"WHITTED_TASK_TRACE\"); FILE *to;"
    print "      if (!traced && trace != NULL && (to = fopen(trace, \"a\")) != NULL) { traced = 1; fputs(\"" id "\\n\", to); fclose(to); } }"
    pending = 0
    next
}
{ print }
