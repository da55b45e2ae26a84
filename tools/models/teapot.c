/* teapot.c: tessellates the Utah teapot into a binary PLY triangle mesh.
 *
 *   teapot N OUTPUT.ply               N subdivisions per patch side
 *   teapot --triangles T OUTPUT.ply   the smallest N giving at least T triangles
 *   teapot --uv ...                   the same triangles, each corner with its patch's (u, v) and a normal
 *
 * The surface is Martin Newell's 1975 teapot (University of Utah): 32 bicubic Bezier patches over
 * 306 control points, as the data set has been published since (rim 4, body 8, handle 4, spout 4,
 * lid 8, bottom 4; Newell's own set had no bottom, whose four patches were added later). It is in
 * the public domain. Control points 205, 206, 216 and 223 (offsets of 0.002 at the knob's apex)
 * are in the data but no patch uses them. The data is z-up; the output is y-up, each point
 * (x, y, z) of the data being written as (x, z, -y) (a proper rotation of -90 degrees about x, so
 * windings are kept: the spout points to +x, the handle to -x, the lid knob to +y).
 *
 * Each patch is evaluated on an (N+1) x (N+1) grid at u, v = i/N, and each grid cell is split
 * into two triangles along its (i, j)-(i+1, j+1) diagonal, so there are at most 64 N^2 triangles.
 * Triangles of zero area are dropped (the lid's top patches and the bottom patches collapse one side
 * to a point, giving N of them per patch), and vertices at exactly the same position (the same
 * float bit patterns, -0 taken as +0) are welded into one. Points on a patch's border are evaluated
 * from that border's curve alone, with its four control points put in a canonical order first, so
 * the two patches along a shared edge compute bit-identical points and the weld joins them.
 * Every triangle is counter-clockwise seen from outside the teapot. The mesh is open only where the
 * data is: the rim's inner edge, the lid's outer edge, both ends of the handle and of the spout.
 *
 * With --uv the file also gives each vertex the (u, v) = (i/N, j/N) of its patch, the natural texture
 * coordinates of a Bezier patch (chapter 14's uv mapping: one copy of a picture on each patch, u along
 * a row of control points and v across them, so that u, v and the outward normal are right-handed and
 * a picture is not mirrored seen from outside). A point on a seam between two patches has a different
 * (u, v) in each, so there each patch keeps its own vertex: the vertices are welded within a patch only
 * (one per grid point that a triangle uses). The triangles are exactly those of the welded mesh, in the
 * same order with the same corner positions; only the vertex list differs. So that the surface stays
 * smooth across the seams, every vertex also carries a normal, nx ny nz: the area-weighted average of
 * the normals of the faces round its position in the welded mesh (the rule mesh_surface_average_normals
 * applies to a file without normals), the same for every copy of a seam vertex.
 *
 * Build: gcc -std=c11 -D_DEFAULT_SOURCE -Wall -Wextra -Werror -O2 tools/models/teapot.c -o build/teapot -lm */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- Newell's data: 306 control points (x, y, z), z up ---------------------------------------- */
