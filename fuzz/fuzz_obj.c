/* fuzz_obj.c: libFuzzer harness for the Wavefront OBJ reader, mesh_read_obj on bytes in memory (make fuzz).
 *
 * Inputs whose first line is "ply" are skipped (mesh_load gives those to the PLY reader, fuzz_ply.c),
 * and so is the empty input (mesh_load refuses it before any reader): every input here reaches the OBJ
 * reader exactly as the same bytes in a file would through mesh_load. */
#include "fuzz_mesh.h"
#include "fuzz_support.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size > 0 && !fuzz_mesh_is_ply(data, size))
        fuzz_mesh_read(data, size, false, "fuzz.obj");
    return 0;
}
