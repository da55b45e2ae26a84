# bench_paths.py: chapter 15's path tracer against Blender's Cycles at equal noise (make bench-paths;
# docs/15-paths.md, "How fast, against Cycles"). Run with Blender's Python, which reads Cycles' OpenEXR:
#
#   blender -b --factory-startup --python-exit-code 1 --python tools/cycles/bench_paths.py -- \
#       CHAPTER15 THREADS OUT_DIR [SAMPLES...]
#
# The scene is chapter 15's Cornell box (scenes/15-paths.scene: diffuse walls, the lamp, the mirror ball
# and the glass ball) at BENCH_SIZE x BENCH_SIZE pixels. Each renderer draws it at each sample count
# (default 16, 64 and 256 a pixel) with two seeds, on THREADS threads: ours is CHAPTER15 (its PFM), once
# as the scene ships (`sampler sobol`: stratified paths, the headline row) and once with
# `--set paths.sampler=independent` (the program's default, for comparison), Cycles
# is tools/cycles/render.py with `smooth` (the balls as a sharp Glossy and a sharp Glass BSDF on smoothly
# shaded meshes), sampling its lights as it does by default, as ours does (multiple importance).
#
# Noise. The RMSE of a picture against the exact one, for an unbiased renderer, is the square root of the
# mean over pixels and channels of each pixel's variance; the two draws A and B at one count differ only by
# noise, so mean((A - B)^2) / 2 estimates it with no reference picture at all (a converged reference would
# add its own noise to the figure). Bias is checked apart: tools/cycles/compare.py tests the two
# renderers' pictures at the largest count block by block, as make compare-cycles does, and its row is
# printed (a renderer that converges to another picture cannot win this benchmark by being fast).
#
# Time. Ours is timed from outside (its whole process); Cycles from inside Blender, around its render call
# (render.py), so that Blender's start-up and the building of the scene in Python are not counted. Both
# still include a fixed cost (reading, building the BVH, Cycles' scene sync and kernel start), so the time
# a sample costs is the slope of a straight line fitted through (samples, seconds) over all the runs, and
# the fixed cost is left out of both. Wall-clock seconds and processor seconds (every thread's) are both
# measured; on a quiet machine with THREADS threads they tell the same story, on a loaded one the
# processor seconds are the steadier.
#
# Time to equal noise: RMSE ~ c / sqrt(samples) for an unbiased estimator, so c is fitted per renderer
# (the geometric mean of RMSE sqrt(samples) over the counts), the target is Cycles' RMSE at the largest
# count, and each renderer's time is (c / target)^2 samples at its cost per sample. Writes a table and
#   paths vs Cycles at equal noise (N threads, wall, sampler S): ours X s, Cycles Y s, ratio X/Y
# for each of our samplers, the scene's own (sobol) first
# to OUT_DIR/report.txt (and standard output, among Blender's own messages).
import math
import os
import re
import resource
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare  # noqa: E402  (Blender's Python: bpy is there)

BENCH_SIZE = 128
DEFAULT_SAMPLES = (16, 64, 256)
SEEDS = (1, 2)
SCENE = "scenes/15-paths.scene"
BLENDER = ["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python"]
HERE = os.path.dirname(os.path.abspath(__file__))


def fail(message):
    print("bench_paths.py: " + message, file=sys.stderr)
    sys.exit(1)


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_ours(chapter, scene, samples, seed, threads, out, sampler):
    start, cpu = time.perf_counter(), children_cpu()
    result = subprocess.run([chapter, scene, "--quiet", "--threads", str(threads), "--set", "paths.samples=%d" % samples,
                             "--set", "paths.seed=%d" % seed, "--set", "paths.sampler=" + sampler, "-o", out + ".png",
                             "--hdr", out + ".pfm"])
    if result.returncode != 0:
        fail("%s failed on %s" % (chapter, scene))
    return time.perf_counter() - start, children_cpu() - cpu, out + ".pfm"


def run_cycles(scene, samples, seed, threads, out):
    result = subprocess.run(BLENDER + [os.path.join(HERE, "render.py"), "--", scene, out + ".exr", str(samples),
                                       str(seed), str(threads), "smooth"], capture_output=True, text=True)
    with open(out + ".log", "w") as log:
        log.write(result.stdout + result.stderr)
    found = re.search(r"render\.py: rendered in ([0-9.]+) s, ([0-9.]+) s of processor time", result.stdout)
    if result.returncode != 0 or not found:
        fail("Blender failed on %s (see %s.log)" % (scene, out))
    return float(found.group(1)), float(found.group(2)), out + ".exr"


def noise(path_a, path_b):
    """The RMSE of one draw against the exact picture, from two draws that differ only by noise."""
    (w, h, a), (_, _, b) = compare.load(path_a), compare.load(path_b)
    total = 0.0
    for k in range(w * h):
        for c in range(3):
            total += (a[4 * k + c] - b[4 * k + c]) ** 2
    return math.sqrt(total / (2 * 3 * w * h))


