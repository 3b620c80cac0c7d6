#version 460
// trace_bvh.comp.glsl: wavefront closest-hit stage (our GLSL BVH rung), one invocation per
// ray of the input queue (indirect dispatch): writes the path's hit record and, when sorting is on, the ray's sort
// key (material, direction octant) at its queue slot. Port of the traversal half of IDKEngine NHit.
#extension GL_GOOGLE_include_directive : require

#include "wf_trace_stage.h"
