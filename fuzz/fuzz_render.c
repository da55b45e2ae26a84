/* fuzz_render.c: libFuzzer harness that reaches the renderer: a scene text parsed, its meshes made
 * tiny, every structure built and a few rays traced in each, all checked against brute force
 * (render_check.h says what is checked). Part of make fuzz.
 *
 * Inputs holding a zero byte are skipped, as in fuzz_scene.c: no scene file can hold one. So are the
 * scenes that trigger a known defect being fixed (render_check.c lists them), so that the fuzzer
 * looks past it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_support.h"
#include "render_check.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (memchr(data, '\0', size) != NULL)
        return 0;
    char *text = fuzz_copy_with_nul(data, size);
    char why[1024];
    if (render_check_scene("fuzz.scene", text, why, sizeof why) == RENDER_CHECK_FAILED)
        fuzz_abort("%s", why);
    free(text);
    return 0;
}
