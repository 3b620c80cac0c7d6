#version 460
// upsample.comp.glsl: one level of the bloom's upsample chain: a 3x3 tent (1 2 1 / 2 4 2 / 1 2 1, / 16) of bilinear
// taps one coarse texel apart, plus the downsample chain's image of this level. Ports IDKEngine's Bloom/compute.glsl
// upsample stage.
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "bloom_types.h"
#include "storage_bilinear.glsl"

layout(local_size_x = kBloomGroupSize, local_size_y = kBloomGroupSize) in;
layout(push_constant, scalar) uniform Push { BloomUpPush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.dstSize))) return;
    vec2 position = (vec2(pixel) + 0.5) * vec2(p.coarseSize) / vec2(p.dstSize);
    vec3 tent = vec3(0.0);
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
            tent += float((2 - abs(x)) * (2 - abs(y))) / 16.0 *
                    storageBilinear(p.coarse, position + vec2(x, y), p.coarseSize);
    vec3 detail = imageLoad(gImagesRgba16f[p.detail], pixel).rgb;
    imageStore(gImagesRgba16f[p.target], pixel, vec4(tent + detail, 1.0));
}
