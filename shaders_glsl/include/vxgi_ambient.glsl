// vxgi_ambient.glsl: deferred lighting's use of the VXGI cone-traced light (passes/vxgi_cone_trace.cpp). Inside
// the grid the traced irradiance and reflection radiance replace the environment's SH irradiance and radiance
// lookup in shadeSurface's ambient term: this returns the difference to add to shadeSurface's result (the same
// formula, (1 - E_s) c_diff / pi E + L E_s, times occlusion), so shadeSurface itself stays shared with the
// transparency pass unchanged.
#ifndef IDK_VXGI_AMBIENT_GLSL
#define IDK_VXGI_AMBIENT_GLSL
#include "pbr.glsl"
#include "environment.glsl"
#include "vxgi_types.h"

vec3 vxgiAmbientDelta(GpuFrame f, uint diffuseImage, uint specularImage, ivec2 pixel, vec3 n, vec3 v,
                      vec3 baseColor, float metallic, float roughness, float occlusion) {
    if (diffuseImage == kNoVxgi) return vec3(0.0);
    vec4 traced = imageLoad(gImagesRgba16f[diffuseImage], pixel);
    if (traced.a <= 0.0) return vec3(0.0);  // outside the grid
    vec3 tracedSpecular = imageLoad(gImagesRgba16f[specularImage], pixel).rgb;
    float NdotV = max(dot(n, v), 1e-4);
    float r = clamp(roughness, kMinRoughness, 1.0);
    vec3 specularAlbedo = environmentBrdfApprox(specularF0(baseColor, metallic), r, NdotV);
    vec3 diffuseWeight = (1.0 - clamp(specularAlbedo, 0.0, 1.0)) * baseColor * (1.0 - metallic) / kPi;
    vec3 environmentSpecular = environmentRadiance(f, reflect(-v, n), environmentLod(f, r));
    return ((traced.rgb - shIrradiance(f, n)) * diffuseWeight + (tracedSpecular - environmentSpecular) * specularAlbedo) *
           occlusion;
}

#endif
