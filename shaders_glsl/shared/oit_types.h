// oit_types.h: order-independent transparency (engine/passes/oit_weighted.cpp): the composite pass's push block.
// Ports the resolve step of IDKEngine's ResolveTransparent/compute.glsl for the weighted blended rung.
#ifndef IDK_OIT_TYPES_H
#define IDK_OIT_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kOitGroupSize, 8u);

struct OitCompositePush {
    uint accum;      // RGBA16F storage image: sum of (radiance a, a) w
    uint revealage;  // RGBA16F storage image: sum of -ln(1 - a) in r
    uint target;     // RGBA16F storage image: the lit HDR image, composited in place
    uint pad;
};
IDK_GPU_SIZE(OitCompositePush, 16);

IDK_GPU_END
#endif