static const double points[306][3] = {
    /*   1 */ {1.4, 0.0, 2.4}, {1.4, -0.784, 2.4}, {0.784, -1.4, 2.4}, {0.0, -1.4, 2.4},
    /*   5 */ {1.3375, 0.0, 2.53125}, {1.3375, -0.749, 2.53125}, {0.749, -1.3375, 2.53125},
    /*   8 */ {0.0, -1.3375, 2.53125}, {1.4375, 0.0, 2.53125}, {1.4375, -0.805, 2.53125},
    /*  11 */ {0.805, -1.4375, 2.53125}, {0.0, -1.4375, 2.53125}, {1.5, 0.0, 2.4},
    /*  14 */ {1.5, -0.84, 2.4}, {0.84, -1.5, 2.4}, {0.0, -1.5, 2.4}, {-0.784, -1.4, 2.4},
    /*  18 */ {-1.4, -0.784, 2.4}, {-1.4, 0.0, 2.4}, {-0.749, -1.3375, 2.53125},
    /*  21 */ {-1.3375, -0.749, 2.53125}, {-1.3375, 0.0, 2.53125}, {-0.805, -1.4375, 2.53125},
    /*  24 */ {-1.4375, -0.805, 2.53125}, {-1.4375, 0.0, 2.53125}, {-0.84, -1.5, 2.4},
    /*  27 */ {-1.5, -0.84, 2.4}, {-1.5, 0.0, 2.4}, {-1.4, 0.784, 2.4}, {-0.784, 1.4, 2.4},
    /*  31 */ {0.0, 1.4, 2.4}, {-1.3375, 0.749, 2.53125}, {-0.749, 1.3375, 2.53125},
    /*  34 */ {0.0, 1.3375, 2.53125}, {-1.4375, 0.805, 2.53125}, {-0.805, 1.4375, 2.53125},
    /*  37 */ {0.0, 1.4375, 2.53125}, {-1.5, 0.84, 2.4}, {-0.84, 1.5, 2.4}, {0.0, 1.5, 2.4},
    /*  41 */ {0.784, 1.4, 2.4}, {1.4, 0.784, 2.4}, {0.749, 1.3375, 2.53125},
    /*  44 */ {1.3375, 0.749, 2.53125}, {0.805, 1.4375, 2.53125}, {1.4375, 0.805, 2.53125},
    /*  47 */ {0.84, 1.5, 2.4}, {1.5, 0.84, 2.4}, {1.75, 0.0, 1.875}, {1.75, -0.98, 1.875},
    /*  51 */ {0.98, -1.75, 1.875}, {0.0, -1.75, 1.875}, {2.0, 0.0, 1.35}, {2.0, -1.12, 1.35},
    /*  55 */ {1.12, -2.0, 1.35}, {0.0, -2.0, 1.35}, {2.0, 0.0, 0.9}, {2.0, -1.12, 0.9},
    /*  59 */ {1.12, -2.0, 0.9}, {0.0, -2.0, 0.9}, {-0.98, -1.75, 1.875}, {-1.75, -0.98, 1.875},
    /*  63 */ {-1.75, 0.0, 1.875}, {-1.12, -2.0, 1.35}, {-2.0, -1.12, 1.35}, {-2.0, 0.0, 1.35},
    /*  67 */ {-1.12, -2.0, 0.9}, {-2.0, -1.12, 0.9}, {-2.0, 0.0, 0.9}, {-1.75, 0.98, 1.875},
    /*  71 */ {-0.98, 1.75, 1.875}, {0.0, 1.75, 1.875}, {-2.0, 1.12, 1.35}, {-1.12, 2.0, 1.35},
    /*  75 */ {0.0, 2.0, 1.35}, {-2.0, 1.12, 0.9}, {-1.12, 2.0, 0.9}, {0.0, 2.0, 0.9},
    /*  79 */ {0.98, 1.75, 1.875}, {1.75, 0.98, 1.875}, {1.12, 2.0, 1.35}, {2.0, 1.12, 1.35},
    /*  83 */ {1.12, 2.0, 0.9}, {2.0, 1.12, 0.9}, {2.0, 0.0, 0.45}, {2.0, -1.12, 0.45},
    /*  87 */ {1.12, -2.0, 0.45}, {0.0, -2.0, 0.45}, {1.5, 0.0, 0.225}, {1.5, -0.84, 0.225},
    /*  91 */ {0.84, -1.5, 0.225}, {0.0, -1.5, 0.225}, {1.5, 0.0, 0.15}, {1.5, -0.84, 0.15},
    /*  95 */ {0.84, -1.5, 0.15}, {0.0, -1.5, 0.15}, {-1.12, -2.0, 0.45}, {-2.0, -1.12, 0.45},
    /*  99 */ {-2.0, 0.0, 0.45}, {-0.84, -1.5, 0.225}, {-1.5, -0.84, 0.225}, {-1.5, 0.0, 0.225},
    /* 103 */ {-0.84, -1.5, 0.15}, {-1.5, -0.84, 0.15}, {-1.5, 0.0, 0.15}, {-2.0, 1.12, 0.45},
    /* 107 */ {-1.12, 2.0, 0.45}, {0.0, 2.0, 0.45}, {-1.5, 0.84, 0.225}, {-0.84, 1.5, 0.225},
    /* 111 */ {0.0, 1.5, 0.225}, {-1.5, 0.84, 0.15}, {-0.84, 1.5, 0.15}, {0.0, 1.5, 0.15},
    /* 115 */ {1.12, 2.0, 0.45}, {2.0, 1.12, 0.45}, {0.84, 1.5, 0.225}, {1.5, 0.84, 0.225},
    /* 119 */ {0.84, 1.5, 0.15}, {1.5, 0.84, 0.15}, {-1.6, 0.0, 2.025}, {-1.6, -0.3, 2.025},
    /* 123 */ {-1.5, -0.3, 2.25}, {-1.5, 0.0, 2.25}, {-2.3, 0.0, 2.025}, {-2.3, -0.3, 2.025},
    /* 127 */ {-2.5, -0.3, 2.25}, {-2.5, 0.0, 2.25}, {-2.7, 0.0, 2.025}, {-2.7, -0.3, 2.025},
    /* 131 */ {-3.0, -0.3, 2.25}, {-3.0, 0.0, 2.25}, {-2.7, 0.0, 1.8}, {-2.7, -0.3, 1.8},
    /* 135 */ {-3.0, -0.3, 1.8}, {-3.0, 0.0, 1.8}, {-1.5, 0.3, 2.25}, {-1.6, 0.3, 2.025},
    /* 139 */ {-2.5, 0.3, 2.25}, {-2.3, 0.3, 2.025}, {-3.0, 0.3, 2.25}, {-2.7, 0.3, 2.025},
    /* 143 */ {-3.0, 0.3, 1.8}, {-2.7, 0.3, 1.8}, {-2.7, 0.0, 1.575}, {-2.7, -0.3, 1.575},
    /* 147 */ {-3.0, -0.3, 1.35}, {-3.0, 0.0, 1.35}, {-2.5, 0.0, 1.125}, {-2.5, -0.3, 1.125},
    /* 151 */ {-2.65, -0.3, 0.9375}, {-2.65, 0.0, 0.9375}, {-2.0, -0.3, 0.9}, {-1.9, -0.3, 0.6},
    /* 155 */ {-1.9, 0.0, 0.6}, {-3.0, 0.3, 1.35}, {-2.7, 0.3, 1.575}, {-2.65, 0.3, 0.9375},
    /* 159 */ {-2.5, 0.3, 1.125}, {-1.9, 0.3, 0.6}, {-2.0, 0.3, 0.9}, {1.7, 0.0, 1.425},
    /* 163 */ {1.7, -0.66, 1.425}, {1.7, -0.66, 0.6}, {1.7, 0.0, 0.6}, {2.6, 0.0, 1.425},
    /* 167 */ {2.6, -0.66, 1.425}, {3.1, -0.66, 0.825}, {3.1, 0.0, 0.825}, {2.3, 0.0, 2.1},
    /* 171 */ {2.3, -0.25, 2.1}, {2.4, -0.25, 2.025}, {2.4, 0.0, 2.025}, {2.7, 0.0, 2.4},
    /* 175 */ {2.7, -0.25, 2.4}, {3.3, -0.25, 2.4}, {3.3, 0.0, 2.4}, {1.7, 0.66, 0.6},
    /* 179 */ {1.7, 0.66, 1.425}, {3.1, 0.66, 0.825}, {2.6, 0.66, 1.425}, {2.4, 0.25, 2.025},
    /* 183 */ {2.3, 0.25, 2.1}, {3.3, 0.25, 2.4}, {2.7, 0.25, 2.4}, {2.8, 0.0, 2.475},
    /* 187 */ {2.8, -0.25, 2.475}, {3.525, -0.25, 2.49375}, {3.525, 0.0, 2.49375},
    /* 190 */ {2.9, 0.0, 2.475}, {2.9, -0.15, 2.475}, {3.45, -0.15, 2.5125}, {3.45, 0.0, 2.5125},
    /* 194 */ {2.8, 0.0, 2.4}, {2.8, -0.15, 2.4}, {3.2, -0.15, 2.4}, {3.2, 0.0, 2.4},
    /* 198 */ {3.525, 0.25, 2.49375}, {2.8, 0.25, 2.475}, {3.45, 0.15, 2.5125},
    /* 201 */ {2.9, 0.15, 2.475}, {3.2, 0.15, 2.4}, {2.8, 0.15, 2.4}, {0.0, 0.0, 3.15},
    /* 205 */ {0.0, -0.002, 3.15}, {0.002, 0.0, 3.15}, {0.8, 0.0, 3.15}, {0.8, -0.45, 3.15},
    /* 209 */ {0.45, -0.8, 3.15}, {0.0, -0.8, 3.15}, {0.0, 0.0, 2.85}, {0.2, 0.0, 2.7},
    /* 213 */ {0.2, -0.112, 2.7}, {0.112, -0.2, 2.7}, {0.0, -0.2, 2.7}, {-0.002, 0.0, 3.15},
    /* 217 */ {-0.45, -0.8, 3.15}, {-0.8, -0.45, 3.15}, {-0.8, 0.0, 3.15}, {-0.112, -0.2, 2.7},
    /* 221 */ {-0.2, -0.112, 2.7}, {-0.2, 0.0, 2.7}, {0.0, 0.002, 3.15}, {-0.8, 0.45, 3.15},
    /* 225 */ {-0.45, 0.8, 3.15}, {0.0, 0.8, 3.15}, {-0.2, 0.112, 2.7}, {-0.112, 0.2, 2.7},
    /* 229 */ {0.0, 0.2, 2.7}, {0.45, 0.8, 3.15}, {0.8, 0.45, 3.15}, {0.112, 0.2, 2.7},
    /* 233 */ {0.2, 0.112, 2.7}, {0.4, 0.0, 2.55}, {0.4, -0.224, 2.55}, {0.224, -0.4, 2.55},
    /* 237 */ {0.0, -0.4, 2.55}, {1.3, 0.0, 2.55}, {1.3, -0.728, 2.55}, {0.728, -1.3, 2.55},
    /* 241 */ {0.0, -1.3, 2.55}, {1.3, 0.0, 2.4}, {1.3, -0.728, 2.4}, {0.728, -1.3, 2.4},
    /* 245 */ {0.0, -1.3, 2.4}, {-0.224, -0.4, 2.55}, {-0.4, -0.224, 2.55}, {-0.4, 0.0, 2.55},
    /* 249 */ {-0.728, -1.3, 2.55}, {-1.3, -0.728, 2.55}, {-1.3, 0.0, 2.55},
    /* 252 */ {-0.728, -1.3, 2.4}, {-1.3, -0.728, 2.4}, {-1.3, 0.0, 2.4}, {-0.4, 0.224, 2.55},
    /* 256 */ {-0.224, 0.4, 2.55}, {0.0, 0.4, 2.55}, {-1.3, 0.728, 2.55}, {-0.728, 1.3, 2.55},
    /* 260 */ {0.0, 1.3, 2.55}, {-1.3, 0.728, 2.4}, {-0.728, 1.3, 2.4}, {0.0, 1.3, 2.4},
    /* 264 */ {0.224, 0.4, 2.55}, {0.4, 0.224, 2.55}, {0.728, 1.3, 2.55}, {1.3, 0.728, 2.55},
    /* 268 */ {0.728, 1.3, 2.4}, {1.3, 0.728, 2.4}, {0.0, 0.0, 0.0}, {1.5, 0.0, 0.15},
    /* 272 */ {1.5, 0.84, 0.15}, {0.84, 1.5, 0.15}, {0.0, 1.5, 0.15}, {1.5, 0.0, 0.075},
    /* 276 */ {1.5, 0.84, 0.075}, {0.84, 1.5, 0.075}, {0.0, 1.5, 0.075}, {1.425, 0.0, 0.0},
    /* 280 */ {1.425, 0.798, 0.0}, {0.798, 1.425, 0.0}, {0.0, 1.425, 0.0}, {-0.84, 1.5, 0.15},
    /* 284 */ {-1.5, 0.84, 0.15}, {-1.5, 0.0, 0.15}, {-0.84, 1.5, 0.075}, {-1.5, 0.84, 0.075},
    /* 288 */ {-1.5, 0.0, 0.075}, {-0.798, 1.425, 0.0}, {-1.425, 0.798, 0.0},
    /* 291 */ {-1.425, 0.0, 0.0}, {-1.5, -0.84, 0.15}, {-0.84, -1.5, 0.15}, {0.0, -1.5, 0.15},
    /* 295 */ {-1.5, -0.84, 0.075}, {-0.84, -1.5, 0.075}, {0.0, -1.5, 0.075},
    /* 298 */ {-1.425, -0.798, 0.0}, {-0.798, -1.425, 0.0}, {0.0, -1.425, 0.0},
    /* 301 */ {0.84, -1.5, 0.15}, {1.5, -0.84, 0.15}, {0.84, -1.5, 0.075}, {1.5, -0.84, 0.075},
    /* 305 */ {0.798, -1.425, 0.0}, {1.425, -0.798, 0.0},
};

