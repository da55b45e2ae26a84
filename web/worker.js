// worker.js: runs one chapter program, compiled to WebAssembly (make web), off the page's main thread.
//
// The page starts one worker per chapter: new Worker("worker.js?chapter=08"). Each message it posts is
// a render: {id, scenePath, text, args}. The worker writes the scene text to scenePath and every mesh
// and texture the scene names (fetched once and kept) into a fresh instance's file system, runs the
// program's main with args, as a shell would run build/chapter-NN, and posts back
// {id, status, stdout, stderr, picture, heatmap, ms}: the exit status, what the program printed, the
// PNG files it wrote (out/chapter-NN.png and, with --heatmap, out/heatmap.png) and the wall time.
// A fresh instance for every render keeps each run independent, like a process.
"use strict";

const chapter = new URL(self.location.href).searchParams.get("chapter");
importScripts(`chapter-${chapter}.js`); // defines createChapter
const compiled = WebAssembly.compileStreaming(fetch(`chapter-${chapter}.wasm`));
const files = new Map(); // path under scenes/ -> Promise of its bytes (null when it cannot be fetched)

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

async function render(job) {
    const names = namedFiles(job.text);
    const contents = await Promise.all(names.map(fetchFile));
    const module = await compiled;
    const stdout = [], stderr = [];
    const program = await createChapter({
        instantiateWasm(imports, done) {
            WebAssembly.instantiate(module, imports).then(instance => done(instance, module));
            return {};
        },
        thisProgram: `./build/chapter-${chapter}`,
        stdout: c => stdout.push(c),
        stderr: c => stderr.push(c),
    });
    const FS = program.FS;
    names.forEach((name, k) => {
        // A file that cannot be fetched is left out: the program reports it as natively.
        if (contents[k] !== null)
            writeFile(FS, `scenes/${name}`, new Uint8Array(contents[k]));
    });
    writeFile(FS, job.scenePath, job.text);
    const started = performance.now();
    const status = program.callMain(job.args);
    const ms = performance.now() - started;
    const decode = bytes => new TextDecoder().decode(new Uint8Array(bytes));
    return {
        id: job.id, status, ms, stdout: decode(stdout), stderr: decode(stderr),
        picture: readFile(FS, `out/chapter-${chapter}.png`), heatmap: readFile(FS, "out/heatmap.png"),
    };
}

self.onmessage = e => {
    render(e.data).then(result => self.postMessage(result),
                        error => self.postMessage({id: e.data.id, status: -1, stdout: "", stderr: String(error)}));
};
