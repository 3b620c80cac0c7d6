#version 460
// downsample.comp.glsl: one level of the bloom's downsample chain with the 13-tap filter of Jimenez, "Next
// Generation Post Processing in Call of Duty: Advanced Warfare" (SIGGRAPH 2014, slides 145-162): five overlapping
// 2x2 groups of bilinear taps (the centre group weighted 0.5, the four corner groups 0.125 each), optionally
// combined with the Karis average (each group weighted by 1 / (1 + luma)). Every tap sits on a texel corner, so
// each is the mean of a 2x2 block. Ports IDKEngine's Bloom/compute.glsl downsample stage, without its threshold
// prefilter (the CoD bloom is a blend of the whole image, which is what keeps it energy conserving).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "bloom_types.h"
#include "storage_bilinear.glsl"

layout(local_size_x = kBloomGroupSize, local_size_y = kBloomGroupSize) in;
layout(push_constant, scalar) uniform Push { BloomDownPush p; };

// The bilinear tap at texel corner k (between texels k - 1 and k in each axis).
vec3 cornerTap(ivec2 k) {
    return 0.25 * (storageTexel(p.source, k - 1, p.srcSize) + storageTexel(p.source, ivec2(k.x, k.y - 1), p.srcSize) +
                   storageTexel(p.source, ivec2(k.x - 1, k.y), p.srcSize) + storageTexel(p.source, k, p.srcSize));
}

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.dstSize))) return;
    ivec2 c = 2 * pixel + 1;  // the destination pixel's centre: a source texel corner
    vec3 a = cornerTap(c + ivec2(-2, -2)), b = cornerTap(c + ivec2(0, -2)), d = cornerTap(c + ivec2(2, -2));
    vec3 e = cornerTap(c + ivec2(-2, 0)), f = cornerTap(c), g = cornerTap(c + ivec2(2, 0));
    vec3 h = cornerTap(c + ivec2(-2, 2)), i = cornerTap(c + ivec2(0, 2)), j = cornerTap(c + ivec2(2, 2));
    vec3 k = cornerTap(c + ivec2(-1, -1)), l = cornerTap(c + ivec2(1, -1));
    vec3 m = cornerTap(c + ivec2(-1, 1)), n = cornerTap(c + ivec2(1, 1));
    vec3 groups[5] = vec3[5](0.25 * (k + l + m + n), 0.25 * (a + b + e + f), 0.25 * (b + d + f + g),
                             0.25 * (e + f + h + i), 0.25 * (f + g + i + j));
    const float base[5] = float[5](0.5, 0.125, 0.125, 0.125, 0.125);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int q = 0; q < 5; ++q) {
        float w = p.karis != 0u ? base[q] / (1.0 + luma(groups[q])) : base[q];
        sum += w * groups[q];
        weights += w;
    }
    imageStore(gImagesRgba16f[p.target], pixel, vec4(sum / weights, 1.0));
}
