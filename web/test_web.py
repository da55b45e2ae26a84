#!/usr/bin/python3
"""test_web.py: the chapters in a real browser (make test-web).

Serves build/web as `make serve` does, drives Debian's headless Chromium through chromium-driver and
Selenium, and checks the page against the native programs:
  - chapters 2, 8 and 10 at rest: the PNG the page's program wrote is byte for byte the native one for
    the same scene and command line, and the canvas's pixels are that picture's;
  - chapter 8's heat-map is the native one; every chapter's own scene at 160 x 120 (chapter 11 at its
    default rung 6, at the SIMD rung 3, the compact rung 7 and the packet rung 10) gives the native PNG too;
  - a broken scene line gives the native program's message ("scenes/NN-name.scene:LINE: what");
  - README's sizes of a chapter's modules ("at most X MB of `.wasm` and Y MB of script") are the
    largest of build/web/chapter-NN.wasm and .js rounded up to the hundredth of a megabyte;
and prints how fast it is: the page's first picture, chapter 8 at 640 x 480, the frame rate while the
camera is dragged, and chapter 10's 353,546 triangles against the native program on one thread. The
page explains itself (each chapter's idea, links and controls; downloads; the heat-map's scale), its
editor numbers lines and marks the error's, it refuses too big a picture, it fits 1280 x 800 and
375 x 667 without sideways scrolling (screenshots: --screenshot for README, and beside it the phone's)
and touches move the camera.

The engine (renders.js, worker.js and common/cli.c's held loop):
  - the teapot scene of chapter 10 dragged: coarse frames a second (printed, and asserted above a floor
    that a machine shared with other work still reaches), and its full picture at rest, drawn again by
    the held instances, against the native program's render on one thread;
  - one worker and several give the same bytes (chapters 8 and 12 in bands, 12's blocks whole);
  - chapter 15 drawn in passes of 1, 2, 4, 8 paths a pixel, its last the native picture byte for byte.
--only engine runs only these.

Run with the system's python3 (/usr/bin/python3), which is where Debian's python3-selenium installs.
Exit status 0 when every check holds; the speeds are printed against their targets, not asserted.
"""
import argparse
import base64
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import zlib

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        failures.append(what)


# README's sentence on the size of the page's modules.
README_MODULE_SIZES = re.compile(r"at most ([0-9.]+) MB of\s+`\.wasm` and\s+([0-9.]+) MB of script")


def check_module_sizes(web):
    """README's sizes of the chapters' modules are the largest .wasm and .js in build/web, in megabytes
    (10^6 bytes) rounded up to a hundredth: true, and not a loose bound that could hide growth."""
    with open(os.path.join(REPO, "README.md"), encoding="utf-8") as f:
        stated = README_MODULE_SIZES.search(f.read())
    check(stated is not None, "README states the size of the page's modules (at most X MB of `.wasm` and Y MB of script)")
    if stated is None:
        return
    for kind, said in ((".wasm", stated.group(1)), (".js", stated.group(2))):
        sizes = {os.path.basename(p): os.path.getsize(p) for p in glob.glob(os.path.join(web, f"chapter-*{kind}"))}
        name = max(sizes, key=sizes.get)
        largest = math.ceil(sizes[name] / 1e4) / 100
        check(float(said) == largest, f"README: at most {said} MB of {kind}; the largest is {name}, "
                                      f"{sizes[name]} bytes, {largest:.2f} MB rounded up")


