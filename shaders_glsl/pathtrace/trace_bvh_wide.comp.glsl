#version 460
// trace_bvh_wide.comp.glsl: trace_bvh.comp.glsl with the 8-wide compressed BLASes (include/bvh_traverse_wide.glsl):
// the wavefront closest-hit stage of the default BVH rung (--traversal bvh; bvh2 is the binary walk).
#extension GL_GOOGLE_include_directive : require
#define PT_BVH_WIDE
#include "wf_trace_stage.h"
