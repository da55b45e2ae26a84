// worker.js: runs one chapter program, compiled to WebAssembly (make web), off the page's main thread.
//
// renders.js starts the workers (new Worker("worker.js?chapter=08"), several at once, one for each band
// of rows) and posts each a render at a time: {id, scenePath, text, args}. The worker writes the scene
// text to scenePath and every mesh and texture the scene names (fetched once and kept) into an
// instance's file system, runs the program's main with args, as a shell would run build/chapter-NN, and
// posts back {id, status, stdout, stderr, picture, heatmap, ms}: the exit status, what the program
// printed, the PNG files it wrote (out/chapter-NN.png and, with --heatmap, out/heatmap.png) and the time
// the program took.
//
// The held instance. After its picture the program does not end: common/cli.c's held loop calls
// Module.nextJob, which posts the picture and waits (Asyncify sets the program's stack aside) for the
// next render. When that render's *world* is the same (the scene text without its camera and image
// lines, the command line without --width, --height, --tile and the samples), the worker writes the new
// scene and command line and wakes the program, which reads only the new camera, size, samples and tile
// and renders again: the meshes are not read again and the structure is not built again. A render of
// another world drops the instance and starts a fresh one, like a new process.
"use strict";

const chapter = new URL(self.location.href).searchParams.get("chapter");
importScripts(`chapter-${chapter}.js`); // defines createChapter
const compiled = WebAssembly.compileStreaming(fetch(`chapter-${chapter}.wasm`));
const files = new Map(); // path under scenes/ -> Promise of its bytes (null when it cannot be fetched)
const HELD_ARGS = "/held/args"; // where common/cli.c's held loop reads the next command line
// The command line's options a held instance takes from render to render, with how many words follow.
const VIEW_OPTIONS = {"--width": 1, "--height": 1, "--tile": 4};
const VIEW_SETS = /^(paths\.samples|antialias\.samples|camera\.fov)=/;

