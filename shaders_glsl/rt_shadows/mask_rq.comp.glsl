#version 460
// mask_rq.comp.glsl: ray-traced shadow mask, native rung of "ray traversal" (VK_KHR_ray_query).
#extension GL_GOOGLE_include_directive : require
#define PT_RAY_QUERY
#include "mask_body.h"
