/* fuzz_support.c: what the libFuzzer harnesses share (make fuzz; not part of any chapter). */
#include "fuzz_support.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void fuzz_abort(const char *format, ...) {
    va_list args;
    va_start(args, format);
    fprintf(stderr, "fuzz: ");
    vfprintf(stderr, format, args);
    fprintf(stderr, "\n");
    va_end(args);
    abort();
}

char *fuzz_copy_with_nul(const uint8_t *data, size_t size) {
    char *copy = malloc(size + 1);
    if (copy == NULL)
        fuzz_abort("out of memory copying a %zu-byte input", size);
    if (size > 0)
        memcpy(copy, data, size);
    copy[size] = '\0';
    return copy;
}

bool fuzz_message_names(const char *err, const char *name) {
    size_t n = strlen(name);
    return strncmp(err, name, n) == 0 && err[n] == ':' && err[n + 1] != '\0';
}
