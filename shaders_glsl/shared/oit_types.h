// oit_types.h: order-independent transparency (engine/passes/oit_weighted.cpp, oit_layers.cpp): the push blocks of
// the weighted composite and of the fixed-layer rung (its per-pixel arrays and resolve).
// Ports the resolve step of IDKEngine's ResolveTransparent/compute.glsl (weighted blended and k-buffer rungs).
#ifndef IDK_OIT_TYPES_H
#define IDK_OIT_TYPES_H
#include "interop.h"
#include "shadow_types.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kOitGroupSize, 8u);

struct OitCompositePush {
    uint accum;      // RGBA16F storage image: sum of (radiance a, a) w
    uint revealage;  // RGBA16F storage image: sum of -ln(1 - a) in r
    uint target;     // RGBA16F storage image: the lit HDR image, composited in place
    uint pad;
};
IDK_GPU_SIZE(OitCompositePush, 16);

// The fixed-layer rung (`--oit layers`): the original's TRANSPARENT_LAYERS = 10 per pixel (reference 2.14).
IDK_CONST(uint, kOitLayerCount, 10u);
IDK_CONST(uint, kOitEmptyKey, 0xFFFFFFFFu);  // a free slot (above every depth's bit pattern in [0, 1])

// Per-pixel arrays, slot-major (slot * pixelCount + y * width + x) so neighbouring pixels touch neighbouring words.
struct OitLayerBuffers {
    DeviceAddress keys;    // uint[kOitLayerCount * pixels]: depth bits, ascending per pixel (kOitEmptyKey = free)
    DeviceAddress claims;  // uint[pixels]: bit i set once a fragment wrote slot i's colour (ties take distinct slots)
    DeviceAddress colors;  // uvec2[kOitLayerCount * pixels]: packHalf2x16 (radiance.rg), (radiance.b, alpha)
    uint width;            // pixels per row
    uint pixelCount;       // width * height
};
IDK_GPU_SIZE(OitLayerBuffers, 32);

// Both raster passes' push block: the forward shading's plus the arrays (oit/layers.vert and its fragments).
struct OitLayersPush {
    TransparencyPush forward;
    OitLayerBuffers layers;
};
IDK_GPU_SIZE(OitLayersPush, 104);

struct OitResolvePush {
    OitLayerBuffers layers;
    uint target;  // RGBA16F storage image: the lit HDR image, composited in place
    uint pad0, pad1, pad2;
};
IDK_GPU_SIZE(OitResolvePush, 48);

IDK_GPU_END
#endif
