# render.py: builds one of our scene files in Blender and renders it with Cycles, for chapter 15's
# comparison with an independent path tracer (tools/cycles/compare-cycles.sh runs it; docs/15-paths.md).
#
#   blender -b --factory-startup --python-exit-code 1 --python tools/cycles/render.py -- \
#       SCENE OUT.exr SAMPLES SEED THREADS [scatter] [smooth]
#
# With `scatter`, no emitter is sampled as a light (each emissive material's Multiple Importance is off):
# Cycles then finds the emitters only by scattering into them. docs/paths-notes.md says why the Cornell box
# needs it: Cycles 3.4's sampling of its large lamp comes out about 2 % darker than the exact direct light
# where the lamp is seen at a grazing angle, while its scattering alone agrees with the exact value.
#
# With `smooth` (make bench-paths, tools/cycles/bench-paths.sh), chapter 15's smooth mirror (`reflection` 1,
# no diffuse part) becomes a Glossy BSDF of roughness 0 and its clear glass (`transmit 1`) a Glass BSDF of
# roughness 0 with the material's `ior`, and the spheres' meshes are shaded smooth (their normals
# interpolated), so that the benchmark's Cornell box keeps its mirror and glass balls. The seconds Cycles
# spent in bpy.ops.render.render (its scene sync and its samples, not Blender's start-up nor the scene's
# building here) are printed as `render.py: rendered in S s, C s of processor time` (C: every thread's).
#
# It reads the subset of the scene format that Cycles can draw exactly as chapters 15 and 17 do: the
# camera, image size, background (a uniform world), the paths line's bounces (its strategy and sampler
# are how ours draws, and are passed over), materials with colour * diffuse (a Diffuse BSDF) and emission
# (an Emission shader, strength 1), triangles, boxes, spheres (a fine mesh: Blender has no exact spheres)
# and area lights (an emitting rectangle, as chapter 15 makes them).
# Chapter 17's rough surfaces too: a rough mirror (`reflection` with `roughness` above 0, `metal none`,
# `lobe ggx`) is a Glossy BSDF (GGX) of that colour and Roughness added to the diffuse part, and rough glass
# (`transmit 1`, `roughness` above 0) a Glass BSDF (GGX) of white colour, that Roughness and the `ior`:
# both read Roughness as we do (alpha = roughness squared). Smooth mirrors and glass, tinted glass
# (`filter`: Cycles' Glass colour tints the reflected light too, ours only the refracted), the metals and
# Schlick's Fresnel (`metal`: the Glossy BSDF has no Fresnel), the Phong lobe, pigments, meshes, planes
# and point lights are refused.
# Cycles is set up as an unbiased path tracer over the same pixels: the box filter of one pixel, no
# clamping, no denoising, no adaptive sampling, no light threshold, the Standard view transform, and the
# picture written as 32-bit linear OpenEXR.
import math
import sys
import time

import bpy
from mathutils import Matrix, Vector

SPHERE_SEGMENTS = 256  # around the equator; half as many rings: the mesh is within 1e-4 of the radius
SPHERE_RINGS = 128


def fail(message):
    print("render.py: " + message, file=sys.stderr)
    sys.exit(1)


def keys(words, spec):
    """Reads `key v1 v2 ...` pairs; spec maps each key to its count of numbers (0: a word)."""
    values, k = {}, 0
    while k < len(words):
        key = words[k]
        if key not in spec:
            fail("unknown key '%s'" % key)
        n = spec[key]
        if n == 0:
            values[key] = words[k + 1]
            k += 2
        else:
            values[key] = [float(w) for w in words[k + 1:k + 1 + n]]
            k += 1 + n
    return values


# Our scenes are y-up; Blender's world is z-up. (x, y, z) -> (x, -z, y) is a rotation, so nothing is mirrored.
def point(v):
    return Vector((v[0], -v[2], v[1]))


