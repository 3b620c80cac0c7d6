// hiz_level.glsl: the body of one level of a Hi-Z depth pyramid (shared/depth_pyramid.h): each texel is the
// HIZ_REDUCE (max or min, defined by the including shader) of the 2 x 2 texels below it (the depth image's pixels
// for level 0; fewer at odd edges, none resampled). One invocation per texel.
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
    d = HIZ_REDUCE(d, below(uvec2(last.x, first.y), belowSize, belowOffset));
    d = HIZ_REDUCE(d, below(uvec2(first.x, last.y), belowSize, belowOffset));
    d = HIZ_REDUCE(d, below(last, belowSize, belowOffset));
    Pyramid(p.pyramid).data[hizLevelOffset(p.depthSize, p.level) + texel.y * size.x + texel.x] = d;
}
