// bloom_types.h: push blocks of the bloom passes (shaders_glsl/bloom/*). Ports the uniforms of IDKEngine's
// Bloom/compute.glsl (one shader with a stage switch there; three small shaders here).
#ifndef IDK_BLOOM_TYPES_H
#define IDK_BLOOM_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

// downsample.comp: the 13-tap filter from `source` (srcSize) into `target` (dstSize = srcSize / 2, rounded down).
struct BloomDownPush {
    uint source;     // RGBA16F storage
    uint target;     // RGBA16F storage
    uvec2 srcSize;
    uvec2 dstSize;
    uint karis;      // 1: Karis average of the five 2x2 groups (the first downsample: keeps fireflies from spreading)
    uint pad;
};
IDK_GPU_SIZE(BloomDownPush, 32);

// upsample.comp: target = tent3x3(coarse, bilinear) + detail (the downsample chain's level of target's size).
struct BloomUpPush {
    uint coarse;     // RGBA16F storage, coarseSize
    uint detail;     // RGBA16F storage, dstSize
    uint target;     // RGBA16F storage, dstSize
    uint pad;
    uvec2 coarseSize;
    uvec2 dstSize;
};
IDK_GPU_SIZE(BloomUpPush, 32);

// composite.comp: hdr = mix(hdr, bilinear(bloom) / levels, strength) (the sum of `levels` blurred copies, each with
// the image's mean, divided by their count: the image's total energy is kept).
struct BloomCompositePush {
    uint hdr;        // RGBA16F storage, read and written in place (alpha kept)
    uint bloom;      // RGBA16F storage, bloomSize
    uvec2 bloomSize;
    uvec2 dstSize;
    float strength;  // 0: no bloom, 1: only the blurred image
    float levels;
};
IDK_GPU_SIZE(BloomCompositePush, 32);

IDK_CONST(uint, kBloomGroupSize, 8);

IDK_GPU_END
#endif
