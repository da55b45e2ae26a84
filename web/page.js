// page.js: the page's controls: the chapter and its scene (its idea, its walkthrough and source), the
// editor (line numbers, the error's line), the camera under the mouse and the fingers, the settings each
// chapter's command line takes, and the renders, which workers run (renders.js, worker.js).
//
// Every picture is the chapter program's own, run with a command line the page shows (the same line
// gives the same picture natively). While the camera moves the program draws a coarse picture (a
// fraction of the width and height, one sample a pixel); at rest, the full one, which the path tracers
// (chapters 15 and 17) draw in passes of more and more samples. A new change while a full picture is
// being drawn stops it.
"use strict";

const CHAPTERS = ["camera", "sphere", "triangle", "plane", "aabb", "phong", "shadows", "recursion", "kdtree",
                  "bvh", "fast", "antialias", "distributed", "textures", "paths", "instances", "rough"];
// Each chapter's new idea, in one line (its walkthrough, docs/NN-name.md, tells the whole story).
const IDEAS = [
    "one ray through the centre of every pixel, coloured by the way it points: the camera alone.",
    "a ray meets a sphere (the quadratic formula); each pixel shows the nearest hit, lit from the eye.",
    "triangles and whole meshes (Möller–Trumbore, then a watertight test), every triangle tried by every ray.",
    "infinite planes: a floor under the shapes, the one shape without a bounding box.",
    "the slab test: boxes as shapes, and a box around each mesh that a missing ray skips whole.",
    "materials and coloured point lights: ambient, diffuse and highlight terms replace the light at the eye.",
    "a shadow ray to each light, offset from the surface so that it does not hit its own start.",
    "mirrors and glass spawn reflected and refracted rays, traced like the camera's, to a maximum depth.",
    "space cut in two again and again; a ray visits the cells it crosses, front to back.",
    "triangles grouped and boxed, the groups split again, so a ray skips every group whose box it misses.",
    "chapter 10's tree and answers, laid out and walked for speed, one rung at a time.",
    "several camera rays a pixel, averaged, some only where neighbouring colours differ.",
    "area lights cast soft shadows, and a lens gives depth of field.",
    "colours that change from point to point (patterns and image maps), and smooth meshes.",
    "the rendering equation solved by Monte Carlo: random paths from the camera, averaged per pixel.",
    "many objects from a few meshes on a two-level BVH, with animation and motion blur.",
    "glossy metal and frosted glass from GGX microfacets, in chapter 15's path tracer.",
];
// The chapters that trace paths (chapter 15's estimator): their samples and bounces are the paths line's.
const PATH_CHAPTERS = [15, 17];
// The settings each chapter's program reads (its --help and its scene's lines); a control is shown only
// on the chapters that read it. depth: the scene's max_depth (chapter 8's recursion and those built on
// it); bounces: the paths line's (15 and 17 stop by bounces and Russian roulette, not max_depth);
// samples: the antialias line's (12 to 14, 16) or the paths line's; accel and split: --accel, --split
// (chapter 16 builds its own two-level tree and takes neither); rung: chapter 11's --rung.
const READS = {
    depth: n => n >= 8 && !PATH_CHAPTERS.includes(n),
    bounces: n => PATH_CHAPTERS.includes(n),
    samples: n => n >= 12,
    accel: n => n >= 9 && n !== 16,
    split: n => n >= 9 && n !== 16,
    rung: n => n === 11,
};
// What the heat-map counts: the samplers of chapters 12, 13, 14 and 16 draw camera rays a pixel on a
// scale to 100 (common/supersample.c); every other chapter draws the work a pixel on a scale to 8192
// (common/heatmap.h).
const CAMERA_RAY_HEATMAP = [12, 13, 14, 16];
// The largest picture the page draws (4096 x 4096): a bigger one would hold gigabytes in the tab (the
// native program draws any size).
const MAX_PIXELS = 4096 * 4096;
// Where the walkthroughs, the chapters' main.c and the scene format are (make web's WEB_REPO_BASE, in
// site.js): empty for the copies beside the page.
const REPO_BASE = (window.WHITTED_SITE && window.WHITTED_SITE.repoBase) || "";
// The editor's line height in pixels (index.html's #gutter and #scene) and the text's top padding.
const LINE_HEIGHT = 18, EDITOR_PAD = 4;
// Chapter 11's rungs, 1 to 10. In the browser rungs 8 and 9 are rung 6, and rung 10's packets walk rung 6's
// tree (WebAssembly has no AVX2; --stats says so).
const RUNGS = ["plain", "wide", "simd", "prefetch", "build", "float", "compact", "eight", "lean", "packet"];
// While the camera moves, the picture is state.coarse times smaller each way: 4 to start with, then
// whatever keeps one coarse picture near COARSE_MS of the program's time (from COARSE_MIN to COARSE_MAX).
const COARSE_MS = 30, COARSE_START = 4, COARSE_MIN = 2, COARSE_MAX = 16;
// The canvas's size for a scene whose image line cannot be read (the program then reports the error).
const DEFAULT_SIZE = [400, 300];
const DEFAULT_CHAPTER = 8; // shown when the address names none
const TYPING_PAUSE = 300; // ms without typing before the picture follows the editor
// The camera under the mouse: radians of orbit a pixel, the distance to the target panned a pixel, the
// distance's factor a wheel unit (as exp), and the highest and lowest the eye goes (radians of pitch).
const ORBIT_PER_PIXEL = 0.01, PAN_PER_PIXEL = 0.002, ZOOM_PER_WHEEL = 0.001, PITCH_LIMIT = 1.5;