/* ---- the 32 patches: 4 rows of 4 control points each, 1-based indices into points ------------- */
static const unsigned short patches[32][16] = {
    /* rim */
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    /* body, upper */
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    /* body, lower */
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    /* handle */
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    /* spout */
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    /* lid, knob */
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    /* lid, dome */
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    /* bottom */
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
};

enum { PATCH_COUNT = 32, POINT_COUNT = 306, MAX_N = 2000 };

/* ---- evaluation --------------------------------------------------------------------------------- */

/* The cubic Bernstein weights at t = k/n. */
static void bernstein(int k, int n, double w[4]) {
    double t = (double)k / (double)n, s = 1.0 - t;
    w[0] = s * s * s;
    w[1] = 3.0 * t * s * s;
    w[2] = 3.0 * t * t * s;
    w[3] = t * t * t;
}

static int point_cmp(const double *a, const double *b) {
    for (int c = 0; c < 3; c++) {
        if (a[c] < b[c]) return -1;
        if (a[c] > b[c]) return 1;
    }
    return 0;
}

/* The point at t = k/n of the cubic Bezier curve q[0..3]. The curve is first put in a canonical
 * order (reversed, with k becoming n - k, when its last control points sort before its first ones),
 * so that the same curve reached from either side gives a bit-identical point. */
