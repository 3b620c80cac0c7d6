#version 460
// lighting.comp.glsl: deferred shading of every G-buffer pixel with geometry (depth < 1): glTF metallic-
// roughness BRDF for each punctual light, ambient from the environment (SH9 diffuse irradiance + a
// roughness-blurred radiance lookup with the split-sum environment BRDF, both times occlusion), plus emission;
// point-light cube shadows (include/surface_lighting.glsl holds the shading core, shared with transparency).
// Ports IDKEngine's DeferredLighting/fragment.glsl as a compute pass (reference 2.19) without its bugs.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "color.glsl"
#include "surface_lighting.glsl"
#include "vrs_rates.glsl"
#include "vxgi_ambient.glsl"
#include "ssr_specular.glsl"

layout(local_size_x = kLightingGroupSize, local_size_y = kLightingGroupSize) in;
layout(push_constant, scalar) uniform Push { LightingPush p; };

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    gPtAlbedoTables = f.albedoTables;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!vrsAnchorOfInvocation(p.vrsRates, pixel)) return;  // software VRS: vrs/reconstruct.comp fills the rest
    if (any(greaterThanEqual(uvec2(pixel), f.extent))) return;
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    if (depth >= 1.0) return;  // background: the sky pass writes it

    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, depth, 1.0);
    vec4 hNear = f.inverseViewProjection * vec4(ndc, 0.0, 1.0);
    vec3 position = h.xyz / h.w;
    vec3 v = normalize(hNear.xyz / hNear.w - position);  // towards the eye (also right for orthographic views)

    vec3 baseColor = srgbDecode(imageLoad(gImagesRgba8[p.albedo], pixel).rgb);
    vec3 n = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r));
    vec4 mro = imageLoad(gImagesRgba8[p.material], pixel);
    float metallic = mro.r, roughness = mro.g, occlusion = mro.b;
    if (p.ambientOcclusion != kLightingNoAo) occlusion *= imageLoad(gImagesR32f[p.ambientOcclusion], pixel).r;  // SSAO
    if (mro.a < 0.5) {  // KHR_materials_unlit
        imageStore(gImagesRgba16f[p.target], pixel, vec4(baseColor, 1.0));
        return;
    }

    vec4 emissive = imageLoad(gImagesRgba16f[p.emissive], pixel);
    uint layered = uint(emissive.a + 0.5);  // 1 + material index for materials with BSDF extensions, else 0
    SurfaceLayers layers = layered > 0u && p.materials != 0 ? materialLayers(MaterialBuffer(p.materials).data[layered - 1u])
                                                            : noLayers();
    vec3 radiance = emissive.rgb;
    gShadowPixel = pixel;  // ray-traced shadows read their mask here (include/rt_shadows.glsl)
    radiance += shadeSurface(f, p.pointShadows, position, n, v, baseColor, metallic, roughness, occlusion, layers);
    radiance += vxgiAmbientDelta(f, p.vxgiDiffuse, p.vxgiSpecular, pixel, n, v, baseColor, metallic, roughness,
                                 occlusion);  // inside the VXGI grid: traced light replaces the SH ambient
    radiance += ssrSpecularDelta(f, p.ssr, p.vxgiDiffuse, p.vxgiSpecular, pixel, n, v, baseColor, metallic, roughness,
                                 occlusion, layers);  // --ssr: on-screen reflections replace the specular ambient

    imageStore(gImagesRgba16f[p.target], pixel, vec4(radiance, 1.0));  // alpha 1: geometry
}
