#version 460
// mask_bvh.comp.glsl: ray-traced shadow mask, portable rung of "ray traversal" (our GLSL BVH, binary walk).
#extension GL_GOOGLE_include_directive : require
#include "mask_body.h"
