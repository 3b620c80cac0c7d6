// deferred_lighting_pixel.glsl: the radiance of one G-buffer pixel with geometry, shared by the compute lighting
// pass (deferred_lighting/lighting.comp) and the hardware-VRS fragment pass (vrs/lighting_rate.frag), so every VRS
// rung shades a pixel identically.
#ifndef IDK_DEFERRED_LIGHTING_PIXEL_GLSL
#define IDK_DEFERRED_LIGHTING_PIXEL_GLSL
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "color.glsl"
#include "surface_lighting.glsl"
#include "vxgi_ambient.glsl"
#include "ssr_specular.glsl"
#include "gbuffer_anisotropy.glsl"
#include "gbuffer_layer_bits.glsl"

// False for background pixels (depth 1: the sky writes them); else the radiance, alpha 1 (geometry).
bool deferredLightingPixel(LightingPush p, GpuFrame f, ivec2 pixel, out vec4 result) {
    result = vec4(0.0);
    gPtAlbedoTables = f.albedoTables;
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    if (depth >= 1.0) return false;

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
        result = vec4(baseColor, 1.0);
        return true;
    }

    vec4 emissive = imageLoad(gImagesRgba16f[p.emissive], pixel);
    uint layered = uint(emissive.a + 0.5);  // 1 + material index for materials with BSDF extensions, else 0
    SurfaceLayers layers = layered > 0u && p.materials != 0 ? materialLayers(MaterialBuffer(p.materials).data[layered - 1u])
                                                            : noLayers();
    if (layered > 0u && p.layers != kLightingNoLayers) {  // the extension textures' texels (gbuffer_fragment.glsl)
        uvec4 packed = imageLoad(gImagesRgba32ui[p.layers], pixel);
        vec4 scalars = unpackUnorm4x8(packed.x);
        vec4 specularColorT = unpackUnorm4x8(packed.y), sheenColorT = unpackUnorm4x8(packed.z);
        GpuMaterial material = MaterialBuffer(p.materials).data[layered - 1u];
        vec2 alphas = vec2(specularColorT.a, sheenColorT.a);  // gbuffer_layer_bits.glsl says what they hold
        // The spill target (allocated for scenes whose materials combine more texels than `packed` holds).
        const bool haveSpill = p.layerSpill != kLightingNoLayers;
        uvec2 spill = haveSpill ? imageLoad(gImagesRg32ui[p.layerSpill], pixel).xy : uvec2(0u);
        float diffTransT;
        vec3 diffTransColorT;
        unpackDiffuseTransmissionTexels(material.flags, alphas, packed.w, haveSpill, spill.x, diffTransT,
                                        diffTransColorT);
        LayerTexels t = LayerTexels(scalars.x, srgbDecode(specularColorT.rgb), scalars.y, scalars.z,
                                    srgbDecode(sheenColorT.rgb), scalars.w, diffTransT, srgbDecode(diffTransColorT));
        layers = texturedLayers(layers, t);
        layers = withIridescenceTexels(layers, material, alphas);
        if (layerBitsHoldCoatNormal(material.flags))  // the coat's own normal
            layers.clearcoatNormal = octDecode(unpackCoatNormalOct(packed.w));
        layers = withAnisotropyStrengthTexel(layers, unpackAnisotropyStrengthTexel(material.flags, packed.w));
        // KHR_materials_anisotropy: the direction the G-buffer stored (none: the isotropic lobe at the rms alpha).
        if (layers.anisotropyStrength > 0.0 && layerBitsHoldAnisotropyDirection(material.flags))
            layers.anisotropyDirection = decodeAnisotropyDirection(packed.w & 0xFFFFu, n);
        else if (layers.anisotropyStrength > 0.0 && haveSpill && layerBitsSpillAnisotropyDirection(material.flags))
            layers.anisotropyDirection = decodeAnisotropyDirection(spill.y, n);
    }
    vec3 radiance = emissive.rgb;
    gShadowPixel = pixel;  // ray-traced shadows read their mask here (include/rt_shadows.glsl)
    radiance += shadeSurface(f, p.pointShadows, position, n, v, baseColor, metallic, roughness, occlusion, layers);
    radiance += vxgiAmbientDelta(f, p.vxgiDiffuse, p.vxgiSpecular, pixel, n, v, baseColor, metallic, roughness,
                                 occlusion, layers);  // inside the VXGI grid: traced light replaces the SH ambient
    radiance += ssrSpecularDelta(f, p.ssr, p.vxgiDiffuse, p.vxgiSpecular, pixel, n, v, baseColor, metallic, roughness,
                                 occlusion, layers);  // --ssr: on-screen reflections replace the specular ambient
    result = vec4(radiance, 1.0);
    return true;
}

#endif
