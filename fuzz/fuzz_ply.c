/* fuzz_ply.c: libFuzzer harness for the PLY reader, mesh_read_ply on bytes in memory (make fuzz).
 *
 * Inputs whose first line is not "ply" are skipped: mesh_load gives those to the OBJ reader, which has
 * its own harness (fuzz_obj.c). So every input here reaches the PLY reader exactly as the same bytes
 * in a file would through mesh_load, and a saved crash replays through mesh_load in the tests. */
#include "fuzz_mesh.h"
#include "fuzz_support.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (fuzz_mesh_is_ply(data, size))
        fuzz_mesh_read(data, size, true, "fuzz.ply");
    return 0;
}
