#!/usr/bin/env node
// bunny-to-ply.js: writes the Stanford bunny of the npm package `bunny` as an ASCII PLY file.
//
//   node tools/models/bunny-to-ply.js PACKAGE_DIR [OUTPUT.ply]
//
// PACKAGE_DIR is the unpacked package (the folder holding its package.json and index.js), or
// `bunny` to let Node resolve it from node_modules. The package exports
// {positions: [[x, y, z], ...], cells: [[i, j, k], ...]} with 0-based indices; they are written
// unchanged (numbers in JavaScript's shortest round-trip form, so the output is reproducible), after
// checking that every cell is a triangle with indices in range and every coordinate is finite.
// Without OUTPUT the PLY goes to standard output. No dependencies besides the package itself.
'use strict';

const fs = require('fs');
const path = require('path');

function fail(msg) {
    process.stderr.write('bunny-to-ply: ' + msg + '\n');
    process.exit(1);
}

function main(argv) {
    if (argv.length < 1 || argv.length > 2 || argv[0] === '-h' || argv[0] === '--help') {
        process.stderr.write('usage: node tools/models/bunny-to-ply.js PACKAGE_DIR [OUTPUT.ply]\n');
        process.exit(2);
    }
    const where = argv[0];
    const target = fs.existsSync(where) ? path.resolve(where) : where;
    let version = 'unknown';
    try {
        version = require(path.join(target, 'package.json')).version;
    } catch (e) {
        // A bare module name: the version comes from its own package.json if Node can find it.
        try { version = require(where + '/package.json').version; } catch (e2) { /* keep unknown */ }
    }
    let bunny;
    try {
        bunny = require(target);
    } catch (e) {
        fail('cannot load the bunny package from ' + where + ': ' + e.message);
    }
    const positions = bunny.positions;
    const cells = bunny.cells;
    if (!Array.isArray(positions) || !Array.isArray(cells)) {
        fail('the package does not export {positions, cells} arrays');
    }

    const lines = [];
    lines.push('ply');
    lines.push('format ascii 1.0');
    lines.push('comment Stanford Bunny: Stanford University Computer Graphics Laboratory, '
        + 'Stanford 3D Scanning Repository (Greg Turk and Marc Levoy, 1994)');
    lines.push('comment converted from the npm package bunny@' + version
        + ' (Mikola Lysenko, licence "Public Domain") by tools/models/bunny-to-ply.js; y is up');
    lines.push('element vertex ' + positions.length);
    lines.push('property float x');
    lines.push('property float y');
    lines.push('property float z');
    lines.push('element face ' + cells.length);
    lines.push('property list uchar int vertex_indices');
    lines.push('end_header');

    positions.forEach((p, n) => {
        if (!Array.isArray(p) || p.length !== 3 || !p.every(Number.isFinite)) {
            fail('position ' + n + ' is not three finite numbers: ' + JSON.stringify(p));
        }
        lines.push(p.map(String).join(' '));
    });
    cells.forEach((c, n) => {
        if (!Array.isArray(c) || c.length !== 3) {
            fail('cell ' + n + ' is not a triangle: ' + JSON.stringify(c));
        }
        for (const i of c) {
            if (!Number.isInteger(i) || i < 0 || i >= positions.length) {
                fail('cell ' + n + ' has an index out of range: ' + JSON.stringify(c));
            }
        }
        lines.push('3 ' + c.join(' '));
    });

    const text = lines.join('\n') + '\n';
    if (argv.length === 2) {
        fs.writeFileSync(argv[1], text);
        process.stderr.write('bunny-to-ply: wrote ' + argv[1] + ': ' + positions.length
            + ' vertices, ' + cells.length + ' triangles\n');
    } else {
        process.stdout.write(text);
    }
}

main(process.argv.slice(2));
