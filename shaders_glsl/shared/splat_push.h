// splat_push.h: the push block of the float-atomics splat kernels (shaders_glsl/atomics/splat_add_*.comp.glsl,
// engine/render/float_splat.cpp): bins[sampleBins[i]] += sampleValues[i] for i < count, by float atomic add
// (native) or a compare-and-swap loop on the bits (fallback). The GL rung's twin is shaders_glsl/gl/splat_add.comp.glsl.
#ifndef IDK_SPLAT_PUSH_H
#define IDK_SPLAT_PUSH_H
#include "interop.h"

IDK_GPU_BEGIN
IDK_CONST(uint, kSplatGroupSize, 64);

struct SplatPush {
    uint bins;          // bindless storage buffer of float bins
    uint sampleBins;    // uint bin index per sample
    uint sampleValues;  // float value per sample
    uint count;         // samples
    uint binCount;      // samples whose bin is out of range are dropped (the oracle drops them too)
};
IDK_GPU_SIZE(SplatPush, 20);
IDK_GPU_END
#endif
