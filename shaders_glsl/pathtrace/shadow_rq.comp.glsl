#version 460
// shadow_rq.comp.glsl: wavefront shadow stage (VK_KHR_ray_query rung), one invocation per next-event
// shadow ray (indirect dispatch): adds the ray's light contribution to its pixel's path when nothing blocks it.
// IDKEngine has no counterpart (no next-event estimation there, reference 2.1).
#extension GL_GOOGLE_include_directive : require
#define PT_RAY_QUERY
#include "wf_shadow_stage.h"
