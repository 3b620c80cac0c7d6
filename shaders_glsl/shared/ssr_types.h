// ssr_types.h: push blocks of the screen-space reflection passes (shaders_glsl/ssr/): the closest-depth Hi-Z pyramid
// build and the Hi-Z ray march. Ports the uniforms of IDKEngine's SSR/compute.glsl (MaxDist, Samples, BinarySteps)
// with the Hi-Z march and thickness test it lacks.
#ifndef IDK_SSR_TYPES_H
#define IDK_SSR_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

// ssr_trace.comp: one mirror ray per G-buffer pixel through the MINIMUM (closest) depth pyramid.
struct SsrPush {
    mat4 previousViewProjection;  // last frame's (jittered) world -> clip: where `history` saw each point
    DeviceAddress frame;          // GpuFrame of this frame (the G-buffer's matrices)
    DeviceAddress pyramid;        // float[]: closest-depth pyramid, shared/depth_pyramid.h layout
    uint depth;                   // R32F storage: G-buffer depth (the pyramid's level "-1")
    uint normal;                  // R32UI storage: octahedral world normal
    uint material;                // RGBA8 storage: metallic, roughness, occlusion, lit
    uint history;                 // RGBA16F storage: last frame's lit image (before TAA)
    uint target;                  // RGBA16F storage: rgb reflected radiance, a hit weight (0: miss)
    uint maxSteps;                // Hi-Z iterations per ray
    float thickness;              // world units a surface is assumed to extend behind its depth
    uint historyValid;            // 0: no lit image from last frame (first frame): every ray misses
};
IDK_GPU_SIZE(SsrPush, 112);

// ssr_keep.comp: copies the frame's lit image into the next frame's history (a compute copy: every image stays in
// the GENERAL layout, so no layout transition follows the bindless dispatches; see deferred_types.h).
struct SsrKeepPush {
    uint source;  // RGBA16F storage: the lit image
    uint target;  // RGBA16F storage: "ssr lit image"
    uvec2 extent;
};
IDK_GPU_SIZE(SsrKeepPush, 16);

IDK_CONST(uint, kSsrGroupSize, 8);
IDK_CONST(uint, kSsrNoImage, 0xFFFFFFFFu);  // LightingPush::ssr when SSR is off
IDK_CONST(float, kSsrMaxRoughness, 0.5f);   // rougher surfaces keep the blurred environment lookup
IDK_CONST(float, kSsrRoughnessFade, 0.3f);  // hits fade out linearly from here to kSsrMaxRoughness
IDK_CONST(float, kSsrEdgeFade, 0.05f);      // hits fade out over this fraction of the screen at its borders

IDK_GPU_END
#endif