def read_scene(path, smooth=False):
    scene = {"materials": {"default": {"colour": [1, 1, 1], "diffuse": 0.6, "emission": [0, 0, 0]}},
             "triangles": [], "spheres": [], "boxes": [], "lights": [], "background": [0, 0, 0], "up": [0, 1, 0],
             "bounces": 256}
    for number, line in enumerate(open(path), 1):
        words = line.split("#")[0].split()
        if not words:
            continue
        what, rest = words[0], words[1:]
        if what == "camera":
            v = keys(rest, {"eye": 3, "target": 3, "up": 3, "fov": 1, "aperture": 1, "focal_point": 3,
                            "blur_samples": 1})
            if "aperture" in v and v["aperture"][0] > 0:
                fail("%s:%d: a lens is not compared" % (path, number))
            scene.update(eye=v["eye"], target=v["target"], fov=v["fov"][0], up=v.get("up", [0, 1, 0]))
        elif what == "image":
            scene["size"] = (int(rest[0]), int(rest[1]))
        elif what == "background":
            scene["background"] = [float(w) for w in rest]
        elif what == "paths":
            # the strategy and the sampler are how ours draws its paths; Cycles keeps its own
            v = keys(rest, {"samples": 1, "seed": 1, "roulette": 1, "bounces": 1, "strategy": 0, "sampler": 0})
            scene["bounces"] = int(v.get("bounces", [256])[0])
        elif what == "material":
            v = keys(rest[1:], {"colour": 3, "ambient": 1, "diffuse": 1, "phong": 1, "phong_size": 1, "reflection": 1,
                                "filter": 1, "transmit": 1, "ior": 1, "pigment": 0, "emission": 3, "roughness": 1,
                                "metal": 0, "lobe": 0})
            rough = v.get("roughness", [0])[0] > 0
            transmit = v.get("transmit", [0])[0]
            refused = [key for key in ("filter", "pigment") if key in v and (key == "pigment" or v[key][0] > 0)]
            refused += [key for key, default in (("metal", "none"), ("lobe", "ggx")) if v.get(key, default) != default]
            if not rough and not smooth:
                refused += [key for key in ("reflection", "transmit") if v.get(key, [0])[0] > 0]
            elif transmit not in (0, 1) or (smooth and not rough and v.get("reflection", [0])[0] not in (0, 1)):
                refused.append("transmit other than 0 or 1")
            if refused:
                fail("%s:%d: material '%s' has %s: only diffuse, emission, rough mirrors and rough clear glass are "
                     "compared" % (path, number, rest[0], ", ".join(refused)))
            m = dict(scene["materials"]["default"])
            m.update({k: v[k] for k in ("colour", "emission") if k in v})
            if "diffuse" in v:
                m["diffuse"] = v["diffuse"][0]
            m["roughness"] = v.get("roughness", [0])[0]
            m["reflection"] = v.get("reflection", [0])[0]
            m["glass"] = transmit == 1
            m["ior"] = v.get("ior", [1])[0]
            scene["materials"][rest[0]] = m
        elif what == "triangle":
            v = keys(rest, {"a": 3, "b": 3, "c": 3, "material": 0})
            scene["triangles"].append((v["a"], v["b"], v["c"], v.get("material", "default")))
        elif what == "sphere":
            v = keys(rest, {"centre": 3, "radius": 1, "material": 0})
            scene["spheres"].append((v["centre"], v["radius"][0], v.get("material", "default")))
        elif what == "box":
            v = keys(rest, {"min": 3, "max": 3, "material": 0})
            scene["boxes"].append((v["min"], v["max"], v.get("material", "default")))
        elif what == "light":
            v = keys(rest, {"position": 3, "colour": 3, "axis1": 3, "axis2": 3, "samples": 2, "adaptive": 1,
                            "circular": 0, "orient": 0})
            if "axis1" not in v:
                fail("%s:%d: a point light: chapter 15 does not see it" % (path, number))
            scene["lights"].append(v)
        elif what in ("antialias", "ambient_light", "max_depth", "adc_bailout", "shadow_offset"):
            pass  # Whitted's settings: chapter 15 does not use them
        else:
            fail("%s:%d: '%s' is not compared" % (path, number, what))
    return scene


def material(name, m, scatter_only):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.cycles.sample_as_light = not scatter_only
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = [c * m["diffuse"] for c in m["colour"]] + [1]
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert
    shader = diffuse.outputs["BSDF"]
    if m.get("glass"):  # chapter 17's rough glass: the diffuse part is not drawn, as chapter 15's glass
        glass = nodes.new("ShaderNodeBsdfGlass")
        glass.distribution = "GGX"
        glass.inputs["Color"].default_value = [1, 1, 1, 1]
        glass.inputs["Roughness"].default_value = m["roughness"]
        glass.inputs["IOR"].default_value = m["ior"]
        shader = glass.outputs["BSDF"]
    elif m.get("reflection", 0) > 0:  # chapter 17's rough mirror, added to the diffuse part
        glossy = nodes.new("ShaderNodeBsdfGlossy")
        glossy.distribution = "GGX"
        glossy.inputs["Color"].default_value = [m["reflection"]] * 3 + [1]
        glossy.inputs["Roughness"].default_value = m["roughness"]
        add = nodes.new("ShaderNodeAddShader")
        links.new(shader, add.inputs[0])
        links.new(glossy.outputs["BSDF"], add.inputs[1])
        shader = add.outputs["Shader"]
    if any(e > 0 for e in m["emission"]):
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = list(m["emission"]) + [1]
        emission.inputs["Strength"].default_value = 1.0
        add = nodes.new("ShaderNodeAddShader")
        links.new(shader, add.inputs[0])
        links.new(emission.outputs["Emission"], add.inputs[1])
        shader = add.outputs["Shader"]
    links.new(shader, out.inputs["Surface"])
    return mat


def mesh_object(name, vertices, faces, mat, smooth=False):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([point(v) for v in vertices], [], faces)
    if smooth:
        mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    mesh.materials.append(mat)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)


