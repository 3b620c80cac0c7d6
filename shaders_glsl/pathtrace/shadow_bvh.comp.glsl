#version 460
// shadow_bvh.comp.glsl: wavefront shadow stage (our GLSL BVH rung), one invocation per next-event
// shadow ray (indirect dispatch): adds the ray's light contribution to its pixel's path when nothing blocks it.
// IDKEngine has no counterpart (no next-event estimation there, reference 2.1).
#extension GL_GOOGLE_include_directive : require

#include "wf_shadow_stage.h"
