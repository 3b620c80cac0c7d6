// rt_shadow_types.h: ray-traced shadows (engine/frame/rt_shadow_feature.cpp, passes/rt_shadows.cpp): the push
// block of the mask pass and the record a ray-traced light's shadow-table entry points at. Ports the interface of
// IDKEngine's ShadowsRayTraced/compute.glsl (one visibility value per pixel and shadowed light, reference 2.12).
#ifndef IDK_RT_SHADOW_TYPES_H
#define IDK_RT_SHADOW_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kRayTracedShadow, 0xFFFFFFFEu);  // GpuPointShadow::cube of a light whose visibility is ray traced
IDK_CONST(uint, kRtShadowMaxLights, 16u);        // lights per mask pass (the settings' shadow-light limit)
IDK_CONST(uint, kRtShadowGroupSize, 8u);         // 8x8 pixels per workgroup

// At GpuPointShadow::mapOffset of a ray-traced light: its visibility is mask[(slot * height + y) * width + x] of
// the pixel the deferred lighting shades (1 lit .. 0 shadowed).
struct GpuRtShadowMask {
    DeviceAddress mask;  // float[slots * width * height]
    uint width;
    uint height;
    uint slot;
    uint pad;
};
IDK_GPU_SIZE(GpuRtShadowMask, 24);

// rt_shadows/mask_{bvh,rq}.comp: one invocation per pixel and shadowed light (z = slot).
struct RtShadowPush {
    DeviceAddress frame;  // GpuFrame
    DeviceAddress scene;  // GpuPtSceneDesc: the path tracer's geometry, BVH / acceleration structure, materials
    DeviceAddress mask;   // float[casterCount * width * height]
    uint depth;           // R32F storage image (G-buffer depth)
    uint normal;          // R32UI storage image (G-buffer octahedral normal)
    uint casterCount;
    uint casters[kRtShadowMaxLights];  // light index per slot
    float lightRadius;    // > 0: point and spot lights are spheres of this radius (soft shadows, softRays rays)
    uint softRays;        // rays per pixel and light with a radius, uniform over the sphere's solid angle
    uint pad;
};
IDK_GPU_SIZE(RtShadowPush, 112);

// rt_shadows/denoise.comp: the edge-aware spatial filter of soft (light radius > 0) masks, noisy -> filtered.
struct RtShadowDenoisePush {
    DeviceAddress frame;     // GpuFrame
    DeviceAddress noisy;     // float[slots * width * height], as RtShadowPush::mask
    DeviceAddress filtered;  // same layout; what the shadow table points the lighting at
    uint depth;              // R32F storage image (G-buffer depth)
    uint normal;             // R32UI storage image (G-buffer octahedral normal)
    uint slots;
    uint rays;               // the mask's rays per pixel: the filter narrows as the estimate's noise falls
};
IDK_GPU_SIZE(RtShadowDenoisePush, 40);

IDK_GPU_END
#endif
