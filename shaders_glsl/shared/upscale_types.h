// upscale_types.h: push block of the temporal upscaler's resolve (shaders_glsl/temporal/upscale_resolve.comp.glsl,
// engine/passes/upscale.cpp). Plays the role of FSR2's upscale constants (render size, display size, jitter).
#ifndef IDK_UPSCALE_TYPES_H
#define IDK_UPSCALE_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

struct UpscalePush {
    DeviceAddress temporal;  // GpuTemporalFrame: extent = render size, jitterPixels in render pixels
    uint color;              // RGBA16F storage (render size): this frame's lit image
    uint depth;              // R32F storage (render size): this frame's depth
    uint motion;             // R32UI storage (render size): packHalf2x16 motion vectors (uv units)
    uint opaque;             // RGBA16F storage (render size): the lit image before transparency; ~0u: none
    uint history;            // RGBA16F storage (output size): last frame's reconstruction; alpha = sample weight
    uint outColor;           // RGBA16F storage (output size): this frame's reconstruction, the next history
    uvec2 outputExtent;      // output size in pixels
    uint historyValid;       // 0: first frame or reset, history is ignored
    float maxWeight;         // cap of the accumulated sample weight
    float clipGamma;         // variance clipping box = mean +- gamma * sigma in YCoCg
    float sigma;             // Gaussian sample kernel's standard deviation in output pixels
    uint frameStatic;        // 1: nothing moved or changed since last frame: the history is kept whole
    uint pad;
};
IDK_GPU_SIZE(UpscalePush, 64);

// upscale_output.comp: the reconstruction's rgb with the coverage alpha of the nearest render pixel (the EXR
// output keeps geometry coverage in alpha).
struct UpscaleOutputPush {
    uint source;         // RGBA16F storage (output size): the reconstruction
    uint renderColor;    // RGBA16F storage (render size): the lit image (alpha = coverage)
    uint target;         // RGBA16F storage (output size)
    uint pad;
    uvec2 extent;        // output size
    uvec2 renderExtent;  // render size
};
IDK_GPU_SIZE(UpscaleOutputPush, 32);

IDK_GPU_END
#endif
