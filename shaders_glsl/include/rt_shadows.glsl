// rt_shadows.glsl: the lighting side of ray-traced shadows: a light whose shadow-table entry says kRayTracedShadow
// takes its visibility from the mask the rt_shadows pass wrote for the pixel being shaded. The deferred lighting
// sets gShadowPixel before shading; a pass without a pixel of the mask (forward transparency) leaves it at -1 and
// sees the light unshadowed.
#ifndef IDK_RT_SHADOWS_GLSL
#define IDK_RT_SHADOWS_GLSL
#extension GL_EXT_buffer_reference : require
#include "shadow_types.h"
#include "rt_shadow_types.h"

ivec2 gShadowPixel = ivec2(-1);

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer RtShadowMaskRecordRef {
    GpuRtShadowMask r;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer RtShadowMaskValues { float v[]; };

float rtShadowVisibility(uint64_t table, GpuPointShadow s) {
    if (gShadowPixel.x < 0) return 1.0;
    GpuRtShadowMask m = RtShadowMaskRecordRef(table + uint64_t(s.mapOffset)).r;
    uint index = (m.slot * m.height + uint(gShadowPixel.y)) * m.width + uint(gShadowPixel.x);
    return RtShadowMaskValues(m.mask).v[index];
}

#endif
