# motion.py: builds a scene of chapter 16 in Blender and renders it with Cycles' object motion blur, for
# the check of chapter 16's motion blur against an independent renderer (tools/cycles/compare-cycles.sh
# runs it; tools/cycles/compare.py compares the pictures; docs/16-instances.md).
#
#   blender -b --factory-startup --python-exit-code 1 --python tools/cycles/motion.py -- \
#       SCENE OUT.exr SAMPLES SEED THREADS
#
# It reads the subset of the scene format whose picture needs no lighting at all: the camera (with its
# shutter), image size, background, ambient_light 1 1 1, materials with ambient 1 and diffuse 0 (each
# surface shows its own colour: an Emission shader of strength 1, seen by camera rays only, Cycles' max
# bounces 0), and object, instance and key lines. Anything else is refused.
#
# The clock is Blender's frames: clock c is frame FRAMES_PER_CLOCK * c. Each instance becomes an object
# with its pose keyframed at its keys' frames, interpolated LINEARLY in each of the nine numbers, as
# chapter 16 does; Blender's Euler XYZ rotation is Rz Ry Rx, our instance line's order. The instances sit
# under an empty turned 90 degrees about x, which takes our y-up world to Blender's z-up one, so their
# keys are our numbers as they are. Cycles' shutter opens at the frame (motion_blur_position START) and
# its rays' times fill FRAMES_PER_CLOCK * shutter frames, as ours fill [c, c + shutter]; the motion is
# sampled at MOTION_STEPS_LOG2 steps (2^(n-1) + 1 poses over the shutter, between which Cycles
# interpolates): on scenes/16-blur.scene a step turns the spinning bunny by 1.4 degrees, and Cycles'
# path between two poses strays from ours (linear in each angle) by (1.4 degrees)^2 / 8 of the bunny's
# size, a few thousandths of a pixel.
# Pixels are Cycles' box filter of one pixel, as ours: no clamping, denoising or adaptive sampling.
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

FRAMES_PER_CLOCK = 100.0
MOTION_STEPS_LOG2 = 7  # Cycles' most: 65 poses over the shutter
# Cycles draws a camera ray's time from a table of the shutter curve's inverse (256 entries) built so that
# its times end at (255/256)^2 of the shutter, not at the shutter's end (measured: a bunny sliding at a
# constant speed is drawn as ours with a shutter 0.8 % shorter). So Cycles is asked for a shutter this
# much longer, and its rays' times fill ours, [c, c + shutter].
CYCLES_SHUTTER_REACH = (255.0 / 256.0) ** 2
MEANS_ONLY_ITSELF = 1e-12  # ambient 1 and diffuse 0 within this: the surface shows its colour only


def fail(message):
    print("motion.py: " + message, file=sys.stderr)
    sys.exit(1)


def numbers(words, counts, where):
    """Reads `key v1 v2 ...` pairs of a line; counts maps each key to its count of numbers (0: a word)."""
    values, k = {}, 0
    while k < len(words):
        if words[k] not in counts:
            fail("%s: '%s' is not compared" % (where, words[k]))
        n = counts[words[k]]
        values[words[k]] = words[k + 1] if n == 0 else [float(w) for w in words[k + 1:k + 1 + n]]
        k += 1 + max(n, 1)
    return values


POSE = {"scale": 3, "rotate": 3, "translate": 3}


def read_scene(path):
    scene = {"materials": {}, "objects": {}, "instances": [], "background": [0, 0, 0], "up": [0, 1, 0],
             "shutter": 0.0}
    labelled = {}
    for number, line in enumerate(open(path), 1):
        words = line.split("#")[0].split()
        where = "%s:%d" % (path, number)
        if not words:
            continue
        what, rest = words[0], words[1:]
        if what == "camera":
            v = numbers(rest, {"eye": 3, "target": 3, "up": 3, "fov": 1, "shutter": 1}, where)
            scene.update(eye=v["eye"], target=v["target"], fov=v["fov"][0], up=v.get("up", [0, 1, 0]),
                         shutter=v.get("shutter", [0])[0])
        elif what == "image":
            scene["size"] = (int(rest[0]), int(rest[1]))
        elif what == "background":
            scene["background"] = [float(w) for w in rest]
        elif what == "ambient_light":
            if [float(w) for w in rest] != [1, 1, 1]:
                fail("%s: ambient_light must be 1 1 1" % where)
        elif what == "antialias":
            pass  # our samples; Cycles takes its count from the command line
        elif what == "material":
            v = numbers(rest[1:], {"colour": 3, "ambient": 1, "diffuse": 1}, where)
            if abs(v.get("ambient", [0])[0] - 1) > MEANS_ONLY_ITSELF or abs(v.get("diffuse", [0.6])[0]) > MEANS_ONLY_ITSELF:
                fail("%s: material '%s' must have ambient 1 and diffuse 0" % (where, rest[0]))
            scene["materials"][rest[0]] = v["colour"]
        elif what == "object":
            if rest[2:] not in ([], ["smooth", "on"], ["smooth", "off"]):
                fail("%s: '%s' is not compared" % (where, " ".join(rest[2:])))
            scene["objects"][rest[0]] = os.path.join(os.path.dirname(path), rest[1])
        elif what == "instance":
            v = numbers(rest[1:], dict(POSE, material=0, id=0), where)
            if "material" not in v:
                fail("%s: an instance needs a material here" % where)
            pose = {k: v.get(k, [1, 1, 1] if k == "scale" else [0, 0, 0]) for k in POSE}
            instance = {"object": rest[0], "material": v["material"], "pose": pose, "keys": []}
            scene["instances"].append(instance)
            if "id" in v:
                labelled[v["id"]] = instance
        elif what == "key":
            v = numbers(rest[1:], dict(POSE, time=1), where)
            instance = labelled[rest[0]]
            pose = {k: v.get(k, instance["pose"][k]) for k in POSE}  # a key's missing parts: the instance's
            instance["keys"].append((v["time"][0], pose))
        else:
            fail("%s: '%s' is not compared" % (where, what))
    return scene


