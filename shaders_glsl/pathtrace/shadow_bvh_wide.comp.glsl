#version 460
// shadow_bvh_wide.comp.glsl: shadow_bvh.comp.glsl with the 8-wide compressed BLASes (include/bvh_traverse_wide.glsl):
// the wavefront shadow stage of the default BVH rung (--traversal bvh; bvh2 is the binary walk).
#extension GL_GOOGLE_include_directive : require
#define PT_BVH_WIDE
#include "wf_shadow_stage.h"
