// volumetric_common.glsl: what the volumetric march and upsample share: the low-resolution sample's full-resolution
// pixel (the centre of its block) and the view distance a depth value means there (background: maxDistance).
#ifndef IDK_VOLUMETRIC_COMMON_GLSL
#define IDK_VOLUMETRIC_COMMON_GLSL
#include "deferred_types.h"
#include "volumetric_types.h"

ivec2 volumetricSamplePixel(ivec2 low, uint scale, uvec2 extent) {
    return min(low * int(scale) + int(scale / 2u), ivec2(extent) - 1);
}

// World position behind full-resolution pixel coordinate `pixel` (continuous, + 0.5 = centre) at `depth`, and the
// unit view direction towards it.
vec3 volumetricPoint(GpuFrame f, vec2 pixel, float depth, out vec3 dir) {
    vec2 ndc = pixel / vec2(f.extent) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, min(depth, 0.5), 1.0);
    vec4 hNear = f.inverseViewProjection * vec4(ndc, 0.0, 1.0);
    vec3 nearPoint = hNear.xyz / hNear.w;
    dir = normalize(h.xyz / h.w - nearPoint);
    if (depth < 1.0) {
        vec4 s = f.inverseViewProjection * vec4(ndc, depth, 1.0);
        return s.xyz / s.w;
    }
    return nearPoint + dir * 1e30;  // background
}

// Distance the march covers in front of `pixel` (to the surface, or maxDistance for the background).
float volumetricLength(GpuFrame f, vec2 pixel, float depth, float maxDistance, out vec3 dir) {
    vec3 p = volumetricPoint(f, pixel, depth, dir);
    return depth < 1.0 ? distance(f.cameraPosition, p) : maxDistance;
}

#endif