def sphere_mesh(centre, radius):
    vertices, faces = [], []
    for ring in range(1, SPHERE_RINGS):
        theta = math.pi * ring / SPHERE_RINGS
        for s in range(SPHERE_SEGMENTS):
            phi = 2 * math.pi * s / SPHERE_SEGMENTS
            vertices.append([centre[0] + radius * math.sin(theta) * math.cos(phi), centre[1] + radius * math.cos(theta),
                             centre[2] + radius * math.sin(theta) * math.sin(phi)])
    top, bottom = len(vertices), len(vertices) + 1
    vertices += [[centre[0], centre[1] + radius, centre[2]], [centre[0], centre[1] - radius, centre[2]]]
    at = lambda ring, s: (ring - 1) * SPHERE_SEGMENTS + s % SPHERE_SEGMENTS
    for s in range(SPHERE_SEGMENTS):
        faces.append((top, at(1, s + 1), at(1, s)))
        faces.append((bottom, at(SPHERE_RINGS - 1, s), at(SPHERE_RINGS - 1, s + 1)))
        for ring in range(1, SPHERE_RINGS - 1):
            faces.append((at(ring, s), at(ring, s + 1), at(ring + 1, s + 1), at(ring + 1, s)))
    return vertices, faces


def box_mesh(lo, hi):
    vertices = [[(lo, hi)[i & 1][0], (lo, hi)[i >> 1 & 1][1], (lo, hi)[i >> 2 & 1][2]] for i in range(8)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return vertices, faces


def build(scene, scatter_only, smooth=False):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    s = bpy.context.scene
    mats = {name: material(name, m, scatter_only) for name, m in scene["materials"].items()}
    for k, (a, b, c, m) in enumerate(scene["triangles"]):
        mesh_object("triangle %d" % k, [a, b, c], [(0, 1, 2)], mats[m])
    for k, (centre, radius, m) in enumerate(scene["spheres"]):
        vertices, faces = sphere_mesh(centre, radius)
        mesh_object("sphere %d" % k, vertices, faces, mats[m], smooth)
    for k, (lo, hi, m) in enumerate(scene["boxes"]):
        vertices, faces = box_mesh(lo, hi)
        mesh_object("box %d" % k, vertices, faces, mats[m])
    for k, light in enumerate(scene["lights"]):  # chapter 15's rectangle: black, emitting the light's colour
        m = material("area light %d" % k, {"colour": [0, 0, 0], "diffuse": 0, "emission": light["colour"]},
                     scatter_only)
        p, a1, a2 = Vector(light["position"]), Vector(light["axis1"]) / 2, Vector(light["axis2"]) / 2
        mesh_object("area light %d" % k, [p - a1 - a2, p + a1 - a2, p + a1 + a2, p - a1 + a2], [(0, 1, 2, 3)], m)
    world = bpy.data.worlds.new("background")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = list(scene["background"]) + [1]
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    s.world = world
    camera = bpy.data.cameras.new("camera")
    camera.sensor_fit = "VERTICAL"
    camera.angle_y = math.radians(scene["fov"])
    camera.clip_start, camera.clip_end = 1e-3, 1e7
    obj = bpy.data.objects.new("camera", camera)
    s.collection.objects.link(obj)
    eye, target, up = point(scene["eye"]), point(scene["target"]), point(scene["up"])
    back = (eye - target).normalized()  # the camera looks down its -z, its y is up in the picture
    right = up.cross(back).normalized()
    rotation = Matrix((right, back.cross(right), back)).transposed()
    obj.matrix_world = Matrix.Translation(eye) @ rotation.to_4x4()
    s.camera = obj


def render(scene, out, samples, seed, threads):
    s = bpy.context.scene
    s.render.engine = "CYCLES"
    c = s.cycles
    c.device = "CPU"
    c.samples = samples
    c.seed = seed
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.blur_glossy = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = scene["bounces"]
    c.transparent_max_bounces = scene["bounces"]
    s.render.resolution_x, s.render.resolution_y = scene["size"]
    s.render.resolution_percentage = 100
    s.render.threads_mode = "FIXED"
    s.render.threads = threads
    s.render.film_transparent = False
    s.view_settings.view_transform = "Standard"
    s.view_settings.look = "None"
    s.view_settings.exposure = 0.0
    s.view_settings.gamma = 1.0
    s.render.image_settings.file_format = "OPEN_EXR"
    s.render.image_settings.color_depth = "32"
    s.render.image_settings.color_mode = "RGB"
    s.render.filepath = out
    start, cpu = time.perf_counter(), time.process_time()
    bpy.ops.render.render()
    print("render.py: rendered in %.6f s, %.6f s of processor time" %
          (time.perf_counter() - start, time.process_time() - cpu))
    bpy.data.images["Render Result"].save_render(out, scene=s)


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    words = args[5:]
    if len(args) < 5 or any(w not in ("scatter", "smooth") for w in words):
        fail("usage: blender -b --python render.py -- SCENE OUT.exr SAMPLES SEED THREADS [scatter] [smooth]")
    scene = read_scene(args[0], "smooth" in words)
    build(scene, "scatter" in words, "smooth" in words)
    render(scene, args[1], int(args[2]), int(args[3]), int(args[4]))


if __name__ == "__main__":
    main()