def png_pixels(data):
    """The RGB pixels of an 8-bit, non-interlaced RGB or RGBA PNG (what stb writes): (w, h, bytes)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length = int.from_bytes(data[pos:pos + 4], "big")
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height = int.from_bytes(body[0:4], "big"), int.from_bytes(body[4:8], "big")
            assert body[8] == 8 and body[9] in (2, 6) and body[12] == 0, "unsupported PNG"
            channels = 3 if body[9] == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), width * channels
    out, prev = bytearray(), bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b, c = prev[x], prev[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        for x in range(width):
            out += line[x * channels:x * channels + 3]
    return width, height, bytes(out)


def run_native(build, chapter, args, text, threads=None):
    """Runs build/chapter-NN with the page's arguments on the page's scene text (written where the page's
    program had it, in a temporary copy of scenes/ that links the models and textures), its outputs
    going to that folder. Returns (status, stdout, stderr, picture bytes, heat-map bytes, wall seconds)."""
    folder = tempfile.mkdtemp(prefix="whitted-web-")
    os.makedirs(os.path.join(folder, "scenes"))
    for shared in ("models", "textures"):
        os.symlink(os.path.join(REPO, "scenes", shared), os.path.join(folder, "scenes", shared))
    with open(os.path.join(folder, args[0]), "w") as f:
        f.write(text)
    args = list(args)
    if "--heatmap" in args:
        args[args.index("--heatmap") + 1] = "heatmap.png"
    command = [os.path.join(REPO, build, f"chapter-{chapter:02d}")] + args + ["-o", "p.png"]
    if threads:
        command += ["--threads", str(threads)]
    started = time.monotonic()
    done = subprocess.run(command, cwd=folder, capture_output=True, text=True)
    seconds = time.monotonic() - started
    read = lambda name: open(os.path.join(folder, name), "rb").read() if os.path.exists(os.path.join(folder, name)) else None
    result = (done.returncode, done.stdout, done.stderr, read("p.png"), read("heatmap.png"), seconds)
    shutil.rmtree(folder)
    return result


class Page:
    def __init__(self, driver, base):
        self.driver, self.base = driver, base

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def wait(self, condition, timeout, what):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if self.js("return " + condition):
                return True
            time.sleep(0.02)
        raise TimeoutError(f"waited {timeout} s for {what}")

    def wait_idle(self, full_shown, timeout=120):
        """Waits until at least full_shown full pictures were shown and nothing is being drawn."""
        self.wait(f"window.whitted && window.whitted.fullShown >= {full_shown} && "
                  "document.body.dataset.state === 'idle'", timeout, "the full picture")

    def open(self, query, timeout=120):
        started = time.monotonic()
        self.driver.get(f"{self.base}/index.html?{query}")
        self.wait_idle(1, timeout)
        return time.monotonic() - started

    def last_full(self):
        """The last full render: its arguments, status, output, PNG bytes and the canvas's pixels."""
        got = self.js("""
            const f = window.whitted.lastFull, c = document.getElementById('picture');
            const b64 = a => { let s = ''; for (let k = 0; k < a.length; k += 32768)
                                   s += String.fromCharCode.apply(null, a.subarray(k, k + 32768));
                               return btoa(s); };
            const px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
            return {args: f.job.args, text: f.job.text, status: f.result.status, stdout: f.result.stdout, stderr: f.result.stderr,
                    ms: f.result.ms, picture: f.result.picture ? b64(f.result.picture) : null,
                    heatmap: f.result.heatmap ? b64(f.result.heatmap) : null,
                    width: c.width, height: c.height, canvas: b64(px)};""")
        for key in ("picture", "heatmap", "canvas"):
            got[key] = base64.b64decode(got[key]) if got[key] else None
        return got

    def set_control(self, element_id, value):
        self.js("const e = document.getElementById(arguments[0]);"
                "if (e.type === 'checkbox') e.checked = arguments[1]; else e.value = arguments[1];"
                "e.dispatchEvent(new Event('change'));", element_id, value)

    def full_shown(self):
        return self.js("return window.whitted.fullShown")


def compare_with_native(page, build, chapter, label):
    """The page's last full picture against the native program's with the same arguments."""
    got = page.last_full()
    status, _, stderr, picture, heatmap, _ = run_native(build, chapter, got["args"], got["text"])
    command = f"chapter-{chapter:02d} " + " ".join(got["args"])
    check(got["status"] == 0 and status == 0, f"{label}: page and native both render ({command})"
          + ("" if status == 0 and got["status"] == 0 else f"; page: {got['stderr'].strip()}; native: {stderr.strip()}"))
    if picture is None or got["picture"] is None:
        return got
    same = got["picture"] == picture
    check(same, f"{label}: the page's PNG is byte for byte the native one ({len(picture)} bytes)")
    if not same:
        w, h, native = png_pixels(picture)
        page_px = png_pixels(got["picture"])[2]
        differ = sum(1 for k in range(0, len(native), 3) if native[k:k + 3] != page_px[k:k + 3])
        print(f"      {differ} of {w * h} pixels differ")
    # The canvas shows the picture, or with --heatmap the heat-map (with its colour bar).
    w, h, native = png_pixels(heatmap if "--heatmap" in got["args"] else picture)
    canvas = got["canvas"]
    shown = bytes(b for k in range(0, len(canvas), 4) for b in canvas[k:k + 3]) if canvas else b""
    check((got["width"], got["height"]) == (w, h) and shown == native,
          f"{label}: the canvas shows those pixels ({got['width']} x {got['height']})")
    if "--heatmap" in got["args"]:
        check(got["heatmap"] == heatmap, f"{label}: the heat-map is byte for byte the native one")
    return got