static void curve_point(const double *q[4], int k, int n, double out[3]) {
    const double *c[4] = {q[0], q[1], q[2], q[3]};
    int order = point_cmp(q[0], q[3]);
    if (order == 0) order = point_cmp(q[1], q[2]);
    if (order > 0) {
        c[0] = q[3], c[1] = q[2], c[2] = q[1], c[3] = q[0];
        k = n - k;
    }
    if (k == 0 || k == n) { /* an end: the control point itself */
        memcpy(out, k == 0 ? c[0] : c[3], 3 * sizeof(double));
        return;
    }
    double w[4];
    bernstein(k, n, w);
    for (int d = 0; d < 3; d++) out[d] = w[0] * c[0][d] + w[1] * c[1][d] + w[2] * c[2][d] + w[3] * c[3][d];
}

/* The point of patch p at u = i/n (along a row of control points) and v = j/n (across the rows). */
static void patch_point(int p, int i, int j, int n, double out[3]) {
    const double *cp[4][4];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) cp[r][c] = points[patches[p][4 * r + c] - 1];
    if (j == 0 || j == n) { /* the first or last row of control points */
        curve_point(cp[j == 0 ? 0 : 3], i, n, out);
        return;
    }
    if (i == 0 || i == n) { /* the first or last column */
        int c = i == 0 ? 0 : 3;
        const double *col[4] = {cp[0][c], cp[1][c], cp[2][c], cp[3][c]};
        curve_point(col, j, n, out);
        return;
    }
    double wu[4], wv[4];
    bernstein(i, n, wu);
    bernstein(j, n, wv);
    for (int d = 0; d < 3; d++) {
        double sum = 0.0;
        for (int r = 0; r < 4; r++) {
            double row = 0.0;
            for (int c = 0; c < 4; c++) row += wu[c] * cp[r][c][d];
            sum += wv[r] * row;
        }
        out[d] = sum;
    }
}

