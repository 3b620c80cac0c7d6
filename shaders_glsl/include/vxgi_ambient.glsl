// vxgi_ambient.glsl: deferred lighting's use of the VXGI cone-traced light (passes/vxgi_cone_trace.cpp). Inside
// the grid the traced irradiance and reflection radiance replace the environment's SH irradiance and radiance
// lookups in shadeSurface's ambient term: this returns the difference to add to shadeSurface's result, through the
// same ambientReflected (surface_lighting.glsl; linear in the light, so the environment's part cancels exactly),
// so shadeSurface itself stays shared with the transparency pass unchanged. The clearcoat reflects the traced
// specular cone (there is no separate cone at the coat's roughness).
#ifndef IDK_VXGI_AMBIENT_GLSL
#define IDK_VXGI_AMBIENT_GLSL
#include "surface_lighting.glsl"
#include "vxgi_types.h"

// The difference for traced irradiance `tracedIrradiance` and reflection radiance `tracedSpecular` (also the
// forward pass of transparent surfaces, transparency/forward_body.h, which traces them per fragment).
vec3 vxgiAmbientDeltaOf(GpuFrame f, vec3 tracedIrradiance, vec3 tracedSpecular, vec3 n, vec3 v, vec3 baseColor,
                        float metallic, float roughness, float occlusion, SurfaceLayers layers) {
    vec3 r = reflect(-v, coatNormal(layers, n));  // the coat's reflection, as shadeSurface's (cancels exactly)
    float cr = clamp(layers.clearcoatRoughness, kMinRoughness, 1.0);
    // KHR_materials_anisotropy: the lookup shadeSurface subtracts (rms roughness, bent reflection) cancels exactly.
    float ambientRoughness = anisotropicRoughness(layers, roughness);
    vec3 rBase = anisotropicReflection(layers, n, v, clamp(roughness, kMinRoughness, 1.0));
    vec3 environmentSpecular =
        environmentRadiance(f, rBase, environmentLod(f, clamp(ambientRoughness, kMinRoughness, 1.0)));
    vec3 environmentCoat = environmentRadiance(f, r, environmentLod(f, cr));
    return ambientReflected(layers, n, v, baseColor, metallic, roughness, tracedIrradiance - shIrradiance(f, n),
                            tracedSpecular - environmentSpecular, tracedSpecular - environmentCoat) *
           occlusion;
}

vec3 vxgiAmbientDelta(GpuFrame f, uint diffuseImage, uint specularImage, ivec2 pixel, vec3 n, vec3 v,
                      vec3 baseColor, float metallic, float roughness, float occlusion, SurfaceLayers layers) {
    if (diffuseImage == kNoVxgi) return vec3(0.0);
    vec4 traced = imageLoad(gImagesRgba16f[diffuseImage], pixel);
    if (traced.a <= 0.0) return vec3(0.0);  // outside the grid
    vec3 tracedSpecular = imageLoad(gImagesRgba16f[specularImage], pixel).rgb;
    return vxgiAmbientDeltaOf(f, traced.rgb, tracedSpecular, n, v, baseColor, metallic, roughness, occlusion, layers);
}

#endif
