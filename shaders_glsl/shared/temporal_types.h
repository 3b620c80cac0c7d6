// temporal_types.h: push blocks of the temporal passes (motion vectors, TAA resolve) and of bloom. Ports the role
// of IDKEngine's TAA UBO (binding 4: jitter, sample count) as push constants.
#ifndef IDK_TEMPORAL_TYPES_H
#define IDK_TEMPORAL_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

// This frame's camera matrices for the temporal passes (one host-visible copy per frame slot; too big for push
// constants, which are limited to 128 bytes).
struct GpuTemporalFrame {
    mat4 viewProjection;     // this frame's jittered matrix (= GpuFrame::viewProjection)
    mat4 unjittered;         // this frame's matrix without jitter
    mat4 inverseUnjittered;  // clip -> world without jitter (reprojects background pixels)
    mat4 previous;           // last frame's matrix without jitter (= unjittered on the first frame)
    mat4 inversePrevious;    // last frame: clip -> world without jitter (positions of the history's depth)
    vec3 cameraPosition;     // this frame's eye (world)
    float pad;
    vec2 jitterPixels;       // sub-pixel offset of this frame's samples from the pixel centres, in pixels
    vec2 previousJitter;     // last frame's jitterPixels
    uvec2 extent;            // render size in pixels
};
IDK_GPU_SIZE(GpuTemporalFrame, 360);

// motion_vectors.vert/.frag: the G-buffer's geometry drawn again with this and last frame's transforms; writes
// the screen-space motion (current uv - previous uv, unjittered) of the surface the G-buffer kept.
struct MotionPush {
    DeviceAddress temporal;       // GpuTemporalFrame
    DeviceAddress vertices;       // GpuVertex[] this frame (skinned copies included)
    DeviceAddress instances;      // GpuInstance[] this frame
    DeviceAddress prevVertices;   // last frame's vertices (== vertices when nothing deforms)
    DeviceAddress prevInstances;  // last frame's instances (== instances when nothing moves)
    uint depth;                   // R32F storage image: the G-buffer's depth (the kept surface)
    uint pad;
};
IDK_GPU_SIZE(MotionPush, 48);

// taa_resolve.comp: blends this frame's lit image into the reprojected history.
struct TaaPush {
    DeviceAddress temporal;  // GpuTemporalFrame
    uint color;              // RGBA16F storage: this frame's lit image
    uint depth;              // R32F storage: this frame's depth
    uint motion;             // R32UI storage: packHalf2x16 motion vectors (uv units)
    uint history;            // RGBA16F storage: last frame's resolved colour; alpha = accumulated sample weight
    uint historyDepth;       // R32F storage: last frame's depth
    uint outColor;           // RGBA16F storage: this frame's resolved colour (+ weight), the next history
    uint outDepth;           // R32F storage: this frame's depth, kept for the next frame's disocclusion test
    uint historyMotion;      // R32UI storage: last frame's motion vectors
    uint outMotion;          // R32UI storage: this frame's motion vectors, kept for the next frame
    uint historyValid;       // 0: first frame or reset, history is ignored
    float maxWeight;         // cap of the accumulated sample weight (a still converges to the mean of this many)
    float clipGamma;         // variance clipping box = mean +- gamma * sigma in YCoCg
    uint clampHistory;       // 0: no neighbourhood clipping ("naive" TAA, tests)
    uint frameStatic;        // 1: nothing moved or changed since last frame: the history is kept whole
};
IDK_GPU_SIZE(TaaPush, 64);

// taa_output.comp: copies the resolved rgb into the frame's HDR image (keeping its alpha).
struct TaaOutputPush {
    uint source;   // RGBA16F storage
    uint target;   // RGBA16F storage
    uvec2 extent;
};
IDK_GPU_SIZE(TaaOutputPush, 16);

IDK_CONST(uint, kTemporalGroupSize, 8);  // 8x8 invocations per workgroup

// motion vectors are stored as packHalf2x16(current uv - previous uv) in an R32UI image (the bindless set has no
// rg16f storage array; the bits are the same as IDKEngine's RG16F velocity texture).

IDK_GPU_END
#endif
