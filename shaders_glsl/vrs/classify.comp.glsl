#version 460
// classify.comp.glsl: one workgroup per tile classifies the tile's shading rate from the mean speed of its pixels
// (the velocity buffer) and the coefficient of variation of their luminance (the lit frame), writing the palette
// index into the rate buffer that the next frame's lighting and sky read. Ports IDKEngine's
// ShadingRateClassification/compute.glsl (reference 2.13): subgroupAdd then shared memory across subgroups; here
// also a shared-memory-only tree (kSubgroupReduce = 0) for devices without subgroup arithmetic, integer sums and
// a decision without division or float sqrt (shared/vrs_types.h), so both variants and the CPU oracle agree bit
// for bit.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "bindless.glsl"
#include "vrs_rates.glsl"

layout(local_size_x = kVrsGroupSize) in;
layout(constant_id = kSpecVrsTileSize) const uint kTileSize = 16;
layout(constant_id = kSpecVrsSubgroupReduce) const uint kSubgroupReduce = 1;
layout(push_constant, scalar) uniform Push { VrsClassifyPush p; };

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer VelocityRef { vec2 v[]; };

// The tree needs one slot per invocation; the subgroup path one per subgroup, at most one per invocation whatever
// the subgroup size (8 on lavapipe, 32/64 on GPUs, varying within [min, max] under SPIR-V 1.6).
shared uvec4 sSlots[kVrsGroupSize];

// x: max (luminance bits), yzw: sums. kMax selects which: one function reduces either way.
uvec4 combine(uvec4 a, uvec4 b, bool isMax) { return isMax ? max(a, b) : a + b; }

uvec4 workgroupReduce(uvec4 value, bool isMax) {
    if (kSubgroupReduce != 0u) {
        uvec4 s = isMax ? subgroupMax(value) : subgroupAdd(value);
        if (subgroupElect()) sSlots[gl_SubgroupID] = s;
        // SYNC: barrier() orders the per-subgroup slot writes before invocation 0 reads them all.
        barrier();
        if (gl_LocalInvocationIndex == 0u) {
            uvec4 acc = sSlots[0];
            for (uint i = 1u; i < gl_NumSubgroups; ++i) acc = combine(acc, sSlots[i], isMax);
            sSlots[0] = acc;
        }
    } else {
        sSlots[gl_LocalInvocationIndex] = value;
        barrier();
        for (uint cutoff = kVrsGroupSize / 2u; cutoff > 0u; cutoff /= 2u) {
            if (gl_LocalInvocationIndex < cutoff)
                sSlots[gl_LocalInvocationIndex] = combine(sSlots[gl_LocalInvocationIndex],
                                                          sSlots[gl_LocalInvocationIndex + cutoff], isMax);
            barrier();
        }
    }
    // SYNC: the result in slot 0 is visible to all before anyone reuses the slots.
    barrier();
    uvec4 result = sSlots[0];
    barrier();
    return result;
}

void main() {
    const uint tilePixels = kTileSize * kTileSize;
    uvec2 origin = gl_WorkGroupID.xy * kTileSize;
    uvec2 inside = min(uvec2(kTileSize), uvec2(p.width, p.height) - origin);
    uint n = inside.x * inside.y;

    // Each invocation takes pixels i, i + 256, ... of the tile (one for 16x16, four for 32x32, 8x8 leaves 192 idle).
    float lum[(32 * 32) / kVrsGroupSize];
    uint speed = 0u, maxBits = 0u;
    for (uint k = 0u; k < (tilePixels + kVrsGroupSize - 1u) / kVrsGroupSize; ++k) {
        uint i = gl_LocalInvocationIndex + k * kVrsGroupSize;
        lum[k] = 0.0;
        uvec2 local = uvec2(i % kTileSize, i / kTileSize);
        if (i >= tilePixels || any(greaterThanEqual(local, inside))) continue;
        uvec2 pixel = origin + local;
        lum[k] = vrsLuminance(imageLoad(gImagesRgba16f[p.lit], ivec2(pixel)).rgb);
        maxBits = max(maxBits, floatBitsToUint(lum[k]));  // non-negative floats order like their bits
        if (p.velocity != 0ul)
            speed += vrsSpeedFixed(VelocityRef(p.velocity).v[pixel.y * p.width + pixel.x], p.invFrameSeconds, tilePixels);
    }
    maxBits = workgroupReduce(uvec4(maxBits, 0u, 0u, 0u), true).x;

    float scale = vrsLumScale(maxBits, vrsLumBits(tilePixels));
    bool dark = maxBits < floatBitsToUint(kVrsDarkLuminance);  // also keeps the scale in range
    uint s1 = 0u, s2 = 0u;
    for (uint k = 0u; k < (tilePixels + kVrsGroupSize - 1u) / kVrsGroupSize && !dark; ++k) {
        uint q = vrsLumFixed(lum[k], scale);
        s1 += q;
        s2 += q * q;
    }
    uvec4 sums = workgroupReduce(uvec4(0u, s1, s2, speed), false);

    if (gl_LocalInvocationIndex == 0u) {
        VrsRatesRef r = VrsRatesRef(p.rates);
        r.rate[gl_WorkGroupID.y * r.header.tilesX + gl_WorkGroupID.x] =
            vrsTileRate(n, tilePixels, maxBits, sums.y, sums.z, sums.w, p.speedFactor, p.lumVarianceFactor);
    }
}
