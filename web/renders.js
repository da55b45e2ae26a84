// renders.js: schedules the page's renders over several workers (worker.js), the only code that starts
// them. page.js asks for a picture with
//     Renders.render({chapter, scenePath, text, args, coarse, samples, onPass(picture, progress), onDone(result)})
// and gets result = {status, stdout, stderr, picture (PNG bytes), heatmap, ms} in onDone, as one
// program run would give; Renders.stop() abandons the render being drawn; Renders.workers is how many
// workers draw.
//
// Every core: the picture is cut into bands of whole rows, each drawn by one worker with the program's
// --tile option (a tile holds the very pixels the whole picture has there), and the bands are joined
// into the whole picture's PNG (web_join.c, with the programs' own PNG encoder): the same bytes for one
// worker or eight. A worker keeps its chapter instance while the world stays the same (worker.js), so a
// new camera, size or sample count only renders.
//
// Progressive paths (chapters 15 and 17): the picture is drawn in passes of 1, 2, 4, ... paths a pixel
// up to the samples asked for, each pass shown as it comes (onPass) with the samples done and the time
// left. Each worker keeps every pixel's running sums between passes (path_pixel_resume), so a pass only
// traces its new paths, and the last pass is the native program's picture at that count, byte for byte.
"use strict";

// The bands' counters as the whole picture's (what the native program prints for it): the first line says
// the whole picture and the slowest band's time; each count is the bands' sum, each per-pixel figure that
// sum over the picture's pixels ("most camera rays" the largest); a line that differs between bands and
// cannot be summed (chapter 15's noise, a rate) is the first band's, and says so.
function joinCounters(outputs) {
    const tile = /\(the \d+ x \d+ tile at column \d+, row \d+ of the (\d+) x (\d+) picture\)/;
    const size = outputs.length > 1 && outputs[0].split("\n")[0].match(tile);
    if (!size)
        return outputs.join("");
    const pixels = Number(size[1]) * Number(size[2]);
    // Each band read as: its first line, its counts and per-pixel figures (label -> value, in order), the rest.
    const bands = outputs.map(text => {
        const band = {first: "", counts: new Map(), pixel: new Map(), pixelHeading: null, rest: []};
        let section = null;
        text.replace(/\n$/, "").split("\n").forEach((line, k) => {
            if (k === 0)
                return void (band.first = line);
            if (!line.startsWith("  ")) {
                section = line === "counters:" ? "counts" : line.startsWith("per pixel") ? "pixel" : null;
                if (section === "pixel")
                    band.pixelHeading = line;
                if (section)
                    return;
            }
            const m = section ? line.match(/^  (.*?)\s+([0-9.]+)$/) : null;
            if (m)
                band[section].set(m[1], Number(m[2]));
            else
                band.rest.push(line);
        });
        return band;
    });
    // Every label in the order the program prints them (a band prints no line for a count of 0).
    const labels = key => {
        const order = [];
        for (const band of bands) {
            let at = 0;
            for (const label of band[key].keys()) {
                const k = order.indexOf(label);
                if (k < 0)
                    order.splice(at++, 0, label);
                else
                    at = k + 1;
            }
        }
        return order;
    };
    const sum = (key, label) => bands.reduce((total, b) => total + (b[key].get(label) || 0), 0);
    const line = (label, value) => `  ${label.padEnd(16)} ${value.padStart(15)}`; // common/stats.c's "  %-16s %15"
    const seconds = Math.max(...bands.map(b => Number((b.first.match(/ in ([0-9.]+) s$/) || [0, 0])[1])));
    const out = [bands[0].first.replace(tile, `(${size[1]} x ${size[2]})`).replace(/ in [0-9.]+ s$/, ` in ${seconds.toFixed(3)} s`)];
    if (bands.some(b => b.counts.size)) {
        out.push("counters:");
        for (const label of labels("counts"))
            out.push(line(label, String(sum("counts", label))));
    }
    const heading = bands.map(b => b.pixelHeading).find(h => h);
    if (heading) {
        out.push(heading);
        const ofCount = {"camera rays": "primary rays", "rays": "rays (all)"};
        for (const label of labels("pixel")) {
            if (label.startsWith("most "))
                out.push(line(label, String(Math.max(...bands.map(b => b.pixel.get(label) || 0)))));
            else
                out.push(line(label, (sum("counts", ofCount[label] || label) / pixels).toFixed(2)));
        }
    }
    bands[0].rest.forEach((text, k) =>
        out.push(bands.every(b => b.rest[k] === text) || text.startsWith("  ") ? text : `${text} (the first band's)`));
    return out.join("\n") + "\n";
}