def drag(page, seconds):
    """Drags the camera around for about `seconds`; returns the coarse frames shown per second."""
    canvas = page.driver.find_element(By.ID, "picture")
    before = page.js("return window.whitted.renders.length")
    started = time.monotonic()
    actions = ActionChains(page.driver, duration=0)
    actions.move_to_element(canvas).click_and_hold()
    steps = int(seconds / 0.02)
    for k in range(steps):
        actions.move_by_offset(4 if (k // 40) % 2 == 0 else -4, 1 if (k // 25) % 2 == 0 else -1).pause(0.02)
    actions.perform()
    elapsed = time.monotonic() - started
    renders = page.js("return window.whitted.renders.slice(arguments[0])", before)
    ActionChains(page.driver).release().perform()
    coarse = [r for r in renders if r["coarse"] and r["status"] == 0]
    mean = sum(r["ms"] for r in coarse) / len(coarse) if coarse else float("nan")
    return len(coarse) / elapsed, mean, elapsed


def measure_chapter_8(page, build, label, shown):
    """On chapter 8's page, after `shown` full pictures: the full picture at 640 x 480 against the
    native one and the time it takes (three renders, at depths 5, 3 and the scene's), then the frame
    rate while the camera is dragged at the scene's size, ending at rest."""
    page.set_control("size", "640x480")
    page.wait_idle(shown + 1)
    got = compare_with_native(page, build, 8, f"{label} at 640 x 480")
    times = []
    for depth in ("5", "3", ""):
        n = page.full_shown()
        page.set_control("max-depth", depth)
        page.wait_idle(n + 1)
        times.append(page.js("return window.whitted.renders[window.whitted.renders.length - 1].ms"))
    native = run_native(build, 8, got["args"], got["text"], threads=1)[5]
    print(f"{label} at 640 x 480 at rest: {sorted(times)[1] / 1000:.2f} s (median of 3; target 1 s); "
          f"native, one thread: {native:.2f} s")
    page.set_control("size", "")
    page.wait_idle(page.full_shown())
    fps, mean, elapsed = drag(page, 4)
    print(f"{label} dragged for {elapsed:.1f} s: {fps:.1f} coarse frames a second (target 15), "
          f"{mean:.0f} ms a frame from request to canvas")
    page.wait_idle(page.full_shown() + 1)


# The frames a second the teapot's drag must reach at least. The target is 15 on two idle cores; the test
# machine is often shared (a loaded machine halves the rate), and a fresh instance for every frame, what
# the held instances replaced, gave 1 to 2: a floor of 5 fails the second and passes the first under load.
TEAPOT_FPS_FLOOR = 5


def open_page(page, query, timeout=300):
    page.driver.get("about:blank")
    return page.open(query, timeout)


def test_teapot(page, build):
    """Chapter 10's teapot scene: the frame rate of a drag and the full picture's time, held."""
    open_page(page, "chapter=10")
    workers = page.js("return window.whitted.workers")
    page.wait_idle(page.full_shown(), 300)
    fps, mean, elapsed = drag(page, 6)
    print(f"teapot (chapter 10) dragged for {elapsed:.1f} s on {workers} workers: {fps:.1f} coarse frames a second "
          f"(target 15, floor {TEAPOT_FPS_FLOOR}), {mean:.0f} ms a frame from request to canvas; load: "
          f"{os.getloadavg()[0]:.1f}")
    check(fps >= TEAPOT_FPS_FLOOR, f"teapot drag: {fps:.1f} frames a second >= {TEAPOT_FPS_FLOOR}")
    page.wait_idle(page.full_shown() + 1, 300)
    got = compare_with_native(page, build, 10, "teapot after the drag")
    times = []
    for size in ("640x480", "", "640x480"):  # the scene's own size: the same picture, the same world, drawn again
        n = page.full_shown()
        page.set_control("size", size)
        page.wait_idle(n + 1, timeout=300)
        times.append(page.js("return window.whitted.lastFull.result.ms") / 1000)
    native = []
    for _ in range(3):
        out = run_native(build, 10, got["args"], got["text"], threads=1)
        wrote = re.search(r"\) in ([0-9.]+) s", out[1])
        native.append((float(wrote.group(1)) if wrote else float("nan"), out[5]))
    in_page = sorted(times)[1]
    render, whole = sorted(n[0] for n in native)[1], sorted(n[1] for n in native)[1]
    print(f"teapot at rest, 640 x 480: {in_page:.2f} s in the page on {workers} workers (median of 3); natively on one "
          f"thread {render:.2f} s to render, {whole:.2f} s the whole program: ratio {in_page / render:.2f} to the "
          f"render (target 1.5), {in_page / whole:.2f} to the program; load: {os.getloadavg()[0]:.1f}")
    check(in_page <= 3 * render, f"teapot at rest: {in_page:.2f} s within 3 x the native render's {render:.2f} s")


def page_picture(page, query, size, samples=None):
    """The full picture of the page opened with query, at size (and samples): its PNG bytes."""
    open_page(page, query)
    n = page.full_shown()
    page.set_control("size", size)
    page.wait_idle(n + 1, 300)
    if samples:
        n = page.full_shown()
        page.set_control("samples", samples)
        page.wait_idle(n + 1, 300)
    return page.last_full()


def test_workers_same_bytes(page, build):
    """One worker and several draw the same bytes, the native ones (bands of rows joined)."""
    for chapter, size in ((8, "160x120"), (12, "200x150")):
        one = page_picture(page, f"chapter={chapter}&workers=1", size)
        several = page_picture(page, f"chapter={chapter}&workers=3", size)
        workers = page.js("return window.whitted.workers")
        check(one["picture"] is not None and one["picture"] == several["picture"] and workers == 3,
              f"chapter {chapter} at {size}: 1 worker and {workers} the same PNG ({len(one['picture'] or b'')} bytes)")
        # The counters the page shows for the bands joined are the whole picture's (all but the time).
        counts = lambda r: re.sub(r" in [0-9.]+ s", "", r["stdout"] or "")
        check(counts(one) == counts(several) and "counters:" in counts(one),
              f"chapter {chapter} at {size}: the counters of {workers} bands joined are one worker's")
        compare_with_native(page, build, chapter, f"chapter {chapter} at {size} on {workers} workers")


def test_progressive_paths(page, build):
    """Chapter 15 in passes of 1, 2, 4 and 8 paths a pixel, the last the native picture."""
    got = page_picture(page, "chapter=15&workers=2", "96x96", samples="8")
    passes = page.js("return window.whitted.passes.map(p => [p.samplesDone, p.samplesTotal, p.secondsLeft])")
    last = [p[0] for p in passes if p[1] == 8][-3:]
    print(f"chapter 15 passes (samples done, total, seconds left): {passes[-3:]}")
    check(last == [1, 2, 4], f"chapter 15: passes of 1, 2 and 4 paths shown before the 8 ({last})")
    check("paths.samples=8" in got["args"], "chapter 15: the full picture asked for 8 paths a pixel")
    compare_with_native(page, build, 15, "chapter 15 after its passes, 8 paths a pixel")


def test_release_while_a_picture_is_shown(page):
    """A drag released while a coarse picture is being put on the canvas, with a newer coarse request
    waiting behind it, still ends in the full picture. (The waiting request used to start after the full
    one and take its place: the full picture never came.) Putting a picture on the canvas is slowed to
    300 ms, so the release surely falls in that moment."""
    open_page(page, "chapter=8")
    n = page.full_shown()
    page.driver.execute_async_script("""
        const done = arguments[arguments.length - 1], canvas = document.getElementById('picture');
        const decode = window.createImageBitmap, before = window.whitted.renders.length;
        window.createImageBitmap = (...a) => new Promise(r => setTimeout(() => r(decode(...a)), 300));
        const pointer = (type, x) => canvas.dispatchEvent(new PointerEvent(type,
            {pointerId: 1, pointerType: 'mouse', clientX: x, clientY: 20, button: 0, bubbles: true}));
        pointer('pointerdown', 100);
        pointer('pointermove', 110); // the first coarse picture starts
        pointer('pointermove', 120); // the second waits for it
        const released = () => {
            if (window.whitted.renders.length === before)
                return setTimeout(released, 1);
            pointer('pointerup', 120); // the first is drawn and being shown, the second still waits
            window.createImageBitmap = decode;
            done();
        };
        released();""")
    try:
        page.wait_idle(n + 1, timeout=60)
        came = True
    except TimeoutError:
        came = False
    renders = page.js("return window.whitted.renders.slice(-3).map(r => r.coarse ? 'coarse' : 'full')")
    check(came, f"a release while a coarse picture is shown ends in the full picture (last renders: {renders})")


def test_engine(page, build):
    test_release_while_a_picture_is_shown(page)
    test_workers_same_bytes(page, build)
    test_progressive_paths(page, build)
    test_teapot(page, build)


CHAPTER_NAMES = ["camera", "sphere", "triangle", "plane", "aabb", "phong", "shadows", "recursion", "kdtree",
                 "bvh", "fast", "antialias", "distributed", "textures", "paths", "instances", "rough"]
TRY_LINK = re.compile(r"\]\(([^)]*)index\.html\?chapter=(\d+)\)")


def check_try_links():
    """Every walkthrough has a "try it" link to its own chapter's page, all on one base address."""
    bases = set()
    for n, name in enumerate(CHAPTER_NAMES, 1):
        with open(os.path.join(REPO, "docs", f"{n:02d}-{name}.md"), encoding="utf-8") as f:
            links = TRY_LINK.findall(f.read())
        check(len(links) == 1 and links[0][1] == str(n),
              f"docs/{n:02d}-{name}.md links to the page at chapter {n} once: {links}")
        bases.update(base for base, _ in links)
    check(len(bases) == 1, f"the walkthroughs' links to the page share one address: {sorted(bases)}")


def visible(page, element_id):
    return page.js("const e = document.getElementById(arguments[0]); return e.offsetParent !== null;", element_id)


def check_explained(page, chapter):
    """The chapter's idea, its walkthrough, its main.c and the scene format are shown and can be fetched; the
    controls are those the chapter reads."""
    name = f"{chapter:02d}-{CHAPTER_NAMES[chapter - 1]}"
    got = page.js("""
        const read = id => document.getElementById(id);
        const fetched = async a => (await fetch(a.href)).status;
        return (async () => ({idea: read('idea').textContent,
            walk: read('walkthrough-link').href, source: read('source-link').href, format: read('format-link').href,
            status: [await fetched(read('walkthrough-link')), await fetched(read('source-link')),
                     await fetched(read('format-link'))]}))();""")
    check(got["idea"].startswith(f"Chapter {chapter}, {CHAPTER_NAMES[chapter - 1]}: ") and len(got["idea"]) > 40,
          f"chapter {chapter}: the page says its idea: {got['idea']!r}")
    check(got["walk"].endswith(f"docs/{name}.md") and got["source"].endswith(f"chapters/{name}/main.c")
          and got["format"].endswith("docs/scene-format.md") and got["status"] == [200, 200, 200],
          f"chapter {chapter}: links to its walkthrough, main.c and the scene format answer {got['status']}")
    shown = {k: visible(page, k) for k in ("max-depth", "bounces", "samples", "accel", "split", "rung")}
    expected = {"max-depth": 8 <= chapter and chapter not in (15, 17), "bounces": chapter in (15, 17),
                "samples": chapter >= 12, "accel": chapter >= 9 and chapter != 16,
                "split": chapter >= 9 and chapter != 16, "rung": chapter == 11}
    check(shown == expected, f"chapter {chapter}: the controls shown are those it reads: {shown}")


def check_downloads_and_counters(page):
    """Chapter 2's downloads are named after it, the heat-map's too, with a note on what it counts; the
    counters say what was drawn, not a file inside the page; the heat-map link goes with the heat-map."""
    page.open("chapter=2")
    names = lambda: page.js("return ['download-picture', 'download-scene', 'download-heatmap']"
                            ".map(id => [document.getElementById(id).download, "
                            "document.getElementById(id).offsetParent !== null])")
    counters = page.driver.find_element(By.ID, "counters").text
    size = page.js("const c = document.getElementById('picture'); return `${c.width} x ${c.height}`;")
    check(names() == [["chapter-02-sphere.png", True], ["02-sphere.scene", True], ["", False]],
          f"chapter 2's downloads: {names()}")
    check("out/" not in counters and re.search(rf"chapter 2 \(sphere\): drew {size} in", counters) is not None,
          f"the counters say what was drawn: {counters.splitlines()[0]!r}")
    n = page.full_shown()
    page.set_control("heatmap", True)
    page.wait_idle(n + 1)
    note = page.driver.find_element(By.ID, "heat-note").text
    check(names()[2] == ["chapter-02-sphere-heatmap.png", True] and "8192" in note and "tests" in note,
          f"the heat-map's download {names()[2]} and its note: {note!r}")
    page.set_control("heatmap", False)
    page.wait_idle(n + 2)


def set_scene(page, text):
    page.js("const e = document.getElementById('scene'); e.value = arguments[0];"
            "e.dispatchEvent(new Event('input'));", text)


def check_editor(page):
    """On chapter 8's scene, 40 comment lines longer (so that the editor scrolls): one line number a line; a
    broken line is marked in the editor (the band over its line, scrolled with the text and the numbers)
    and the old picture is marked stale; mending it clears both."""
    page.open("chapter=8")
    n = page.full_shown()
    text = "# a comment\n" * 40 + page.js("return document.getElementById('scene').value")
    set_scene(page, text)
    page.wait_idle(n + 1)
    numbers = page.driver.find_element(By.ID, "gutter").get_attribute("textContent").split("\n")
    lines = text.split("\n")
    check(numbers[:len(lines)] == [str(k) for k in range(1, len(lines) + 1)] and not "".join(numbers[len(lines):]),
          f"the gutter numbers the scene's {len(lines)} lines")
    line = len(lines) - 1  # near the end, so that the editor scrolls to it
    while not lines[line - 1].startswith("sphere"):
        line -= 1
    broken = lines[:line - 1] + ["sphere centre 0 1 0 radius -2 material glass"] + lines[line:]
    n = len(page.js("return window.whitted.renders"))
    set_scene(page, "\n".join(broken))
    page.wait(f"window.whitted.renders.length > {n} && document.body.dataset.state === 'idle'", 60, "the message")
    page.js("document.getElementById('scene').scrollTop = 300; document.getElementById('scene')"
            ".dispatchEvent(new Event('scroll'));")
    got = page.js("""const s = document.getElementById('scene'), m = document.getElementById('error-line'),
                     g = document.getElementById('gutter');
                     return {top: m.offsetTop, shown: m.offsetParent !== null, scroll: s.scrollTop, gutter: g.scrollTop,
                             stale: document.getElementById('view').classList.contains('stale'),
                             note: document.getElementById('stale-note').offsetParent !== null,
                             opacity: getComputedStyle(document.getElementById('picture')).opacity};""")
    check(got["shown"] and got["scroll"] > 0 and got["top"] == 4 + (line - 1) * 18 - got["scroll"]
          and got["gutter"] == got["scroll"],
          f"the error's line {line} is marked beside its number (band at {got['top']} px, scrolled {got['scroll']} px)")
    check(got["stale"] and got["note"] and float(got["opacity"]) < 1,
          f"while the error stands the old picture is marked stale (opacity {got['opacity']})")
    n = page.full_shown()
    set_scene(page, text)
    page.wait_idle(n + 1)
    check(not visible(page, "error-line") and not visible(page, "stale-note"), "mended, the marks are gone")


def check_size_guard(page):
    """A 16384 x 16384 picture is refused before any render, with the reason; the scene's size again draws."""
    page.open("chapter=8")
    text = page.js("return document.getElementById('scene').value")
    lines = text.split("\n")
    k = next(k for k, l in enumerate(lines) if l.startswith("image"))
    n = len(page.js("return window.whitted.renders"))
    set_scene(page, "\n".join(lines[:k] + ["image 16384 16384"] + lines[k + 1:]))
    time.sleep(1.5)  # past the typing pause
    message = page.driver.find_element(By.ID, "errors").text
    renders = len(page.js("return window.whitted.renders"))
    check(renders == n and "16384 x 16384 is 268.4 megapixels: the page draws at most 16.8" in message
          and visible(page, "error-line"), f"a 16384 x 16384 picture is refused without a render: {message!r}")
    n = page.full_shown()
    set_scene(page, text)
    page.wait_idle(n + 1)
    check(page.driver.find_element(By.ID, "errors").text == "", "the scene's own size draws again")


def emulate(page, width, height, mobile):
    page.driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                                {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": mobile})
    page.driver.execute_cdp_cmd("Emulation.setTouchEmulationEnabled", {"enabled": mobile, "maxTouchPoints": 2})


def layout(page):
    return page.js("""const box = id => { const r = document.getElementById(id).getBoundingClientRect();
                                          return {left: r.left, right: r.right, top: r.top, bottom: r.bottom}; };
                      return {scroll: document.documentElement.scrollWidth, width: innerWidth, height: innerHeight,
                              picture: box('picture'), editor: box('scene'), counters: box('counters')};""")


def check_layout(page, width, height, screenshot):
    """At width x height: chapter 8 (a 640 x 480 picture) and chapter 15 (its long counter line) at 160 x 120
    fit the width with the editor and the picture on the page; on a wide screen both within the first
    screen, the editor in the same place for both chapters. Saves a screenshot of chapter 8."""
    emulate(page, width, height, width < 800)
    places = []
    for query in ("chapter=15", "chapter=8"):
        page.driver.get(f"{page.base}/index.html?{query}")
        page.wait("window.whitted && window.whitted.renders.length >= 1", 120, "a first picture")
        if query == "chapter=15":  # chapter 15's full picture is slow: a small one
            page.set_control("size", "160x120")
        page.wait_idle(1, 300)
        got = layout(page)
        pic, ed = got["picture"], got["editor"]
        fits = all(0 <= b["left"] and b["right"] <= got["width"] for b in (pic, ed, got["counters"]))
        within = pic["top"] < height and ed["top"] < height if width >= 800 else True
        check(got["scroll"] <= got["width"] and fits and within and ed["bottom"] - ed["top"] >= 200,
              f"{width} x {height}, {query}: no sideways scroll ({got['scroll']} <= {got['width']}), picture "
              f"{pic['left']:.0f}..{pic['right']:.0f} top {pic['top']:.0f}, editor {ed['left']:.0f}..{ed['right']:.0f} "
              f"top {ed['top']:.0f}")
        places.append(ed["left"])
    check(places[0] == places[1], f"{width} x {height}: the editor stays in place between chapters ({places})")
    if screenshot:
        page.driver.save_screenshot(screenshot)
        print(f"screenshot: {screenshot}")


def touch(page, kind, points_list):
    page.driver.execute_cdp_cmd("Input.dispatchTouchEvent", {
        "type": kind, "touchPoints": [{"x": x, "y": y, "id": k} for k, (x, y) in enumerate(points_list)]})


def camera(page):
    return page.js("return document.getElementById('scene').value.split('\\n').find(l => l.startsWith('camera'))")


def check_touch(page):
    """At 375 x 667 with touch: one finger orbits, two fingers spreading zoom in, two moving together pan; each
    moves the camera line, and lifting the fingers draws the full picture."""
    emulate(page, 375, 667, True)
    page.open("chapter=8")
    r = page.js("const r = document.getElementById('picture').getBoundingClientRect();"
                "return [r.left + r.width / 2, r.top + r.height / 2];")
    x, y = r
    eye = lambda c: [float(v) for v in c.split("eye")[1].split()[:3]]
    target = lambda c: [float(v) for v in c.split("target")[1].split()[:3]]
    gestures = (("one finger", [[(x + 8 * k, y)] for k in range(8)]),
                ("a pinch", [[(x - 20 - 2 * k, y), (x + 20 + 2 * k, y)] for k in range(8)]),
                ("two fingers", [[(x - 20, y + 4 * k), (x + 20, y + 4 * k)] for k in range(8)]))
    for what, steps in gestures:
        before, n = camera(page), page.full_shown()
        touch(page, "touchStart", steps[0])
        for points in steps[1:]:
            touch(page, "touchMove", points)
            time.sleep(0.03)
        touch(page, "touchEnd", [])
        page.wait_idle(n + 1, 300)  # the full picture after the gesture; slow on a loaded machine
        after = camera(page)
        span = lambda c: math.dist(eye(c), target(c))
        if what == "one finger":
            ok = target(after) == target(before) and eye(after) != eye(before) and abs(span(after) - span(before)) < 1e-3
        elif what == "a pinch":
            ok = target(after) == target(before) and span(after) < span(before) - 1e-3
        else:
            ok = target(after) != target(before) and abs(span(after) - span(before)) < 1e-3
        check(ok, f"touch, {what}: {before!r} -> {after!r}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--web", default="build/web")
    parser.add_argument("--build", default="build")
    parser.add_argument("--port", type=int, default=8642)
    parser.add_argument("--screenshot", default=None)
    parser.add_argument("--only", choices=["engine"], default=None, help="run only the engine's tests")
    o = parser.parse_args()
    os.chdir(REPO)
    if not o.only:
        check_module_sizes(o.web)

    server = subprocess.Popen([sys.executable, "-m", "http.server", "--bind", "127.0.0.1", str(o.port)],
                              cwd=o.web, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1300,900"):
        options.add_argument(flag)
    driver = None
    try:
        time.sleep(0.5)
        driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
        page = Page(driver, f"http://127.0.0.1:{o.port}")
        test_engine(page, o.build)
        if o.only:
            return finish()

        # Chapter 2, and the first view of the page.
        page.open("chapter=2")
        page.driver.get(f"{page.base}/index.html?chapter=8")  # with the browser's caches warm
        page.wait_idle(1)
        first = page.js("return performance.getEntriesByType('navigation')[0].domContentLoadedEventEnd")
        renders = page.js("return window.whitted.renders")
        full = next(r for r in renders if not r["coarse"])
        print(f"page: controls shown {first:.0f} ms after loading; chapter 8's first (coarse) picture at "
              f"{renders[0]['at']:.0f} ms (target 2000 ms), its full picture at {full['at']:.0f} ms "
              f"(the program {full['programMs']:.0f} ms)")
        compare_with_native(page, o.build, 8, "chapter 8")
        page.open("chapter=2")
        compare_with_native(page, o.build, 2, "chapter 2")

        # Chapter 8: the heat-map, the full 640 x 480 picture, the drag.
        page.open("chapter=8")
        n = page.full_shown()
        page.set_control("heatmap", True)
        page.wait_idle(n + 1)
        compare_with_native(page, o.build, 8, "chapter 8 heat-map")
        page.set_control("heatmap", False)
        page.wait_idle(n + 2)
        measure_chapter_8(page, o.build, "chapter 8", n + 2)
        compare_with_native(page, o.build, 8, "chapter 8 after the drag (the moved camera's scene)")

        # Chapter 8's other scene, the glass of water (no mesh): the same measures.
        page.open("chapter=8&scene=08-glass-of-water.scene")
        measure_chapter_8(page, o.build, "chapter 8, glass of water,", page.full_shown())
        page.open("chapter=8")

        # A broken line: the native program's message.
        text = page.js("return document.getElementById('scene').value").split("\n")
        line = next(k for k, l in enumerate(text) if l.startswith("sphere")) + 1
        text[line - 1] = "sphere centre 0 1 0 radius -2 material glass"
        broken = "\n".join(text)
        n = len(page.js("return window.whitted.renders"))
        page.js("const e = document.getElementById('scene'); e.value = arguments[0];"
                "e.dispatchEvent(new Event('input'));", broken)
        page.wait(f"window.whitted.renders.length > {n} && document.body.dataset.state === 'idle'", 60, "the message")
        shown = page.driver.find_element(By.ID, "errors").text.strip()
        args = page.js("return window.whitted.renders[window.whitted.renders.length - 1].args")
        status, _, stderr, _, _, _ = run_native(o.build, 8, args, broken)
        check(status == 1 and shown == stderr.strip() and shown.startswith(f"scenes/08-recursion.scene:{line}:"),
              f"a broken line {line} shows the native message: {shown!r}")

        # The page explains itself, its editor, its size guard, its layout and touch.
        check_try_links()
        for chapter in (8, 11, 15, 16):
            page.open(f"chapter={chapter}") if chapter != 15 else page.driver.get(f"{page.base}/index.html?chapter=15")
            page.wait("document.getElementById('idea').textContent !== ''", 60, "the chapter's idea")
            check_explained(page, chapter)
        check_downloads_and_counters(page)
        check_editor(page)
        check_size_guard(page)
        # README's screenshot is the wide one; the phone's goes beside it (web-page-375x667.png).
        check_layout(page, 1280, 800, o.screenshot)
        check_layout(page, 375, 667, o.screenshot and re.sub(r"(\.png)?$", "-375x667.png", o.screenshot, count=1))
        check_touch(page)
        emulate(page, 1280, 800, False)

        # Every chapter's own scene at 160 x 120, and chapter 11's SIMD rung (3), compact rung (7) and
        # packet rung (10: rung 6's tree in the browser, rung 8's natively, the same picture).
        for chapter in range(1, 18):
            page.open(f"chapter={chapter}", timeout=300)
            n = page.full_shown()
            page.set_control("size", "160x120")
            page.wait_idle(n + 1, timeout=300)
            compare_with_native(page, o.build, chapter, f"chapter {chapter} at 160 x 120")
            for rung in ("3", "7", "10") if chapter == 11 else ():
                n = page.full_shown()
                page.set_control("rung", rung)
                page.wait_idle(n + 1, timeout=300)
                compare_with_native(page, o.build, chapter, f"chapter 11 at 160 x 120, rung {rung}")
            if chapter == 11:  # no structure built: the rung and split controls pass nothing (the programs refuse them)
                for control, value in (("split", "seed"), ("accel", "none")):
                    n = page.full_shown()
                    page.set_control(control, value)
                    page.wait_idle(n + 1, timeout=300)
                got = compare_with_native(page, o.build, chapter, "chapter 11 at 160 x 120, --accel none")
                check("--accel" in got["args"] and "--rung" not in got["args"] and "--split" not in got["args"],
                      f"chapter 11 with no structure passes neither rung nor split: {' '.join(got['args'])}")
            if chapter == 15:  # the bounces control sets the paths line's bounces
                n = page.full_shown()
                page.set_control("bounces", "1")
                page.wait_idle(n + 1, timeout=300)
                got = compare_with_native(page, o.build, chapter, "chapter 15 at 160 x 120, one bounce")
                check("paths.bounces=1" in got["args"], f"chapter 15's bounces control: {' '.join(got['args'])}")

        # Chapter 10: the big teapot, from a fresh page.
        started = time.monotonic()
        page.open("chapter=10", timeout=300)
        first10 = time.monotonic() - started
        got = compare_with_native(page, o.build, 10, "chapter 10")
        page_times, native_times = [got["ms"] / 1000], []
        for depth in ("5", ""):  # the scene's own max_depth is 5: the same picture, drawn again
            n = page.full_shown()
            page.set_control("max-depth", depth)
            page.wait_idle(n + 1, timeout=300)
            page_times.append(page.js("return window.whitted.lastFull.result.ms") / 1000)
        for _ in range(3):
            native_times.append(run_native(o.build, 10, got["args"], got["text"], threads=1)[5])
        in_page, native = sorted(page_times)[1], sorted(native_times)[1]
        triangles = next((l for l in got["stdout"].splitlines() if l.startswith("acceleration:")), "")
        print(f"chapter 10: first full picture {first10:.1f} s after loading the page (target 10 s); the program "
              f"{in_page:.2f} s in the page, {native:.2f} s natively on one thread, whole process (medians of 3; "
              f"ratio {in_page / native:.2f}, target 3)")
        if triangles:
            print(f"      {triangles.strip()}")

    finally:
        if driver:
            driver.quit()
        server.terminate()
        server.wait()
    return finish()


def finish():
    print(f"test-web: {'all checks hold' if not failures else f'{len(failures)} checks FAILED'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
