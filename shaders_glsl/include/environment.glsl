// environment.glsl: the equirectangular environment (engine/render/environment.cpp uses the same mapping):
// direction <-> uv, SH9 diffuse irradiance, and a roughness-blurred radiance lookup from the box-filtered mip
// chain. IDKEngine's rasterizer has no IBL (reference section 5); this is the ambient term the issue asks for.
#ifndef IDK_ENVIRONMENT_GLSL
#define IDK_ENVIRONMENT_GLSL
#include "bindless.glsl"
#include "deferred_types.h"

// u = 0.5 looks down -Z, v = 0 is straight up (+Y): dir = (sin t sin p, cos t, -sin t cos p), p = 2 pi (u - 0.5),
// t = pi v.
vec2 equirectUv(vec3 dir) {
    float phi = atan(dir.x, -dir.z);
    float theta = acos(clamp(dir.y, -1.0, 1.0));
    return vec2(phi * (0.5 / 3.14159265358979) + 0.5, theta * (1.0 / 3.14159265358979));
}

vec3 shIrradiance(GpuFrame f, vec3 n) {
    vec3 e = f.irradianceSh[0] + f.irradianceSh[1] * n.y + f.irradianceSh[2] * n.z + f.irradianceSh[3] * n.x +
             f.irradianceSh[4] * (n.x * n.y) + f.irradianceSh[5] * (n.y * n.z) +
             f.irradianceSh[6] * (3.0 * n.z * n.z - 1.0) + f.irradianceSh[7] * (n.x * n.z) +
             f.irradianceSh[8] * (n.x * n.x - n.y * n.y);
    return max(e, vec3(0.0));  // SH9 rings below zero opposite a bright sun
}

// The sampler repeats in both axes (right for u); v is clamped to the centre of the first and last rows of the
// coarser mip used, so bilinear filtering never blends the zenith with the nadir.
vec3 environmentRadiance(GpuFrame f, vec3 dir, float lod) {
    vec2 uv = equirectUv(dir);
    float rows = max(1.0, f.environmentHeight / exp2(ceil(lod)));
    uv.y = clamp(uv.y, 0.5 / rows, 1.0 - 0.5 / rows);
    vec3 c = textureLod(sampler2D(gTextures2D[nonuniformEXT(f.environmentTexture)], gSamplers[f.environmentSampler]),
                        uv, lod).rgb;
    return c * f.environmentIntensity;
}

// Mip level whose texels span the GGX lobe of the reflected direction: the half-vector lobe's half width at
// half maximum is about atan(0.64 alpha), the reflected lobe twice that; full width = 4 atan(0.64 alpha),
// divided by the angle of one mip-0 texel (2 pi / width). A box-filtered mip stands in for a GGX-prefiltered
// one (documented approximation; a prefiltered cube is the upgrade path).
float environmentLod(GpuFrame f, float perceptualRoughness) {
    float alpha = perceptualRoughness * perceptualRoughness;
    float texels = 4.0 * atan(0.64 * alpha) * f.environmentWidth / (2.0 * 3.14159265358979);
    return clamp(log2(max(texels, 1.0)), 0.0, f.environmentMaxLod);
}

#endif
