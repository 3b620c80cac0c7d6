#version 460
// hiz_min.comp.glsl: one level of the CLOSEST-depth Hi-Z pyramid for the SSR march: the layout and push block of
// culling/hiz_build.comp.glsl (shared/depth_pyramid.h), the reduction min instead of max. Culling needs the
// farthest depth of a cell (an occluder hides a box only behind all of it); a ray march needs the nearest (a ray
// in front of the nearest surface of a cell passes the whole cell without hitting anything).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "bindless.glsl"
#include "depth_pyramid.h"

layout(local_size_x = kHizGroupSize, local_size_y = kHizGroupSize) in;
layout(push_constant, scalar) uniform Push { HizBuildPush p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Pyramid { float data[]; };

float below(uvec2 texel, uvec2 size, uint offset) {
    if (p.level == 0u) return imageLoad(gImagesR32f[p.depth], ivec2(texel)).r;
    return Pyramid(p.pyramid).data[offset + texel.y * size.x + texel.x];
}

void main() {
    uvec2 size = hizLevelSize(p.depthSize, p.level);
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(texel, size))) return;
    uvec2 belowSize = p.level == 0u ? p.depthSize : hizLevelSize(p.depthSize, p.level - 1u);
    uint belowOffset = p.level == 0u ? 0u : hizLevelOffset(p.depthSize, p.level - 1u);
    uvec2 first = texel * 2u;
    uvec2 last = min(first + 1u, belowSize - 1u);
    float d = below(first, belowSize, belowOffset);
    d = min(d, below(uvec2(last.x, first.y), belowSize, belowOffset));
    d = min(d, below(uvec2(first.x, last.y), belowSize, belowOffset));
    d = min(d, below(last, belowSize, belowOffset));
    Pyramid(p.pyramid).data[hizLevelOffset(p.depthSize, p.level) + texel.y * size.x + texel.x] = d;
}
