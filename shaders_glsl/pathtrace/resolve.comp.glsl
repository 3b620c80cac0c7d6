#version 460
// resolve.comp.glsl: one invocation per pixel: the mean of the accumulated samples into the output images (linear
// radiance RGBA32F, albedo and normal RGBA16F, view distance R32F, the variance of the mean luminance R32F (-1 below
// two samples)), the denoiser's inputs.
#extension GL_GOOGLE_include_directive : require
#include "wf_common.h"

layout(set = 0, binding = kBindingStorageImages, rgba32f) uniform writeonly image2D gPtImagesRgba32f[];

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= pc.extent.x || p.y >= pc.extent.y) return;
    uint pixel = p.y * pc.extent.x + p.x;
    GpuPtAccum a = WfAccumRef(pc.accum).a;
    vec4 c = WfVec4Ref(a.color).v[pixel];
    float inv = c.w > 0.0 ? 1.0 / c.w : 0.0;
    vec4 albedo = WfVec4Ref(a.albedo).v[pixel];
    vec4 normal = WfVec4Ref(a.normal).v[pixel];
    vec3 n = normal.xyz * inv;
    float nl = length(n);
    imageStore(gPtImagesRgba32f[a.colorImage], ivec2(p), vec4(c.xyz * inv, 1.0));
    imageStore(gImagesRgba16f[a.albedoImage], ivec2(p), vec4(albedo.xyz * inv, 1.0));
    imageStore(gImagesRgba16f[a.normalImage], ivec2(p), vec4(nl > 0.0 ? n / nl : vec3(0.0), 0.0));
    imageStore(gImagesR32f[a.depthImage], ivec2(p), vec4(WfFloatRef(a.depth).f[pixel] * inv));
    // Variance of the mean luminance, (E[l^2] - E[l]^2) / (n - 1): the noise the denoiser weighs against.
    float mean = dot(c.xyz * inv, vec3(0.2126, 0.7152, 0.0722));
    float variance = c.w >= 2.0 ? max(WfFloatRef(a.moment).f[pixel] * inv - mean * mean, 0.0) / (c.w - 1.0) : -1.0;
    imageStore(gImagesR32f[a.varianceImage], ivec2(p), vec4(variance));
}