const $ = id => document.getElementById(id);
const state = {
    chapter: DEFAULT_CHAPTER, scenes: [], running: null, pending: null, nextId: 1, typing: 0,
    picture: null, dragging: null, coarse: COARSE_START, gutterLines: 0, errorLine: 0, refused: false,
};
// What the browser test reads: every render's kind, times and status, the last full render.
// passes: the path tracers' passes shown ({samplesDone, samplesTotal, secondsLeft, at}); workers: how many draw.
window.whitted = {renders: [], fullShown: 0, lastFull: null, loadedAt: performance.now(), passes: [],
                  workers: Renders.workers};

const pad = n => String(n).padStart(2, "0");
const chapterName = n => `${pad(n)}-${CHAPTERS[n - 1]}`;

// ---- the scene text: the camera and image lines ----------------------------------------------------
function sceneLine(text, directive) {
    return text.split("\n").findIndex(l => l.replace(/#.*/, "").trim().split(/\s+/)[0] === directive);
}

// The values of the camera line's keys eye, target, up and fov (up defaults to 0 1 0).
function readCamera(text) {
    const k = sceneLine(text, "camera");
    if (k < 0)
        return null;
    const words = text.split("\n")[k].replace(/#.*/, "").trim().split(/\s+/);
    const key = (name, n) => {
        const at = words.indexOf(name);
        return at < 0 ? null : words.slice(at + 1, at + 1 + n).map(Number);
    };
    const cam = {eye: key("eye", 3), target: key("target", 3), up: key("up", 3) || [0, 1, 0], fov: key("fov", 1)};
    return cam.eye && cam.target && [...cam.eye, ...cam.target].every(Number.isFinite) ? cam : null;
}

// The text with the camera line's eye and target replaced, every other word kept.
function writeCamera(text, eye, target) {
    const lines = text.split("\n");
    const k = sceneLine(text, "camera");
    const comment = lines[k].includes("#") ? " " + lines[k].slice(lines[k].indexOf("#")) : "";
    const words = lines[k].replace(/#.*/, "").trim().split(/\s+/);
    const num = x => String(Number(x.toFixed(4)));
    for (const [name, v] of [["eye", eye], ["target", target]]) {
        const at = words.indexOf(name);
        words.splice(at + 1, 3, ...v.map(num));
    }
    lines[k] = words.join(" ") + comment;
    return lines.join("\n");
}

function readImageSize(text) {
    const k = sceneLine(text, "image");
    const w = k < 0 ? [] : text.split("\n")[k].replace(/#.*/, "").trim().split(/\s+/);
    return [Number(w[1]) || DEFAULT_SIZE[0], Number(w[2]) || DEFAULT_SIZE[1]];
}

// ---- the command line -------------------------------------------------------------------------------
function scenePath() {
    return `scenes/${$("scene-file").value}`;
}

function pictureSize(text) {
    const size = $("size").value;
    return size ? size.split("x").map(Number) : readImageSize(text);
}

// The arguments of the chapter program for the current controls; coarse: the quick picture.
function commandArgs(text, coarse) {
    const args = [scenePath(), "--stats"];
    const set = s => args.push("--set", s);
    const n = state.chapter;
    if ($("max-depth").value && READS.depth(n))
        set(`max_depth=${$("max-depth").value}`);
    if ($("bounces").value && READS.bounces(n))
        set(`paths.bounces=${$("bounces").value}`);
    if ($("fov").value)
        set(`camera.fov=${$("fov").value}`);
    const samplesKey = PATH_CHAPTERS.includes(n) ? "paths.samples" : n >= 12 ? "antialias.samples" : null;
    if (samplesKey && (coarse || $("samples").value))
        set(`${samplesKey}=${coarse ? 1 : $("samples").value}`);
    const accel = READS.accel(n) ? $("accel").value : "";
    if (accel)
        args.push("--accel", accel);
    // The programs refuse --split with --accel none, and --rung with any structure but the BVH: a
    // structure that is not built has no rule and no rungs, so those controls then pass nothing.
    if (READS.split(n) && $("split").value && accel !== "none")
        args.push("--split", $("split").value);
    if (READS.rung(n) && $("rung").value && (accel === "" || accel === "bvh"))
        args.push("--rung", $("rung").value);
    let [w, h] = pictureSize(text);
    if (coarse)
        [w, h] = [Math.max(1, Math.ceil(w / state.coarse)), Math.max(1, Math.ceil(h / state.coarse))];
    if (coarse || $("size").value)
        args.push("--width", String(w), "--height", String(h));
    if ($("heatmap").checked)
        args.push("--heatmap", "out/heatmap.png");
    return args;
}

function shellWord(w) {
    return /^[\w./=:,-]+$/.test(w) ? w : `'${w.replace(/'/g, "'\\''")}'`;
}

// ---- the renders (renders.js) ----------------------------------------------------------------------
// Stops the picture being drawn, if any.
function stopRender() {
    Renders.stop();
    state.running = null;
    state.pending = null;
    document.body.dataset.state = "idle";
}

function run(job) {
    state.running = job;
    job.started = performance.now();
    document.body.dataset.state = "rendering";
    Renders.render({chapter: state.chapter, scenePath: job.scenePath, text: job.text, args: job.args,
                    coarse: job.coarse, onPass: (picture, progress) => passShown(job, picture, progress),
                    onDone: result => finished(job, result)});
}

// Asks for a picture of the editor's scene: a coarse one while the camera moves, else the full one.
function render(coarse) {
    const text = $("scene").value;
    if (refusedAsTooBig(text))
        return;
    const job = {id: state.nextId++, coarse, text, scenePath: scenePath(), args: commandArgs(text, coarse)};
    if (!state.running) {
        state.pending = null; // an older request still waiting (a picture was being shown) is out of date
        run(job);
    } else if (!state.running.coarse) {
        Renders.stop(); // a full picture is being drawn: stop it
        run(job);
    } else {
        state.pending = job; // a coarse picture is quick: the newest request waits for it
    }
}

// A path tracer's pass (chapters 15 and 17): its picture, the samples so far and the time left.
async function passShown(job, picture, progress) {
    if (state.running !== job)
        return;
    window.whitted.passes.push({...progress, at: performance.now()});
    const bitmap = await createImageBitmap(new Blob([picture], {type: "image/png"}));
    if (state.running !== job)
        return;
    const canvas = $("picture");
    [canvas.width, canvas.height] = [bitmap.width, bitmap.height];
    canvas.getContext("2d").drawImage(bitmap, 0, 0);
    $("status").textContent = `${progress.samplesDone} of ${progress.samplesTotal} paths a pixel, ` +
                              `about ${Math.ceil(progress.secondsLeft)} s left`;
}

async function finished(job, result) {
    if (state.running !== job)
        return;
    state.running = null;
    const ms = performance.now() - job.started;
    window.whitted.renders.push({coarse: job.coarse, ms, programMs: result.ms, status: result.status,
                                 at: performance.now(), args: job.args});
    if (job.coarse && result.status === 0)
        state.coarse = Math.min(COARSE_MAX, Math.max(COARSE_MIN, state.coarse * Math.sqrt(result.ms / COARSE_MS)));
    await show(job, result, ms);
    if (state.running)
        return; // a request came while the picture was being shown and is being drawn: it is the newest
    if (state.pending) {
        const next = state.pending;
        state.pending = null;
        run(next);
    } else if (!state.running) {
        document.body.dataset.state = "idle";
    }
}

async function show(job, result, ms) {
    const errors = result.status !== 0;
    if (!state.refused) {
        $("errors").textContent = errors ? result.stderr.trim() : "";
        markStale(errors || !result.picture, errors ? errorLine(result.stderr, job.scenePath) : 0);
    }
    $("warnings").textContent = errors ? "" : result.stderr.trim();
    if (errors || !result.picture) {
        $("status").textContent = `the program stopped with status ${result.status}`;
        if (!job.coarse)
            window.whitted.lastFull = {job, result};
        return;
    }
    const png = job.args.includes("--heatmap") ? result.heatmap : result.picture;
    const bitmap = await createImageBitmap(new Blob([png], {type: "image/png"}));
    const canvas = $("picture");
    const ctx = canvas.getContext("2d");
    if (job.coarse) { // stretched over the last full picture's canvas
        ctx.imageSmoothingEnabled = false;
        ctx.drawImage(bitmap, 0, 0, canvas.width, canvas.height);
        $("status").textContent = `coarse ${bitmap.width} x ${bitmap.height}: ${ms.toFixed(0)} ms`;
        return;
    }
    [canvas.width, canvas.height] = [bitmap.width, bitmap.height];
    ctx.drawImage(bitmap, 0, 0);
    $("status").textContent = `${bitmap.width} x ${bitmap.height} in ${(ms / 1000).toFixed(2)} s ` +
                              `(the program: ${(result.ms / 1000).toFixed(2)} s)`;
    $("counters").textContent = pageCounters(result.stdout);
    $("command").textContent = `./build/chapter-${pad(state.chapter)} ` + job.args.map(shellWord).join(" ") +
                               "\n(with the scene as the editor has it)";
    state.picture = result.picture;
    offerDownload($("download-picture"), result.picture, `chapter-${chapterName(state.chapter)}.png`);
    const heatmap = job.args.includes("--heatmap") && result.heatmap;
    $("download-heatmap").classList.toggle("hidden", !heatmap);
    if (heatmap)
        offerDownload($("download-heatmap"), result.heatmap, `chapter-${chapterName(state.chapter)}-heatmap.png`);
    window.whitted.lastFull = {job, result};
    window.whitted.fullShown++;
}

// ---- the camera under the mouse -----------------------------------------------------------------
const sub = (a, b) => a.map((x, i) => x - b[i]);
const add = (a, b) => a.map((x, i) => x + b[i]);
const scale = (a, s) => a.map(x => x * s);
const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const unit = a => scale(a, 1 / Math.sqrt(dot(a, a)));

// Moves the camera of the editor's scene: orbit around the target (dx, dy in pixels), pan both eye and
// target, or zoom (factor on the distance). Returns false when the scene has no readable camera line.
function moveCamera(kind, dx, dy, factor) {
    const text = $("scene").value;
    const cam = readCamera(text);
    if (!cam)
        return false;
    let {eye, target} = cam;
    const offset = sub(eye, target);
    const r = Math.sqrt(dot(offset, offset));
    if (kind === "orbit") {
        const yaw = Math.atan2(offset[0], offset[2]) - dx * ORBIT_PER_PIXEL;
        const pitch = Math.max(-PITCH_LIMIT, Math.min(PITCH_LIMIT,
                               Math.asin(Math.max(-1, Math.min(1, offset[1] / r))) + dy * ORBIT_PER_PIXEL));
        eye = add(target, [r * Math.cos(pitch) * Math.sin(yaw), r * Math.sin(pitch), r * Math.cos(pitch) * Math.cos(yaw)]);
    } else if (kind === "pan") {
        const forward = unit(scale(offset, -1));
        const right = unit(cross(forward, cam.up));
        const up = cross(right, forward);
        const move = add(scale(right, -dx * r * PAN_PER_PIXEL), scale(up, dy * r * PAN_PER_PIXEL));
        eye = add(eye, move);
        target = add(target, move);
    } else {
        eye = add(target, scale(offset, factor));
    }
    $("scene").value = writeCamera(text, eye, target);
    updateSceneLink();
    updateGutter();
    return true;
}

function setUpMouse() {
    const canvas = $("picture");
    canvas.addEventListener("contextmenu", e => e.preventDefault());
    canvas.addEventListener("pointerdown", e => {
        if (e.pointerType === "touch")
            return; // setUpTouch's
        state.dragging = {x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2};
        canvas.setPointerCapture(e.pointerId);
        canvas.classList.add("dragging");
    });
    canvas.addEventListener("pointermove", e => {
        const d = state.dragging;
        if (!d)
            return;
        const [dx, dy] = [e.clientX - d.x, e.clientY - d.y];
        [d.x, d.y] = [e.clientX, e.clientY];
        if ((dx || dy) && moveCamera(d.pan ? "pan" : "orbit", dx, dy))
            render(true);
    });
    const release = () => {
        if (!state.dragging)
            return;
        state.dragging = null;
        canvas.classList.remove("dragging");
        render(false);
    };
    canvas.addEventListener("pointerup", release);
    canvas.addEventListener("pointercancel", release);
    let wheelTimer = 0;
    canvas.addEventListener("wheel", e => {
        e.preventDefault();
        if (!moveCamera("zoom", 0, 0, Math.exp(e.deltaY * ZOOM_PER_WHEEL)))
            return;
        render(true);
        clearTimeout(wheelTimer);
        wheelTimer = setTimeout(() => render(false), TYPING_PAUSE);
    }, {passive: false});
}

// The camera under the fingers, with the mouse's moves: one finger orbits, two fingers pinch to zoom
// (the distance to the target shrinks as they spread) and drag together to pan.
function setUpTouch() {
    const canvas = $("picture");
    let last = null, moved = false; // the fingers' centre, spread and count at the last event
    const measure = touches => {
        const t = [...touches].slice(0, 2);
        const x = t.reduce((s, p) => s + p.clientX, 0) / t.length, y = t.reduce((s, p) => s + p.clientY, 0) / t.length;
        const spread = t.length < 2 ? 0 : Math.hypot(t[0].clientX - t[1].clientX, t[0].clientY - t[1].clientY);
        return {x, y, spread, count: t.length};
    };
    canvas.addEventListener("touchstart", e => {
        e.preventDefault();
        last = measure(e.touches);
    }, {passive: false});
    canvas.addEventListener("touchmove", e => {
        e.preventDefault();
        const now = measure(e.touches);
        if (last && now.count === last.count) {
            const [dx, dy] = [now.x - last.x, now.y - last.y];
            let changed = false;
            if (now.count === 1) {
                changed = (dx || dy) && moveCamera("orbit", dx, dy);
            } else {
                changed = (dx || dy) && moveCamera("pan", dx, dy);
                if (now.spread > 0 && last.spread > 0 && now.spread !== last.spread)
                    changed = moveCamera("zoom", 0, 0, last.spread / now.spread) || changed;
            }
            if (changed) {
                moved = true;
                render(true);
            }
        }
        last = now;
    }, {passive: false});
    const lift = e => {
        e.preventDefault();
        last = e.touches.length ? measure(e.touches) : null;
        if (!last && moved) {
            moved = false;
            render(false);
        }
    };
    canvas.addEventListener("touchend", lift);
    canvas.addEventListener("touchcancel", lift);
}

// ---- what the page says: the chapter's idea and links, the counters, the downloads ------------------
function showAbout() {
    const n = state.chapter, name = chapterName(n);
    $("idea").textContent = `Chapter ${n}, ${CHAPTERS[n - 1]}: ${IDEAS[n - 1]}`;
    const link = (id, path) => {
        $(id).href = REPO_BASE + path;
        $(id).textContent = path;
    };
    link("walkthrough-link", `docs/${name}.md`);
    link("source-link", `chapters/${name}/main.c`);
    for (const id of ["format-link", "format-link-2"])
        $(id).href = REPO_BASE + "docs/scene-format.md";
    $("format-link").textContent = "docs/scene-format.md";
    $("format-link-2").textContent = "docs/scene-format.md";
}

// What the heat-map's colours count on this chapter, and the bar under it.
function showHeatNote() {
    const on = $("heatmap").checked;
    $("heat-note").classList.toggle("hidden", !on);
    $("heat-note").textContent = CAMERA_RAY_HEATMAP.includes(state.chapter)
        ? "Heat-map: the camera rays each pixel took, on a logarithmic scale from 0 (black) through blue, red " +
          "and yellow to 100 or more (white); the bar under the picture marks 0, 1, 10 and 100."
        : "Heat-map: the work each pixel cost, its rays' node visits plus box and shape tests, on a logarithmic " +
          "scale from 0 (black) through blue, red and yellow to 8192 or more (white); the bar under the picture " +
          "marks 0, 1, 10, 100, 1000 and 8192.";
}

// The program's counters as the page shows them: its picture is not a file here, so "wrote out/…png
// (W x H)" reads "drew W x H".
function pageCounters(stdout) {
    return stdout.trim().replace(/: wrote \S+ \(([^)]*)\)/g, ": drew $1");
}

function offerDownload(link, bytes, name) {
    URL.revokeObjectURL(link.href);
    link.href = URL.createObjectURL(new Blob([bytes], {type: "image/png"}));
    link.download = name;
    link.textContent = name;
}

// ---- the editor: line numbers, the error's line, the stale picture --------------------------------
function updateGutter() {
    const lines = $("scene").value.split("\n").length;
    if (lines !== state.gutterLines) { // one number a line, and one more for the scroll bar's height
        $("gutter").textContent = Array.from({length: lines + 1}, (_, k) => (k < lines ? k + 1 : "")).join("\n");
        state.gutterLines = lines;
    }
    $("gutter").scrollTop = $("scene").scrollTop;
    placeErrorLine();
}

function placeErrorLine() {
    const line = state.errorLine, mark = $("error-line");
    mark.classList.toggle("hidden", !line);
    if (line)
        mark.style.top = `${EDITOR_PAD + (line - 1) * LINE_HEIGHT - $("scene").scrollTop}px`;
}

// The scene's line a message names ("scenes/NN-name.scene:LINE: what"), 0 when it names none.
function errorLine(stderr, path) {
    const named = stderr.split("\n").find(l => l.startsWith(path + ":"));
    return named ? Number(named.slice(path.length + 1).split(":")[0]) || 0 : 0;
}

// Marks the picture and counters as stale (from the last scene that worked) and the editor's line
// `line` (0: none) while an error stands.
function markStale(stale, line) {
    $("view").classList.toggle("stale", stale);
    $("stale-note").classList.toggle("hidden", !stale || !window.whitted.fullShown);
    state.errorLine = stale ? line : 0;
    placeErrorLine();
}

// Refuses a picture over MAX_PIXELS before any render, saying so; returns true when refused.
function refusedAsTooBig(text) {
    const [w, h] = pictureSize(text);
    state.refused = w * h > MAX_PIXELS;
    if (!state.refused)
        return false;
    const mega = x => (x / 1e6).toFixed(1);
    $("errors").textContent = `${w} x ${h} is ${mega(w * h)} megapixels: the page draws at most ${mega(MAX_PIXELS)} megapixels ` +
        `(4096 x 4096), so that the tab keeps within its memory. The native program draws it:\n` +
        `./build/chapter-${pad(state.chapter)} ${scenePath()} --width ${w} --height ${h}`;
    $("status").textContent = "not drawn: the picture is too big for the page";
    markStale(true, $("size").value ? 0 : sceneLine(text, "image") + 1);
    return true;
}

// ---- the chapter and its scene --------------------------------------------------------------------
function updateSceneLink() {
    const link = $("download-scene");
    URL.revokeObjectURL(link.href);
    link.href = URL.createObjectURL(new Blob([$("scene").value], {type: "text/plain"}));
    link.download = $("scene-file").value;
    link.textContent = link.download;
}

// Shows the controls the chapter's program reads (READS; the others every chapter reads).
function showControls() {
    const n = state.chapter;
    for (const label of document.querySelectorAll("#controls label")) {
        const reads = READS[label.dataset.option];
        label.classList.toggle("hidden", reads !== undefined && !reads(n));
    }
    showAbout();
    showHeatNote();
    const kinds = n === 9 ? ["kdtree", "none"] : ["bvh", "kdtree", "none"];
    $("accel").innerHTML = kinds.map((k, i) => `<option value="${i ? k : ""}">${k}${i ? "" : " (default)"}</option>`).join("");
    $("samples").placeholder = PATH_CHAPTERS.includes(n) ? "paths'" : "scene's";
}

async function loadScene(name) {
    $("scene-file").value = name;
    const response = await fetch(`scenes/${name}`);
    $("scene").value = await response.text();
    $("scene").scrollTop = 0;
    updateSceneLink();
    updateGutter();
    render(true); // a quick first view, then the full picture
    render(false);
}

async function chooseChapter(n, sceneName) {
    state.chapter = n;
    $("chapter").value = String(n);
    const own = state.scenes.filter(s => s.startsWith(pad(n) + "-"));
    $("scene-file").innerHTML = own.map(s => `<option>${s}</option>`).join("");
    showControls();
    stopRender();
    const name = own.includes(sceneName) ? sceneName : own.includes(`${chapterName(n)}.scene`) ? `${chapterName(n)}.scene` : own[0];
    const url = new URL(location.href);
    url.searchParams.set("chapter", String(n));
    url.searchParams.set("scene", name);
    history.replaceState(null, "", url);
    await loadScene(name);
}

async function start() {
    $("chapter").innerHTML = CHAPTERS.map((t, i) => `<option value="${i + 1}">${i + 1} ${t}</option>`).join("");
    $("rung").innerHTML = `<option value="">6 float (default)</option>` +
                          RUNGS.map((r, i) => `<option value="${i + 1}">${i + 1} ${r}</option>`).join("");
    state.scenes = await (await fetch("scenes/index.json")).json();
    setUpMouse();
    setUpTouch();
    $("scene").addEventListener("scroll", updateGutter);
    $("heatmap").addEventListener("change", showHeatNote);
    $("chapter").addEventListener("change", () => chooseChapter(Number($("chapter").value)));
    $("scene-file").addEventListener("change", () => loadScene($("scene-file").value));
    $("scene").addEventListener("input", () => {
        updateSceneLink();
        updateGutter();
        clearTimeout(state.typing);
        state.typing = setTimeout(() => render(false), TYPING_PAUSE);
    });
    for (const id of ["max-depth", "bounces", "fov", "samples", "accel", "split", "rung", "size", "heatmap"])
        $(id).addEventListener("change", () => render(false));
    const params = new URL(location.href).searchParams;
    const n = Number(params.get("chapter"));
    await chooseChapter(n >= 1 && n <= CHAPTERS.length ? n : DEFAULT_CHAPTER, params.get("scene"));
}

start();
