/* Chapter 15, path tracing: the rendering equation solved by Monte Carlo. Each pixel is the mean of the
 * scene's paths per pixel (its paths line, common/path_settings.h): a path leaves the camera through a
 * random point of the pixel and bounces through the scene, a cosine-weighted direction off a Lambertian
 * surface, the mirror direction off a mirror, reflected or refracted by Fresnel's share at glass
 * (common/bsdf.c); at each Lambertian point a shadow ray goes to a point chosen on the emitting surfaces
 * (common/emitter.c), weighed against scattering by multiple importance sampling, and Russian roulette
 * ends the path (common/path_trace.c). The picture is tone-mapped into the PNG and kept linear in an HDR
 * file with --hdr (common/path_image.c). The world is chapter 11's fast BVH, the surfaces may be
 * chapter 14's textures, and the random numbers chapter 12's counter-based hash: the picture is the same
 * for any number of threads. The steps after the command line are common/path_program.c's, which
 * chapter 17 shares. */
#include "accel.h"
#include "box.h"
#include "cli.h"
#include "path_program.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"

static struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

int main(int argc, char **argv) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 15,
        .title = "path tracing",
        .default_scene = "scenes/15-paths.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --hdr FILE       also write the linear radiance: a Radiance .hdr file, or a Portable\n"
                        "                   Float Map when FILE ends in .pfm (every float kept whole); - for\n"
                        "                   standard output (the counters then go to standard error)\n"
                        "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule\n",
        .output_option = "--hdr",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    return path_program_run(&run, &choice, NULL);
}
