/* shape_kinds.h: every kind of shape the scene format knows, one line each (chapter 1; shape.h
 * explains the two halves of a shape's module).
 *
 * Each header ends with its registration line, SHAPE_KIND(type, array, FEATURE, chapter), outside its
 * include guard. Included plainly, this file includes the headers. Included again with SHAPE_KIND
 * defined (scene.h, scene.c), the guarded parts are skipped and only the registration lines remain,
 * in this order: the order of the scene's arrays, of the POV-Ray twin and of the world's loops.
 * Adding a kind of shape is its module (header and .c) and one line here. No include guard, on purpose. */
#include "sphere.h"
#include "triangle.h"
#include "plane.h"
#include "box.h"
