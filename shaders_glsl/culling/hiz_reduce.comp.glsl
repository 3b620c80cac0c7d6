#version 460
// hiz_reduce.comp.glsl: one level of the Hi-Z depth pyramid (shared/depth_pyramid.h) on the native rung of the
// ladder "hiz-reduction": each texel is ONE textureLod of the level below through a sampler whose reduction mode is
// MAX (VK_EXT_sampler_filter_minmax), placed at the corner the 2 x 2 texels share, so the filter unit returns their
// maximum (not a weighted average). The result goes to the pyramid buffer the culling passes read (the pass copies
// the level into an image for the next level to sample). Bit-exact with the compute rung (culling/hiz_build.comp.glsl): a
// maximum picks one of the depths unchanged. On a real GPU this halves the loads of the compute rung; lavapipe
// samples in software.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "bindless.glsl"
#include "depth_pyramid.h"

layout(local_size_x = kHizGroupSize, local_size_y = kHizGroupSize) in;
layout(push_constant, scalar) uniform Push { HizReducePush p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Pyramid { float data[]; };

void main() {
    uvec2 size = hizLevelSize(p.depthSize, p.level);
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(texel, size))) return;
    uvec2 belowSize = p.level == 0u ? p.depthSize : hizLevelSize(p.depthSize, p.level - 1u);
    // Texel 2t + 1's left/top edge: the footprint is texels 2t and 2t + 1 (clamped to the last at an odd edge),
    // both with weight 1/2, so the MAX reduction sees exactly the block.
    vec2 uv = vec2(texel * 2u + 1u) / vec2(belowSize);
    float d = textureLod(sampler2D(gTextures2D[p.source], gSamplers[p.samplerIndex]), uv, 0.0).r;
    Pyramid(p.pyramid).data[hizLevelOffset(p.depthSize, p.level) + texel.y * size.x + texel.x] = d;
}
