#version 460
// march.comp.glsl: volumetric lighting at reduced resolution: one view ray per block of scale x scale pixels
// (through the block's centre, to the surface seen at its centre pixel or maxDistance), midpoint steps through a
// homogeneous medium; at each step the in-scattered light of every punctual light (its incidence times its shadow
// visibility from the cubes / cascades / spot maps, times the Henyey-Greenstein phase) attenuated by the
// transmittance back to the eye. Writes rgb = in-scattered radiance, a = transmittance over the whole ray.
// Ports IDKEngine's VolumetricLight/compute.glsl (there shadows of point lights only, jittered steps + TAA).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "pbr.glsl"
#include "shadows.glsl"
#include "light_shadows.glsl"
#include "rt_shadow_types.h"
#include "volumetric_common.glsl"

layout(local_size_x = kVolumetricGroupSize, local_size_y = kVolumetricGroupSize) in;
layout(push_constant, scalar) uniform Push { VolumetricPush p; };

float henyeyGreenstein(float cosTheta, float g) {
    float d = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * kPi * d * sqrt(d));
}

// A light's shadow visibility at a point of the medium: as a surface facing the light (n = l). Ray-traced
// shadows exist only for G-buffer pixels: the medium sees those lights unshadowed.
float mediumVisibility(uint i, vec3 position, vec3 l) {
    if (p.shadows == 0) return 1.0;
    GpuPointShadow s = PointShadowBuffer(p.shadows).data[i];
    if (s.mapCount != 0u) return mapShadowVisibility(p.shadows, s, position, l, l);
    if (s.cube != kNoShadow && s.cube != kRayTracedShadow) return pointShadowVisibility(s, position, l, l);
    return 1.0;
}

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 low = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(gImagesRgba16f[p.lowRes]);
    if (any(greaterThanEqual(low, size))) return;
    ivec2 pixel = volumetricSamplePixel(low, p.scale, f.extent);
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    vec3 dir;
    float len = volumetricLength(f, vec2(pixel) + 0.5, depth, p.maxDistance, dir);

    LightBuffer lights = LightBuffer(f.lights);
    vec3 radiance = vec3(0.0);
    float dt = len / float(p.steps);
    for (uint k = 0u; k < p.steps; ++k) {
        float t = (float(k) + 0.5) * dt;
        vec3 x = f.cameraPosition + dir * t;
        vec3 inscatter = vec3(0.0);
        for (uint i = 0u; i < f.lightCount; ++i) {
            vec3 l;
            vec3 incident = lightIncidence(lights.data[i], x, l);
            if (all(equal(incident, vec3(0.0)))) continue;
            inscatter += incident * henyeyGreenstein(dot(l, dir), p.anisotropy) * mediumVisibility(i, x, l);
        }
        radiance += inscatter * (p.scattering * exp(-p.extinction * t) * dt);
    }
    imageStore(gImagesRgba16f[p.lowRes], low, vec4(radiance, exp(-p.extinction * len)));
}