/* ---- the mesh: welded vertices and triangles ------------------------------------------------------ */

struct mesh {
    float (*v)[3];
    size_t nv, cap_v;
    int32_t (*f)[3];
    size_t nf, cap_f;
    uint32_t (*grid_corner)[3]; /* each face's corners as grid points, patch * (N+1)^2 + j * (N+1) + i */
    int32_t *slots; /* open-addressing hash of vertex indices, -1 for empty */
    size_t nslots;  /* a power of two */
};

static void *xrealloc(void *p, size_t size) {
    void *q = realloc(p, size);
    if (!q) {
        fprintf(stderr, "teapot: out of memory\n");
        exit(1);
    }
    return q;
}

static uint32_t float_bits(float x) {
    uint32_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

static size_t hash_position(const float p[3]) {
    uint64_t h = 1469598103934665603u; /* FNV-1a over the three bit patterns */
    for (int c = 0; c < 3; c++) {
        uint32_t b = float_bits(p[c]);
        for (int k = 0; k < 4; k++) {
            h ^= (b >> (8 * k)) & 0xffu;
            h *= 1099511628211u;
        }
    }
    return (size_t)(h ^ (h >> 29));
}

static void mesh_init(struct mesh *m, size_t expected_vertices) {
    memset(m, 0, sizeof *m);
    m->nslots = 1024;
    while (m->nslots < 2 * expected_vertices) m->nslots *= 2;
    m->slots = xrealloc(NULL, m->nslots * sizeof *m->slots);
    for (size_t s = 0; s < m->nslots; s++) m->slots[s] = -1;
}

static void mesh_free(struct mesh *m) {
    free(m->v);
    free(m->f);
    free(m->grid_corner);
    free(m->slots);
    memset(m, 0, sizeof *m);
}

static void mesh_grow_hash(struct mesh *m) {
    free(m->slots);
    m->nslots *= 2;
    m->slots = xrealloc(NULL, m->nslots * sizeof *m->slots);
    for (size_t s = 0; s < m->nslots; s++) m->slots[s] = -1;
    for (size_t k = 0; k < m->nv; k++) {
        size_t s = hash_position(m->v[k]) & (m->nslots - 1);
        while (m->slots[s] >= 0) s = (s + 1) & (m->nslots - 1);
        m->slots[s] = (int32_t)k;
    }
}

/* The index of the vertex at exactly p (bit for bit), added if new. */
static int32_t mesh_vertex(struct mesh *m, const float p[3]) {
    size_t s = hash_position(p) & (m->nslots - 1);
    for (; m->slots[s] >= 0; s = (s + 1) & (m->nslots - 1)) {
        const float *q = m->v[m->slots[s]];
        if (float_bits(q[0]) == float_bits(p[0]) && float_bits(q[1]) == float_bits(p[1]) &&
            float_bits(q[2]) == float_bits(p[2]))
            return m->slots[s];
    }
    if (m->nv == m->cap_v) {
        m->cap_v = m->cap_v ? 2 * m->cap_v : 4096;
        m->v = xrealloc(m->v, m->cap_v * sizeof *m->v);
    }
    memcpy(m->v[m->nv], p, sizeof m->v[0]);
    m->slots[s] = (int32_t)m->nv;
    m->nv++;
    if (2 * m->nv > m->nslots) mesh_grow_hash(m);
    return (int32_t)(m->nv - 1);
}

/* Adds the triangle a, b, c unless its area is zero; its corners are the grid points ga, gb, gc. */
static void mesh_triangle(struct mesh *m, int32_t a, int32_t b, int32_t c, uint32_t ga, uint32_t gb, uint32_t gc) {
    if (a == b || b == c || c == a) return;
    double e1[3], e2[3];
    for (int d = 0; d < 3; d++) {
        e1[d] = (double)m->v[b][d] - (double)m->v[a][d];
        e2[d] = (double)m->v[c][d] - (double)m->v[a][d];
    }
    double n0 = e1[1] * e2[2] - e1[2] * e2[1];
    double n1 = e1[2] * e2[0] - e1[0] * e2[2];
    double n2 = e1[0] * e2[1] - e1[1] * e2[0];
    if (n0 == 0.0 && n1 == 0.0 && n2 == 0.0) return;
    if (m->nf == m->cap_f) {
        m->cap_f = m->cap_f ? 2 * m->cap_f : 4096;
        m->f = xrealloc(m->f, m->cap_f * sizeof *m->f);
        m->grid_corner = xrealloc(m->grid_corner, m->cap_f * sizeof *m->grid_corner);
    }
    m->f[m->nf][0] = a, m->f[m->nf][1] = b, m->f[m->nf][2] = c;
    m->grid_corner[m->nf][0] = ga, m->grid_corner[m->nf][1] = gb, m->grid_corner[m->nf][2] = gc;
    m->nf++;
}

/* Tessellates the teapot with n subdivisions per patch side into m. */
static void tessellate(int n, struct mesh *m) {
    size_t side = (size_t)n + 1;
    mesh_init(m, PATCH_COUNT * side * side);
    int32_t *grid = xrealloc(NULL, side * side * sizeof *grid);
    for (int p = 0; p < PATCH_COUNT; p++) {
        for (int j = 0; j <= n; j++) {
            for (int i = 0; i <= n; i++) {
                double q[3];
                patch_point(p, i, j, n, q);
                /* z-up (x, y, z) to y-up (x, z, -y); adding +0 turns -0 into +0 */
                float f[3] = {(float)q[0] + 0.0f, (float)q[2] + 0.0f, -(float)q[1] + 0.0f};
                grid[(size_t)j * side + (size_t)i] = mesh_vertex(m, f);
            }
        }
        for (int j = 0; j < n; j++) {
            for (int i = 0; i < n; i++) {
                size_t ga = (size_t)j * side + (size_t)i, gb = ga + 1, gc = gb + side, gd = ga + side;
                uint32_t first = (uint32_t)((size_t)p * side * side); /* the patch's first grid point */
                /* Newell's patches have du x dv pointing out of the teapot, so a, b, c and
                 * a, c, d are counter-clockwise seen from outside. */
                mesh_triangle(m, grid[ga], grid[gb], grid[gc], first + (uint32_t)ga, first + (uint32_t)gb,
                              first + (uint32_t)gc);
                mesh_triangle(m, grid[ga], grid[gc], grid[gd], first + (uint32_t)ga, first + (uint32_t)gc,
                              first + (uint32_t)gd);
            }
        }
    }
    free(grid);
}

/* ---- output --------------------------------------------------------------------------------------- */

static void put_u32le(unsigned char *b, uint32_t x) {
    b[0] = (unsigned char)(x & 0xffu);
    b[1] = (unsigned char)((x >> 8) & 0xffu);
    b[2] = (unsigned char)((x >> 16) & 0xffu);
    b[3] = (unsigned char)((x >> 24) & 0xffu);
}

/* The normal at each welded vertex of m: the sum of its faces' (b - a) x (c - a), twice their areas along
 * their normals, made unit length (zero where they cancel). Returns a malloc'd array of m->nv. */
static float (*average_normals(const struct mesh *m))[3] {
    double(*sum)[3] = xrealloc(NULL, (m->nv ? m->nv : 1) * sizeof *sum);
    memset(sum, 0, (m->nv ? m->nv : 1) * sizeof *sum);
    for (size_t k = 0; k < m->nf; k++) {
        const float *a = m->v[m->f[k][0]], *b = m->v[m->f[k][1]], *c = m->v[m->f[k][2]];
        double e1[3], e2[3];
        for (int d = 0; d < 3; d++) {
            e1[d] = (double)b[d] - (double)a[d];
            e2[d] = (double)c[d] - (double)a[d];
        }
        double area[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int corner = 0; corner < 3; corner++)
            for (int d = 0; d < 3; d++) sum[m->f[k][corner]][d] += area[d];
    }
    float(*normals)[3] = xrealloc(NULL, (m->nv ? m->nv : 1) * sizeof *normals);
    for (size_t k = 0; k < m->nv; k++) {
        double length = sqrt(sum[k][0] * sum[k][0] + sum[k][1] * sum[k][1] + sum[k][2] * sum[k][2]);
        for (int d = 0; d < 3; d++) normals[k][d] = length > 0.0 ? (float)(sum[k][d] / length) : 0.0f;
    }
    free(sum);
    return normals;
}

/* The vertices of the --uv file: one per grid point that a face uses, numbered in grid order. Fills
 * welded[g] with the welded vertex at grid point g and number[g] with its new index (both -1 if no face
 * uses g), and returns how many there are. */
static size_t number_grid_points(const struct mesh *m, int n, int32_t *welded, int32_t *number) {
    size_t side = (size_t)n + 1, points = PATCH_COUNT * side * side, count = 0;
    for (size_t g = 0; g < points; g++) welded[g] = -1;
    for (size_t k = 0; k < m->nf; k++)
        for (int corner = 0; corner < 3; corner++) welded[m->grid_corner[k][corner]] = m->f[k][corner];
    for (size_t g = 0; g < points; g++) number[g] = welded[g] < 0 ? -1 : (int32_t)count++;
    return count;
}

/* Writes m as a binary PLY of `vertices` vertices. Without welded (NULL), its welded vertices; with it,
 * the grid points of number_grid_points (welded and number are its), with normal and (u, v). */
static int write_ply(const char *path, const struct mesh *m, int n, const int32_t *welded, const int32_t *number,
                     size_t vertices) {
    FILE *out = fopen(path, "wb");
    if (!out) {
        fprintf(stderr, "teapot: cannot write %s: %s\n", path, strerror(errno));
        return 0;
    }
    int uv = welded != NULL;
    size_t side = (size_t)n + 1;
    fprintf(out,
            "ply\n"
            "format binary_little_endian 1.0\n"
            "comment Utah teapot: Martin Newell's 1975 Bezier patch data (University of Utah), "
            "32 bicubic patches, 306 control points; public domain\n"
            "comment tessellated by tools/models/teapot.c: %d x %d grid cells per patch, 2 triangles per "
            "cell, zero-area triangles dropped, equal vertices welded%s\n"
            "comment y is up: each data point (x, y, z) written as (x, z, -y)\n",
            n, n, uv ? " within each patch" : "");
    if (uv)
        fprintf(out, "comment u v: the patch's own parameters; nx ny nz: the faces' normals averaged across "
                     "patches\n");
    fprintf(out, "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n", vertices);
    if (uv)
        fprintf(out, "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n");
    fprintf(out, "element face %zu\nproperty list uchar int vertex_indices\nend_header\n", m->nf);
    unsigned char buf[32];
    if (uv) {
        float(*normals)[3] = average_normals(m);
        size_t points = PATCH_COUNT * side * side;
        for (size_t g = 0; g < points; g++) {
            if (number[g] < 0) continue;
            size_t i = g % side, j = (g / side) % side; /* the grid point (i, j) of its patch */
            const float *at = m->v[welded[g]], *normal = normals[welded[g]];
            float values[8] = {at[0], at[1], at[2], normal[0], normal[1], normal[2], (float)((double)i / n),
                               (float)((double)j / n)};
            for (int c = 0; c < 8; c++) put_u32le(buf + 4 * c, float_bits(values[c]));
            fwrite(buf, 1, 32, out);
        }
        free(normals);
    } else {
        for (size_t k = 0; k < m->nv; k++) {
            for (int c = 0; c < 3; c++) put_u32le(buf + 4 * c, float_bits(m->v[k][c]));
            fwrite(buf, 1, 12, out);
        }
    }
    for (size_t k = 0; k < m->nf; k++) {
        buf[0] = 3;
        for (int c = 0; c < 3; c++)
            put_u32le(buf + 1 + 4 * c, (uint32_t)(uv ? number[m->grid_corner[k][c]] : m->f[k][c]));
        fwrite(buf, 1, 13, out);
    }
    if (ferror(out) | fclose(out)) {
        fprintf(stderr, "teapot: error writing %s\n", path);
        return 0;
    }
    return 1;
}

/* ---- command line ----------------------------------------------------------------------------- */

static _Noreturn void usage(void) {
    fprintf(stderr,
            "usage: teapot [--uv] N OUTPUT.ply               N subdivisions per patch side (1..%d)\n"
            "       teapot [--uv] --triangles T OUTPUT.ply   the smallest N giving at least T triangles\n"
            "       --uv: each corner with its patch's (u, v) and the averaged normal\n",
            MAX_N);
    exit(2);
}

static long parse_positive(const char *s, long max) {
    char *end;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (errno || end == s || *end || x < 1 || x > max) return -1;
    return x;
}

int main(int argc, char **argv) {
    struct mesh m;
    int n;
    const char *path;
    int uv = argc > 1 && strcmp(argv[1], "--uv") == 0;
    if (uv) { /* the rest as without it */
        argc--;
        argv++;
    }
    if (argc == 3) {
        long x = parse_positive(argv[1], MAX_N);
        if (x < 0) usage();
        n = (int)x;
        path = argv[2];
        tessellate(n, &m);
    } else if (argc == 4 && strcmp(argv[1], "--triangles") == 0) {
        long t = parse_positive(argv[2], 64L * MAX_N * MAX_N);
        if (t < 0) usage();
        path = argv[3];
        /* There are at most 64 n^2 triangles, so no n below sqrt(t / 64) can do. */
        n = (int)floor(sqrt((double)t / 64.0));
        if (n < 1) n = 1;
        for (;; n++) {
            if (n > MAX_N) {
                fprintf(stderr, "teapot: no N up to %d gives %ld triangles\n", MAX_N, t);
                return 1;
            }
            tessellate(n, &m);
            if (m.nf >= (size_t)t) break;
            mesh_free(&m);
        }
        printf("teapot: %ld triangles asked for: N = %d gives %zu\n", t, n, m.nf);
    } else {
        usage();
    }
    size_t side = (size_t)n + 1;
    int32_t *welded = uv ? xrealloc(NULL, PATCH_COUNT * side * side * sizeof *welded) : NULL;
    int32_t *number = uv ? xrealloc(NULL, PATCH_COUNT * side * side * sizeof *number) : NULL;
    size_t vertices = uv ? number_grid_points(&m, n, welded, number) : m.nv;
    int ok = write_ply(path, &m, n, uv ? welded : NULL, number, vertices);
    if (ok) printf("teapot: wrote %s: N = %d, %zu vertices, %zu triangles\n", path, n, vertices, m.nf);
    free(welded);
    free(number);
    mesh_free(&m);
    return ok ? 0 : 1;
}
