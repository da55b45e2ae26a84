# compare.py: chapter 15's picture beside Cycles', as numbers (tools/cycles/compare-cycles.sh runs it with
# Blender's Python, which reads both files: our Radiance .hdr, Cycles' OpenEXR).
#
#   blender -b --factory-startup --python-exit-code 1 --python tools/cycles/compare.py -- \
#       NAME BLOCK OURS_A.pfm OURS_B.pfm CYCLES_A.exr CYCLES_B.exr [SIDE_BY_SIDE.png]
#
# Ours is read from the Portable Float Maps chapter 15 writes with --hdr NAME.pfm (or chapter 16's PNG) (every float whole: the
# Radiance format's 8-bit mantissas would move the mean by up to half a percent), Cycles' from its EXR.
# Each renderer drew the scene twice with different seeds (A and B). The two draws of one renderer differ
# only by noise, so (A - B)^2 / 4 is an unbiased estimate of the variance of a pixel of their mean, and the
# variance of a block's mean is the sum of its pixels' over the count squared (the pixels' noise being
# independent). For every BLOCK x BLOCK block and channel, the difference of the two renderers' means is
# measured in combined standard errors, z = (ours - cycles) / sqrt(var ours + var cycles): it passes when
# every |z| <= 4 (about one block and channel in 16,000 would fail by chance) and the whole picture's means
# differ by at most 1 %. Prints one line for the table and exits 1 when the rule fails.
import array
import math
import sys

import bpy

Z_LIMIT = 4.0
MEAN_LIMIT = 0.01
# Both pictures are 32-bit floats, and Cycles adds its samples up in them: where there is no noise at all
# (the sky seen directly) the two still differ by rounding, a few parts in a million after 512 samples,
# so a block's standard error is never taken below this share of its mean.
FLOAT_SHARE = 1e-5
# A PNG (chapter 16 writes no floats) holds each value rounded to a 255th: a value that both draws round
# alike (the faint tip of a blur) shows no noise between them, so a PNG pixel's variance is never taken
# below that of the rounding, (1/255)^2 / 12, halved for the mean of the two draws.
PNG_ROUNDING_VARIANCE = (1.0 / 255.0) ** 2 / 12 / 2


def load(path):
    if path.endswith(".pfm"):  # "PF", width height, -1.0 (little-endian), rows from the bottom as Blender's
        data = open(path, "rb").read()
        magic, size, scale, floats = data.split(b"\n", 3)
        width, height = (int(w) for w in size.split())
        if magic != b"PF" or float(scale) >= 0 or len(floats) != 12 * width * height:
            print("compare.py: %s is not a little-endian colour PFM" % path, file=sys.stderr)
            sys.exit(2)
        rgb = array.array("f", floats)
        if sys.byteorder != "little":
            rgb.byteswap()
        pixels = array.array("f", [1.0]) * (width * height * 4)
        for k in range(width * height):
            pixels[4 * k:4 * k + 3] = rgb[3 * k:3 * k + 3]
        return width, height, pixels
    image = bpy.data.images.load(path)
    image.colorspace_settings.name = "Non-Color"  # the numbers as stored: linear radiance
    width, height = image.size
    pixels = array.array("f", [0.0]) * (width * height * 4)
    image.pixels.foreach_get(pixels)
    return width, height, pixels


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    name, block = args[0], int(args[1])
    images = [load(p) for p in args[2:6]]
    width, height = images[0][0], images[0][1]
    if any((w, h) != (width, height) for w, h, _ in images):
        print("compare.py: the four pictures differ in size", file=sys.stderr)
        sys.exit(2)
    oa, ob, ca, cb = (p for _, _, p in images)
    rounding = sum(PNG_ROUNDING_VARIANCE for path in args[2:6:2] if path.endswith(".png"))  # ours', Cycles'
    worst, within2, tests, z2 = 0.0, 0, 0, 0.0
    totals = [[0.0] * 3, [0.0] * 3]
    for by in range(height // block):
        for bx in range(width // block):
            for c in range(3):
                so = sc = vo = vc = 0.0
                for j in range(by * block, (by + 1) * block):
                    for i in range(bx * block, (bx + 1) * block):
                        k = 4 * (j * width + i) + c
                        so += oa[k] + ob[k]
                        sc += ca[k] + cb[k]
                        vo += (oa[k] - ob[k]) ** 2 / 4
                        vc += (ca[k] - cb[k]) ** 2 / 4
                n = block * block
                mo, mc = so / (2 * n), sc / (2 * n)
                var = (vo + vc + n * rounding) / (n * n) + (FLOAT_SHARE * max(abs(mo), abs(mc))) ** 2
                z = (mo - mc) / math.sqrt(var) if var > 0 else 0.0  # 0: both black
                worst = max(worst, abs(z))
                within2 += abs(z) <= 2
                z2 += z * z
                tests += 1
                totals[0][c] += so
                totals[1][c] += sc
    means = [sum(t) / (2 * 3 * width * height) for t in totals]
    relative = (means[0] - means[1]) / means[1]
    passed = worst <= Z_LIMIT and abs(relative) <= MEAN_LIMIT
    # the table's row: scene, blocks x channels, worst |z|, share within 2, mean z^2, both means, their gap
    print("| %s | %d x %d blocks of %d x %d, 3 channels | %.2f | %.1f %% | %.2f | %.5f | %.5f | %+.2f %% | %s |" %
          (name, width // block, height // block, block, block, worst, 100.0 * within2 / tests, z2 / tests,
           means[0], means[1], 100 * relative, "agrees" if passed else "DISAGREES"))
    if len(args) > 6:  # the two pictures side by side, clipped and sRGB-encoded as chapter 15's PNG
        out = bpy.data.images.new("side by side", 2 * width, height, float_buffer=True)
        pixels = array.array("f", [0.0]) * (2 * width * height * 4)
        for j in range(height):
            for i in range(width):
                for c in range(3):
                    k = 4 * (j * width + i) + c
                    pixels[4 * (j * 2 * width + i) + c] = (oa[k] + ob[k]) / 2
                    pixels[4 * (j * 2 * width + width + i) + c] = (ca[k] + cb[k]) / 2
                pixels[4 * (j * 2 * width + i) + 3] = pixels[4 * (j * 2 * width + width + i) + 3] = 1.0
        out.pixels.foreach_set(pixels)
        scene = bpy.context.scene
        scene.view_settings.view_transform = "Standard"
        scene.view_settings.look = "None"
        scene.render.image_settings.file_format = "PNG"
        scene.render.image_settings.color_mode = "RGB"
        out.save_render(args[6], scene=scene)
    sys.exit(0 if passed else 1)


if __name__ == "__main__":
    main()
