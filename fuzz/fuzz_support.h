/* fuzz_support.h: what the libFuzzer harnesses in fuzz/ share (make fuzz; not part of any chapter).
 *
 * A harness is a function LLVMFuzzerTestOneInput(data, size) that libFuzzer calls with millions of
 * inputs; it returns 0, and reports a broken promise by aborting, which libFuzzer saves as a crash. */
#ifndef WHITTED_FUZZ_SUPPORT_H
#define WHITTED_FUZZ_SUPPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* libFuzzer's entry point, declared here so that every harness defines it with this signature. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Prints "fuzz: " and the message to stderr and aborts: libFuzzer saves the input as a crash. */
_Noreturn void fuzz_abort(const char *format, ...) __attribute__((format(printf, 1, 2)));

/* Returns a malloc'd copy of data[0..size) followed by a NUL byte; aborts when memory runs out. */
char *fuzz_copy_with_nul(const uint8_t *data, size_t size);

/* Returns true when the error message `err` starts with "name:", as every message of the readers
 * does ("file:line: what is wrong", "file: what is wrong"), and says something after it. */
bool fuzz_message_names(const char *err, const char *name);

#endif