def read_ply(path):
    """The vertices and triangles of an ASCII PLY file whose vertices start with x y z."""
    lines = open(path).read().split("\n")
    counts, k = {}, 0
    while lines[k].strip() != "end_header":
        words = lines[k].split()
        if words[:1] == ["format"] and words[1] != "ascii":
            fail("%s: only ASCII PLY is read here" % path)
        if words[:1] == ["element"]:
            counts[words[1]] = int(words[2])
        k += 1
    body = lines[k + 1:]
    vertices = [[float(w) for w in body[i].split()[:3]] for i in range(counts["vertex"])]
    faces = [[int(w) for w in body[counts["vertex"] + i].split()[1:]] for i in range(counts["face"])]
    return vertices, faces


def emission(name, colour):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    glow = nodes.new("ShaderNodeEmission")
    glow.inputs["Color"].default_value = list(colour) + [1]
    glow.inputs["Strength"].default_value = 1.0
    mat.node_tree.links.new(glow.outputs["Emission"], out.inputs["Surface"])
    return mat


def set_pose(obj, pose):
    obj.scale = pose["scale"]
    obj.rotation_euler = [math.radians(a) for a in pose["rotate"]]
    obj.location = pose["translate"]


def build(scene):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    s = bpy.context.scene
    y_up = bpy.data.objects.new("y up", None)  # our world in Blender's: (x, y, z) -> (x, -z, y)
    y_up.rotation_euler = (math.pi / 2, 0, 0)
    s.collection.objects.link(y_up)
    mats = {name: emission(name, colour) for name, colour in scene["materials"].items()}
    meshes = {}
    for name, path in scene["objects"].items():
        vertices, faces = read_ply(path)
        meshes[name] = bpy.data.meshes.new(name)
        meshes[name].from_pydata(vertices, [], faces)
    for k, instance in enumerate(scene["instances"]):
        obj = bpy.data.objects.new("instance %d" % k, meshes[instance["object"]])
        obj.data = obj.data.copy()  # one material per instance
        obj.data.materials.append(mats[instance["material"]])
        obj.rotation_mode = "XYZ"
        obj.parent = y_up
        obj.cycles.use_motion_blur = True
        obj.cycles.motion_steps = MOTION_STEPS_LOG2
        s.collection.objects.link(obj)
        set_pose(obj, instance["pose"])
        for time, pose in instance["keys"]:
            set_pose(obj, pose)
            for path in ("scale", "rotation_euler", "location"):
                obj.keyframe_insert(path, frame=FRAMES_PER_CLOCK * time)
        if obj.animation_data:
            for curve in obj.animation_data.action.fcurves:
                curve.extrapolation = "CONSTANT"  # before the first key and after the last, the pose holds
                for point in curve.keyframe_points:
                    point.interpolation = "LINEAR"
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
    z_up = lambda v: Vector((v[0], -v[2], v[1]))
    eye, target, up = z_up(scene["eye"]), z_up(scene["target"]), z_up(scene["up"])
    back = (eye - target).normalized()  # the camera looks down its -z, its y is up in the picture
    right = up.cross(back).normalized()
    obj.matrix_world = Matrix.Translation(eye) @ Matrix((right, back.cross(right), back)).transposed().to_4x4()
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
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 0
    c.transparent_max_bounces = c.volume_bounces = 0
    s.frame_start = s.frame_end = 0
    s.frame_set(0)  # clock 0: the single picture
    s.render.use_motion_blur = scene["shutter"] > 0
    s.render.motion_blur_shutter = FRAMES_PER_CLOCK * scene["shutter"] / CYCLES_SHUTTER_REACH
    c.motion_blur_position = "START"
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
    bpy.ops.render.render(write_still=True)


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    if len(args) != 5:
        fail("usage: blender -b --python motion.py -- SCENE OUT.exr SAMPLES SEED THREADS")
    scene = read_scene(args[0])
    build(scene)
    render(scene, args[1], int(args[2]), int(args[3]), int(args[4]))


main()
