// ssr_specular.glsl: deferred lighting's use of the screen-space reflections (passes/ssr.cpp). Where a mirror ray
// hit something on screen, the reflected radiance replaces the specular ambient radiance that shadeSurface (or,
// inside the VXGI grid, vxgiAmbientDelta) took from the environment or the cone-traced light, with the same BRDF
// weight (the split-sum specular albedo) and occlusion, blended by the hit's weight. Returns the difference to add,
// so shadeSurface stays shared with the transparency pass unchanged. Layered materials' sheen and clearcoat
// scaling of the base layer is not applied to the difference (a small approximation on such surfaces).
#ifndef IDK_SSR_SPECULAR_GLSL
#define IDK_SSR_SPECULAR_GLSL
#include "material_layers.glsl"
#include "environment.glsl"
#include "vxgi_types.h"
#include "ssr_types.h"

vec3 ssrSpecularDelta(GpuFrame f, uint ssrImage, uint vxgiDiffuse, uint vxgiSpecular, ivec2 pixel, vec3 n, vec3 v,
                      vec3 baseColor, float metallic, float roughness, float occlusion, SurfaceLayers layers) {
    if (ssrImage == kSsrNoImage) return vec3(0.0);
    vec4 reflected = imageLoad(gImagesRgba16f[ssrImage], pixel);
    if (reflected.a <= 0.0) return vec3(0.0);  // miss: the environment / VXGI term stays
    float r = clamp(roughness, kMinRoughness, 1.0);
    vec3 specularAlbedo = ambientSpecularAlbedo(layers, baseColor, metallic, r, n, v);
    vec3 fallback = environmentRadiance(f, reflect(-v, n), environmentLod(f, r));
    if (vxgiDiffuse != kNoVxgi && imageLoad(gImagesRgba16f[vxgiDiffuse], pixel).a > 0.0)
        fallback = imageLoad(gImagesRgba16f[vxgiSpecular], pixel).rgb;
    return (reflected.rgb - fallback) * specularAlbedo * occlusion * reflected.a;
}

#endif