const Renders = (() => {
    const WORKERS_MAX = 8;   // the most workers drawing at once
    const BAND_QUANTUM = 32; // band edges on this grid of rows: chapter 12's blocks (ANTIALIAS_BLOCK) stay whole
    const BANDS_PER_WORKER = 2; // bands of a full picture a worker draws, so that a stop waits for little
    const PATH_CHAPTERS = [15, 17];
    const PATH_DEFAULT_SAMPLES = 16; // path_settings_default's samples, for a scene without a paths line
    const asked = Number(new URL(location.href).searchParams.get("workers")); // ?workers=N for tests
    const count = asked >= 1 ? Math.min(WORKERS_MAX, Math.floor(asked))
                             : Math.max(1, Math.min(WORKERS_MAX, navigator.hardwareConcurrency || 1));

    let pool = {chapter: null, workers: []}; // workers: {worker, busy (a band), joiner (a pending join)}
    let current = null;  // the render being drawn
    let pending = null;  // the newest request waiting for a coarse render to finish
    let nextId = 1;

    function startPool(chapter) {
        for (const w of pool.workers)
            w.worker.terminate();
        pool = {chapter, workers: []};
        for (let k = 0; k < count; k++) {
            const w = {worker: new Worker(`worker.js?chapter=${String(chapter).padStart(2, "0")}`), busy: null,
                       replies: new Map()};
            w.worker.onmessage = e => received(w, e.data);
            pool.workers.push(w);
        }
    }

    function received(w, data) {
        const reply = w.replies.get(data.id);
        w.replies.delete(data.id);
        if (w.busy && w.busy.id === data.id)
            w.busy = null;
        if (reply)
            reply(data);
        dispatch();
    }

    // Posts a message to worker w; resolves with its reply.
    function ask(w, message) {
        message.id = nextId++;
        return new Promise(resolve => {
            w.replies.set(message.id, resolve);
            w.worker.postMessage(message);
        });
    }

    // The bands of a picture `height` rows tall for `wanted` bands: [top, rows] on the grid of BAND_QUANTUM.
    function bands(height, wanted) {
        const quanta = Math.ceil(height / BAND_QUANTUM);
        const n = Math.max(1, Math.min(wanted, quanta));
        const out = [];
        for (let k = 0; k < n; k++) {
            const top = Math.floor(k * quanta / n) * BAND_QUANTUM;
            const bottom = Math.min(height, Math.floor((k + 1) * quanta / n) * BAND_QUANTUM);
            out.push([top, bottom - top]);
        }
        return out;
    }

    // The picture's size for the command line: --width/--height if given, else the scene's image line.
    function sizeOf(text, args) {
        const option = name => (args.includes(name) ? Number(args[args.indexOf(name) + 1]) : 0);
        const line = text.split("\n").map(l => l.replace(/#.*/, "").trim().split(/\s+/)).find(w => w[0] === "image");
        return [option("--width") || (line ? Number(line[1]) : 0), option("--height") || (line ? Number(line[2]) : 0)];
    }

    // The jobs of one pass: the whole picture on one worker, or its bands, each with --tile.
    function passJobs(request, args) {
        const [width, height] = sizeOf(request.text, args);
        const oneWorker = count === 1 || args.includes("--heatmap") || !(width > 0 && height > 0);
        if (oneWorker) // a heat-map's colour bar belongs to the whole picture; a bad size is the program's to report
            return [{args, band: 0}];
        const cut = bands(height, request.coarse ? count : count * BANDS_PER_WORKER);
        return cut.map(([top, rows], k) => ({args: [...args, "--tile", "0", String(top), String(width), String(rows)], band: k}));
    }

    // Sends the queued jobs of the current render to idle workers: band k to worker k mod count, so that a
    // worker draws the same rows pass after pass (its pixels' sums go on).
    function dispatch() {
        if (!current)
            return;
        for (const job of current.queue) {
            if (job.sent)
                continue;
            const w = pool.workers[job.band % pool.workers.length];
            if (w.busy)
                continue;
            job.sent = true;
            const message = {scenePath: current.request.scenePath, text: current.request.text, args: job.args};
            const render = current;
            const promise = ask(w, message);
            w.busy = message;
            promise.then(result => bandDone(render, job, result));
        }
    }

    function bandDone(render, job, result) {
        if (render !== current)
            return; // a stopped render's band
        job.result = result;
        if (render.queue.every(j => j.result))
            passDone(render);
    }

    // The bands of a pass joined: the first failing band's result as the program's, else the whole PNG.
    async function passDone(render) {
        const results = render.queue.map(j => j.result);
        const failed = results.find(r => r.status !== 0 || !r.picture);
        let picture = results[0].picture;
        if (!failed && results.length > 1) {
            const joined = await ask(pool.workers[0], {join: results.map(r => r.picture)});
            if (render !== current)
                return;
            if (joined.status !== 0) {
                finish(render, {...results[0], status: -1, stderr: joined.stderr, picture: null});
                return;
            }
            picture = joined.picture;
        }
        const ms = performance.now() - render.started;
        const result = failed ? {...failed, ms} : {
            status: 0, ms, picture, heatmap: results[0].heatmap,
            stdout: joinCounters(results.map(r => r.stdout)),
            stderr: results.map(r => r.stderr).filter((s, k, all) => all.indexOf(s) === k).join(""),
        };
        if (failed || render.passes.length === 0) {
            finish(render, result);
            return;
        }
        // Each pass traces only its new paths: the time left is the paths left at this pass's rate.
        const done = render.passSamples, total = render.request.samples;
        const msPerSample = (performance.now() - render.passStarted) / Math.max(1, done - render.lastSamples);
        const progress = {samplesDone: done, samplesTotal: total, secondsLeft: (total - done) * msPerSample / 1000};
        if (render.request.onPass)
            render.request.onPass(picture, progress, result);
        startPass(render);
    }

    function finish(render, result) {
        current = null;
        render.request.onDone && render.request.onDone(result);
        if (pending) {
            const next = pending;
            pending = null;
            begin(next);
        }
    }

    // The arguments of a pass of `samples` paths a pixel: the request's with its paths.samples replaced.
    function withSamples(args, samples) {
        const out = args.filter((a, k) => !/^paths\.samples=/.test(a) && !(a === "--set" && /^paths\.samples=/.test(args[k + 1] || "")));
        return [...out, "--set", `paths.samples=${samples}`];
    }

    // The paths a pixel the request asks for: request.samples, else the command line's paths.samples,
    // else the scene's paths line's samples, else the program's default.
    function pathSamples(request) {
        if (request.samples > 0)
            return request.samples;
        const set = request.args.find(a => /^paths\.samples=/.test(a));
        if (set)
            return Number(set.split("=")[1]);
        const words = request.text.split("\n").map(l => l.replace(/#.*/, "").trim().split(/\s+/)).find(w => w[0] === "paths");
        return words && words.includes("samples") ? Number(words[words.indexOf("samples") + 1]) : PATH_DEFAULT_SAMPLES;
    }

    function startPass(render) {
        const samples = render.passes.shift();
        render.lastSamples = render.passSamples || 0;
        render.passSamples = samples;
        render.passStarted = performance.now();
        const args = samples === undefined ? render.request.args : withSamples(render.request.args, samples);
        render.queue = passJobs(render.request, args);
        dispatch();
    }

    function begin(request) {
        if (pool.chapter !== request.chapter)
            startPool(request.chapter);
        const render = {request, started: performance.now(), passes: [], queue: []};
        const total = request.samples = pathSamples(request);
        if (PATH_CHAPTERS.includes(request.chapter) && !request.coarse && total > 1) {
            for (let n = 1; n < total; n *= 2)
                render.passes.push(n);
            render.passes.push(total);
        }
        current = render;
        startPass(render);
    }

    // A new request: a full render being drawn is stopped; a coarse one finishes first (the newest
    // request waits for it), so that dragging shows every frame it can.
    function render(request) {
        if (current && current.request.coarse && pool.chapter === request.chapter) {
            pending = request;
            return;
        }
        stop();
        begin(request);
    }

    // Abandons the render being drawn (its bands still being drawn finish, unseen) and any waiting one.
    function stop() {
        pending = null;
        current = null;
    }

    return {render, stop, get workers() { return count; }, get busy() { return current !== null; }};
})();