def slope(points):
    """The least-squares slope of seconds against samples: the cost of one more sample a pixel."""
    n = len(points)
    mx, my = sum(x for x, _ in points) / n, sum(y for _, y in points) / n
    return sum((x - mx) * (y - my) for x, y in points) / sum((x - mx) ** 2 for x, _ in points)


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    if len(args) < 3:
        fail("usage: blender -b --python bench_paths.py -- CHAPTER15 THREADS OUT_DIR [SAMPLES...]")
    chapter, threads, out = os.path.abspath(args[0]), int(args[1]), os.path.abspath(args[2])
    counts = [int(a) for a in args[3:]] or list(DEFAULT_SAMPLES)
    if len(counts) < 2 or threads < 1:
        fail("at least two sample counts and one thread")
    os.makedirs(out, exist_ok=True)
    scene = os.path.join(out, "bench.scene")
    with open(SCENE) as source, open(scene, "w") as bench:
        for line in source:
            bench.write("image %d %d\n" % (BENCH_SIZE, BENCH_SIZE) if line.startswith("image ") else line)
    # (samples, wall, cpu, noise); ours as chapter 15's scene ships, then with the program's default sampler
    runs = {"ours (sobol)": [], "ours, independent": [], "Cycles": []}
    samplers = (("ours (sobol)", "sobol"), ("ours, independent", "independent"))
    for n in counts:
        paths = {name: [] for name in runs}
        for seed in SEEDS:  # the renderers in turn, so that a drift of the machine's speed hits all
            for name, sampler in samplers:
                wall, cpu, path = run_ours(chapter, scene, n, seed, threads, "%s/%s-%d-%d" % (out, sampler, n, seed),
                                           sampler)
                runs[name].append([n, wall, cpu])
                paths[name].append(path)
            wall, cpu, path = run_cycles(scene, n, seed, threads, "%s/cycles-%d-%d" % (out, n, seed))
            runs["Cycles"].append([n, wall, cpu])
            paths["Cycles"].append(path)
        for name in runs:
            sigma = noise(*paths[name])
            for run in runs[name][-len(SEEDS):]:
                run.append(sigma)
    largest = max(counts)
    check = subprocess.run(BLENDER + [os.path.join(HERE, "compare.py"), "--", "bench", "16",
                                      "%s/sobol-%d-1.pfm" % (out, largest), "%s/sobol-%d-2.pfm" % (out, largest),
                                      "%s/cycles-%d-1.exr" % (out, largest), "%s/cycles-%d-2.exr" % (out, largest)],
                           capture_output=True, text=True)
    rows = [line for line in check.stdout.splitlines() if line.startswith("|")]
    report = []
    say = report.append  # the report's lines, written out at the end
    say("chapter 15's Cornell box at %d x %d, %d thread%s, two seeds at each count" %
          (BENCH_SIZE, BENCH_SIZE, threads, "" if threads == 1 else "s"))
    say("| renderer | samples | RMSE | wall s | processor s |")
    say("|---|---|---|---|---|")
    fits = {}
    for name, rs in runs.items():
        for n, wall, cpu, sigma in rs[::len(SEEDS)]:
            say("| %s | %d | %.4f | %.3f | %.3f |" % (name, n, sigma, wall, cpu))
        c = math.exp(sum(math.log(sigma * math.sqrt(n)) for n, _, _, sigma in rs) / len(rs))
        fits[name] = (c, slope([(n, wall) for n, wall, _, _ in rs]), slope([(n, cpu) for n, _, cpu, _ in rs]))
    target = [sigma for n, _, _, sigma in runs["Cycles"] if n == largest][0]
    pixels = BENCH_SIZE * BENCH_SIZE
    for name, (c, per_wall, per_cpu) in fits.items():
        say("%s: RMSE %.4f / sqrt(samples); a sample a pixel costs %.4f s (wall), %.4f s (processor): %.0f paths "
              "a second (wall), %.0f a processor second" % (name, c, per_wall, per_cpu, pixels / per_wall,
                                                            pixels / per_cpu))
    say("target RMSE %.4f (Cycles' at %d samples)" % (target, largest))
    for clock, k in (("wall", 1), ("processor", 2)):
        times = {name: (fit[0] / target) ** 2 * fit[k] for name, fit in fits.items()}
        for ours, sampler in samplers:
            say("paths vs Cycles at equal noise (%d thread%s, %s, sampler %s): ours %.2f s, Cycles %.2f s, ratio %.2f" %
                (threads, "" if threads == 1 else "s", clock, sampler, times[ours], times["Cycles"],
                 times[ours] / times["Cycles"]))
    say("converged to the same picture (ours with sampler sobol against Cycles at %d samples, blocks of 16 x 16):" %
        largest)
    say("\n".join(rows) if rows else "compare.py printed no row: " + check.stderr.strip()[-300:])
    with open(os.path.join(out, "report.txt"), "w") as f:
        f.write("\n".join(report) + "\n")
    sys.stdout.write("\n".join(report) + "\n")


if __name__ == "__main__":
    main()
