/* figures.c: draws every walkthrough figure into a directory (tools/figures; `make figures`).
 *
 * Usage: figures DIR. Writes DIR/NN-name.svg for every figure; the committed copies live in
 * docs/figures/, and tests/test_figures.c checks that they are what this program draws now. Exit
 * status 0, 2 for a bad command line, 3 when a file cannot be written (nothing half-written is left). */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "figures.h"

static const struct {
    const char *file;
    void (*draw)(FILE *out);
} figures[] = {
    {"01-camera.svg", figure_camera},   {"02-sphere.svg", figure_sphere},   {"03-triangle.svg", figure_triangle},
    {"04-plane.svg", figure_plane},     {"05-slabs.svg", figure_slabs},     {"06-phong.svg", figure_phong},
    {"07-shadow.svg", figure_shadow},   {"08-recursion.svg", figure_recursion}, {"09-kdtree.svg", figure_kdtree},
    {"10-bvh.svg", figure_bvh},         {"12-antialias.svg", figure_antialias}, {"13-penumbra.svg", figure_penumbra},
    {"13-lens.svg", figure_lens},       {"14-normals.svg", figure_textures}, {"15-sampling.svg", figure_sampling},
    {"15-convergence.svg", figure_convergence}, {"17-microfacets.svg", figure_microfacets},
};

/* Draws one figure into path through a temporary file renamed into place, so a failed run leaves no
 * half-written figure. Returns false with a message on stderr when the file cannot be written. */
static bool write_figure(const char *path, void (*draw)(FILE *out)) {
    char temporary[4200];
    snprintf(temporary, sizeof temporary, "%s.part", path);
    FILE *out = fopen(temporary, "w");
    if (out == NULL) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    draw(out);
    bool ok = !ferror(out);
    if (fclose(out) != 0)
        ok = false;
    if (!ok || rename(temporary, path) != 0) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        remove(temporary);
        return false;
    }
    return true;
}

int main(int argc, char **argv) {
    if (argc != 2 || argv[1][0] == '-') {
        fprintf(stderr, "usage: %s DIR   (writes every walkthrough figure as DIR/NN-name.svg)\n", argv[0]);
        return 2;
    }
    for (size_t k = 0; k < sizeof figures / sizeof figures[0]; k++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", argv[1], figures[k].file);
        if (!write_figure(path, figures[k].draw))
            return 3;
    }
    return 0;
}
