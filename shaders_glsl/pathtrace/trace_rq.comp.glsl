#version 460
// trace_rq.comp.glsl: wavefront closest-hit stage (VK_KHR_ray_query rung), one invocation per
// ray of the input queue (indirect dispatch): writes the path's hit record and, when sorting is on, the ray's sort
// key (material, direction octant) at its queue slot. Port of the traversal half of IDKEngine NHit.
#extension GL_GOOGLE_include_directive : require
#define PT_RAY_QUERY
#include "wf_trace_stage.h"
