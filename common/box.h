/* box.h: the axis-aligned box as a renderable shape (the type arrives with chapter 5; the scene
 * format knows it from the start so that every scene file reads the same in every chapter). */
#ifndef WHITTED_BOX_H
#define WHITTED_BOX_H

#include "vec3.h"

struct box {
    vec3 min, max; /* opposite corners, min < max on every axis */
    int material;  /* index into scene.materials */
};

#endif