// The files a scene names, relative to scenes/: a mesh line's file, an object line's file (chapter 16)
// and an image_map's file (the same words the Makefile's chapter-N rule looks for).
function namedFiles(text) {
    const names = [];
    for (const line of text.split("\n")) {
        const words = line.replace(/#.*/, "").trim().split(/\s+/);
        if (words[0] === "mesh" && words.length > 1)
            names.push(words[1]);
        if (words[0] === "object" && words.length > 2)
            names.push(words[2]);
        if (words[0] === "pigment")
            for (let k = 2; k + 1 < words.length; k++)
                if (words[k] === "file")
                    names.push(words[k + 1]);
    }
    return names;
}

// What the held instance's world is made of: the scene without its image line and with only the
// camera line's shutter (chapter 16 builds its moving instances for it), and the command line without
// the options of the view. Two renders with the same world differ only in what cli.c's held loop takes.
function worldOf(job) {
    const lines = job.text.split("\n").map(line => {
        const words = line.replace(/#.*/, "").trim().split(/\s+/);
        if (words[0] === "image")
            return "";
        if (words[0] === "camera")
            return "camera shutter " + (words.includes("shutter") ? words[words.indexOf("shutter") + 1] : "");
        return line;
    });
    const args = [];
    for (let k = 0; k < job.args.length; k++) {
        const a = job.args[k];
        if (a in VIEW_OPTIONS)
            k += VIEW_OPTIONS[a];
        else if (a === "--set" && VIEW_SETS.test(job.args[k + 1] || ""))
            k += 1;
        else
            args.push(a);
    }
    return JSON.stringify([job.scenePath, args, lines]);
}

function fetchFile(name) {
    if (!files.has(name))
        files.set(name, fetch(`scenes/${name}`).then(r => (r.ok ? r.arrayBuffer() : null)).catch(() => null));
    return files.get(name);
}

function writeFile(FS, path, bytes) {
    const slash = path.lastIndexOf("/");
    if (slash > 0)
        FS.mkdirTree(path.slice(0, slash));
    FS.writeFile(path, bytes);
}

function readFile(FS, path) {
    try {
        return FS.readFile(path);
    } catch (e) {
        return null;
    }
}

function removeFile(FS, path) {
    try {
        FS.unlink(path);
    } catch (e) { /* not there */ }
}

// The instance held between renders (null when none waits): its world, its program, the render it is on,
// what that render printed, and how to wake the program (wake) and hand back the result (done).
let held = null;

function outputsOf(session, status) {
    const decode = bytes => new TextDecoder().decode(new Uint8Array(bytes));
    const FS = session.program.FS;
    return {
        id: session.job.id, status, ms: performance.now() - session.started,
        stdout: decode(session.stdout), stderr: decode(session.stderr),
        picture: readFile(FS, `out/chapter-${chapter}.png`), heatmap: readFile(FS, "out/heatmap.png"),
    };
}

// Starts the session's job on its program: the scene written, the old pictures removed.
function begin(session, job) {
    const FS = session.program.FS;
    session.job = job;
    session.stdout = [];
    session.stderr = [];
    removeFile(FS, `out/chapter-${chapter}.png`);
    removeFile(FS, "out/heatmap.png");
    writeFile(FS, job.scenePath, job.text);
}

// A render in a fresh instance; it is held afterwards when the program reaches its held loop.
async function renderFresh(job, world) {
    const names = namedFiles(job.text);
    const contents = await Promise.all(names.map(fetchFile));
    const module = await compiled;
    const session = {world, program: null, job, stdout: [], stderr: [], started: 0, wake: null, done: null};
    const program = await createChapter({
        instantiateWasm(imports, done) {
            WebAssembly.instantiate(module, imports).then(instance => done(instance, module));
            return {};
        },
        thisProgram: `./build/chapter-${chapter}`,
        stdout: c => session.stdout.push(c),
        stderr: c => session.stderr.push(c),
        holdRenders: !job.args.includes("--pov"),
        // Called by the held loop with the status of the render it finished; resolves when the next one
        // is written.
        nextJob(status) {
            const done = session.done;
            session.done = null;
            held = session;
            done(outputsOf(session, status));
            return new Promise(resolve => { session.wake = resolve; });
        },
        onAbort(what) {
            if (held === session)
                held = null;
            if (session.done)
                session.done({id: session.job.id, status: -1, stdout: "", stderr: `the program stopped: ${what}`});
            session.done = null;
        },
    });
    session.program = program;
    const FS = program.FS;
    names.forEach((name, k) => {
        // A file that cannot be fetched is left out: the program reports it as natively.
        if (contents[k] !== null)
            writeFile(FS, `scenes/${name}`, new Uint8Array(contents[k]));
    });
    begin(session, job);
    return new Promise(done => {
        session.done = done;
        session.started = performance.now();
        const status = program.callMain(job.args);
        if (held !== session && session.done) { // the program ended without reaching its held loop
            session.done = null;
            done(outputsOf(session, status));
        }
    });
}

// A render of the held instance's world: the new scene and command line written, the program woken.
function renderHeld(job) {
    const session = held;
    held = null;
    begin(session, job);
    const words = [`./build/chapter-${chapter}`, ...job.args].map(w => w + "\0").join("");
    writeFile(session.program.FS, HELD_ARGS, new TextEncoder().encode(words));
    return new Promise(done => {
        session.done = done;
        session.started = performance.now();
        const wake = session.wake;
        session.wake = null;
        wake();
    });
}

function render(job) {
    const world = worldOf(job);
    if (held !== null && held.world === world)
        return renderHeld(job);
    held = null; // another world: the old instance is dropped
    return renderFresh(job, world);
}

// The bands of a picture joined into the whole picture's PNG by web_join.c, in an instance of its own
// (made once; its main never runs): {id, join: [PNG bytes of each band, top first]} -> {id, status,
// picture, stderr}.
let joiner = null, joinErrors = [];
async function join(message) {
    const stderr = joinErrors = [];
    if (joiner === null) {
        const module = await compiled;
        joiner = await createChapter({
            instantiateWasm(imports, done) {
                WebAssembly.instantiate(module, imports).then(instance => done(instance, module));
                return {};
            },
            stderr: c => joinErrors.push(c),
        });
    }
    message.join.forEach((png, k) => writeFile(joiner.FS, `/join/band-${k}.png`, png));
    const status = joiner._web_join_bands(message.join.length);
    return {id: message.id, status, picture: status === 0 ? readFile(joiner.FS, "/join/whole.png") : null,
            stderr: new TextDecoder().decode(new Uint8Array(stderr))};
}

let queue = Promise.resolve(); // one render at a time, in the order they came
self.onmessage = e => {
    const job = e.data;
    if (job.join) {
        join(job).then(result => self.postMessage(result),
                       error => self.postMessage({id: job.id, status: -1, stderr: String(error)}));
        return;
    }
    queue = queue.then(() => render(job)).then(result => self.postMessage(result),
                                               error => self.postMessage({id: job.id, status: -1, stdout: "", stderr: String(error)}));
};
