// transmission_types.h: the screen-space transmission pass's push blocks (engine/passes/transmission.cpp):
// the opaque-colour chain's downsample and the forward pass's extra block after TransparencyPush.
#ifndef IDK_TRANSMISSION_TYPES_H
#define IDK_TRANSMISSION_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kTransmissionGroupSize, 8);
// Levels of the opaque-colour chain: level 0 is the lit frame, level k about 2^-k of it (ceil halving), so 10
// levels reach 1/512 of the frame; the roughest lookups clamp to the last.
IDK_CONST(uint, kTransmissionMaxLevels, 10);

// transmission/downsample.comp: dst = the mean of the 2x2 block of src under it (scale 2, clamped to src), or a
// copy (scale 1, level 0). RGBA16F storage images.
struct TransmissionDownPush {
    uint source;
    uint target;
    uvec2 sourceSize;
    uvec2 targetSize;
    uint scale;  // 1 or 2
};
IDK_GPU_SIZE(TransmissionDownPush, 28);

// transmission/forward.frag: follows TransparencyPush (72 bytes) in the push block; 72 + 48 <= 128, the push
// constant size Vulkan guarantees.
struct TransmissionPush {
    uint levels[kTransmissionMaxLevels];  // RGBA16F storage indices of the chain's levels 0..levelCount-1
    uint levelCount;                      // 0: --transmission off (the material drawn opaque, no refraction)
    uint pad;
};
IDK_GPU_SIZE(TransmissionPush, 48);

IDK_GPU_END
#endif
