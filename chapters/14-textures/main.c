/* Chapter 14, textures: surfaces whose colour changes from point to point. A material may name a
 * pigment (common/pigment.h): a procedural pattern (checker, gradient, brick, radial) or an image map
 * (a PNG or JPEG decoded to linear light, wrapped by a planar or spherical mapping), each moved by its
 * texture transform. Meshes may be smooth: their corners' normals (from the file, or averaged) blended
 * across each triangle (common/mesh_surface.c), and may carry texture coordinates for `map uv`. The
 * pigments are evaluated in common/texture.c and common/image_map.c and reach the shading through the
 * scene's paint hook, which hands chapter 8's tracer the material and the normal as they are at each
 * hit. Everything else is chapter 13's: soft shadows, the lens, chapter 12's sampling, the fast BVH. */
#include "accel_fast_bvh.h"
#include "box.h"
#include "cli.h"
#include "fast_bvh.h"
#include "mesh_surface.h"
#include "plane.h"
#include "soft_shadow.h"
#include "sphere.h"
#include "texture.h"
#include "thin_lens.h"
#include "triangle.h"
#include "whitted.h"

static struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

/* Chapter 13's tracer: soft shadows from area lights (texture_paint reaches it through scene.paint). */
static vec3 trace_soft(const void *world, const ray *r) {
    return whitted_trace_shadowed(world, r, soft_shadow_filtered);
}

int main(int argc, char **argv) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 14,
        .title = "textures",
        .default_scene = "scenes/14-textures.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule\n",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    /* What chapter 14 adds: the image maps read, the meshes' normals and texture coordinates kept (and
     * averaged where a mesh is to be smooth without them), and every hit painted by texture_paint. */
    run.scene.paint = texture_paint;
    run.scene.shadow_paint = texture_paint_shadow; /* shadows through patterned glass take its pattern */
    if (!texture_load_images(&run.scene, run.err, sizeof run.err) ||
        !scene_load_meshes(&run.scene, run.err, sizeof run.err) ||
        !mesh_surface_prepare(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct accel_world *w =
        accel_world_create_at_rung(&run.scene, &choice, FAST_BVH_RUNG_DEFAULT, run.err, sizeof run.err);
    if (w == NULL)
        return cli_fail(&run);
    if (cli_render_sampled(&run, trace_soft, &w->world, &thin_lens_sampler))
        accel_report(w, &run.total, run.options.stats);
    accel_world_destroy(w);
    return cli_finish(&run);
}
