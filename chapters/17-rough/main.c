/* Chapter 17, rough surfaces: chapter 15's path tracer with glossy metal and frosted glass. A material
 * with a roughness above 0 is a field of tiny mirrors, the GGX (Trowbridge-Reitz) microfacet model with
 * Smith's masking (common/microfacet.c): a rough mirror of a colour or of a real metal's complex index,
 * or rough glass that reflects and refracts through its facets (Walter et al. 2007). It plugs into
 * chapter 15's estimator as a path_surface (common/rough_surface.c): next-event estimation asks it for
 * f cos and its density, scattering draws the visible normals (Heitz 2018), and multiple importance
 * sampling weighs the two with the density of the lobe a path would have drawn. Everything else, the
 * emitters, the sample streams, the paths line and its strategy, is chapter 15's; a scene without
 * roughness draws chapter 15's picture exactly. The program is chapter 15's (common/path_program.c)
 * with the rough surfaces plugged in. */
#include <stdio.h>
#include <string.h>

#include "accel.h"
#include "box.h"
#include "cli.h"
#include "path_program.h"
#include "plane.h"
#include "rough_surface.h"
#include "sphere.h"
#include "text_escape.h"
#include "triangle.h"

static struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};
/* --form cycles-3.4: the lobes as Cycles 3.4 writes them, for the comparison with it only (rough_surface.h). */
static const struct path_surface *rough_hook = &rough_surface_hook;

static int parse_option(const char *option, const char *value) {
    if (strcmp(option, "--form") == 0) {
        if (value != NULL && (strcmp(value, "chapter") == 0 || strcmp(value, "cycles-3.4") == 0)) {
            rough_hook = strcmp(value, "cycles-3.4") == 0 ? &rough_surface_hook_cycles_3_4 : &rough_surface_hook;
            return 2;
        }
        char got[256];
        text_escape(value != NULL ? value : "", got, sizeof got); /* the value comes from the command line */
        fprintf(stderr, "--form needs 'chapter' (the default) or 'cycles-3.4' (to compare with it), got '%s'\n", got);
        return -1;
    }
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

int main(int argc, char **argv) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 17,
        .title = "rough surfaces",
        .default_scene = "scenes/17-rough.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --hdr FILE       also write the linear radiance: a Radiance .hdr file, or a Portable\n"
                        "                   Float Map when FILE ends in .pfm (every float kept whole); - for\n"
                        "                   standard output (the counters then go to standard error)\n"
                        "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule\n"
                        "  --form FORM      chapter (default): the chapter's lobes; cycles-3.4: masking by\n"
                        "                   G1(wo) G1(wi) and glass's Fresnel at the normal, as Blender 3.4's\n"
                        "                   Cycles has them, for comparing with it only\n",
        .output_option = "--hdr",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    return path_program_run(&run, &choice, rough_hook);
}
