#version 460
// ssr_keep.comp.glsl: copies this frame's lit image into the persistent "ssr lit image" that the next frame's SSR
// hits sample (passes/ssr.cpp). IDKEngine's SSR reads the current frame's image instead (ssr_feature.hpp says why).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "ssr_types.h"

layout(local_size_x = kSsrGroupSize, local_size_y = kSsrGroupSize) in;
layout(push_constant, scalar) uniform Push { SsrKeepPush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.extent))) return;
    imageStore(gImagesRgba16f[p.target], pixel, imageLoad(gImagesRgba16f[p.source], pixel));
}
