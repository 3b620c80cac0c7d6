#version 460
// lighting.comp.glsl: deferred shading of every G-buffer pixel with geometry (depth < 1): glTF metallic-
// roughness BRDF for each punctual light, ambient from the environment (SH9 diffuse irradiance + a
// roughness-blurred radiance lookup with the split-sum environment BRDF, both times occlusion), plus emission;
// point-light cube shadows (include/surface_lighting.glsl holds the shading core, shared with transparency;
// include/deferred_lighting_pixel.glsl the per-pixel body, shared with the hardware-VRS fragment pass).
// Ports IDKEngine's DeferredLighting/fragment.glsl as a compute pass (reference 2.19) without its bugs.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "vrs_rates.glsl"
#include "deferred_lighting_pixel.glsl"  // the shading of one pixel (shared with the hardware-VRS fragment pass)

layout(local_size_x = kLightingGroupSize, local_size_y = kLightingGroupSize) in;
layout(push_constant, scalar) uniform Push { LightingPush p; };

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!vrsAnchorOfInvocation(p.vrsRates, pixel)) return;  // software VRS: vrs/reconstruct.comp fills the rest
    if (any(greaterThanEqual(uvec2(pixel), f.extent))) return;
    vec4 radiance;
    if (deferredLightingPixel(p, f, pixel, radiance)) imageStore(gImagesRgba16f[p.target], pixel, radiance);
}
