// surface_lighting.glsl: the radiance a surface point sends towards the eye, shared by the deferred lighting pass
// and the forward transparency pass so both shade alike: the glTF BRDF for every punctual light (times its
// shadow visibility when it casts one: cube, cascades or spot map), plus ambient from the environment (SH9 diffuse irradiance and the
// split-sum specular lookup, both times occlusion). Ports IDKEngine's DeferredLighting/fragment.glsl shading core.
#ifndef IDK_SURFACE_LIGHTING_GLSL
#define IDK_SURFACE_LIGHTING_GLSL
#include "scene_buffers.glsl"
#include "material_layers.glsl"
#include "environment.glsl"
#include "shadows.glsl"
#include "light_shadows.glsl"
#include "rt_shadows.glsl"

// The ambient light reflected towards v (before occlusion), from the irradiance E on n and the radiance arriving
// along the reflection at the base layer's roughness (specular) and at the clearcoat's (coat); roughness: the
// material's perceptual roughness (anisotropic materials: ambientSpecularAlbedo takes their rms and E itself). Specular: split-sum,
// the radiance times the directional albedo E_s = f0 A + f90 B with the multiple-scattering factor
// (material_layers.glsl). Diffuse: c_diff / pi * E, weighted by (1 - E_s) as the direct term's (1 - F), so a white
// surface in a constant environment reflects exactly the environment (the furnace test checks it). Sheen and
// clearcoat: their albedo at n.v times E / pi (sheen) or the coat radiance (coat), the layers beneath scaled as in
// direct light. Linear in (E, specular, coat): shadeSurface feeds it the environment's light, VXGI
// (vxgi_ambient.glsl) the difference of its cone-traced light to that, so swapping the two cancels exactly.
vec3 ambientReflected(SurfaceLayers layers, vec3 n, vec3 v, vec3 baseColor, float metallic, float roughness,
                      vec3 irradiance, vec3 specularRadiance, vec3 coatRadiance) {
    float NdotV = max(dot(n, v), 1e-4);
    float r = clamp(roughness, kMinRoughness, 1.0);
    vec3 specularAlbedo = ambientSpecularAlbedo(layers, baseColor, metallic, r, n, v);
    vec3 diffuse = (1.0 - clamp(specularAlbedo, 0.0, 1.0)) * baseColor * (1.0 - metallic) / kPi * irradiance;
    if ((layers.flags & kMaterialDiffuseTransmission) != 0u) diffuse *= 1.0 - layers.diffuseTransmission;
    vec3 ambient = diffuse + specularRadiance * specularAlbedo;
    if ((layers.flags & kMaterialSheen) != 0u) {
        float sheenAlbedo = ptAlbedoSheen(NdotV, layers.sheenRoughness);
        ambient = ambient * max(1.0 - maxOf(layers.sheenColor) * sheenAlbedo, 0.0) +
                  layers.sheenColor * sheenAlbedo * irradiance / kPi;
    }
    if ((layers.flags & kMaterialClearcoat) != 0u) {
        float NdotVc = max(dot(coatNormal(layers, n), v), 1e-4);  // the coat's own normal (clearcoatNormalTexture)
        float cr = clamp(layers.clearcoatRoughness, kMinRoughness, 1.0);
        float coat = layers.clearcoat * fresnelSchlick(vec3(0.04), NdotVc).x;
        vec3 coatAlbedo = layers.clearcoat * environmentBrdfApprox(vec3(0.04), cr, NdotVc);
        ambient = ambient * (1.0 - coat) + coatRadiance * coatAlbedo;
    }
    return ambient;
}

// KHR_materials_diffuse_transmission (thin-surface approximation, material_layers.glsl): the irradiance E from
// behind (SH on -n) through the surface, with the punctual lobe's weight W(n.v, mu) (dielectricDiffuseWeight, the
// path tracers' ptDiffuseWeight) integrated over the hemisphere behind: the cosine-weighted mean of 1 - Es(mu) is
// 1 - Es_avg, W's denominator, so E takes (1 - Es(n.v)) exactly, as the reflected split-sum diffuse takes its
// 1 - E_s in front (exact for uniform light behind; SH light that varies over the hemisphere would weight the
// grazing directions a little less). The sheen and coat layers above as in direct light. Only the SH ambient:
// VXGI and SSR replace the reflected side's light, not this. w: the punctual lobe's (surfaceDiffuseWeightView).
vec3 ambientTransmitted(SurfaceLayers layers, DiffuseWeightView w, vec3 n, vec3 v, float metallic,
                        vec3 irradianceBehind) {
    if ((layers.flags & kMaterialDiffuseTransmission) == 0u) return vec3(0.0);
    float NdotV = max(dot(n, v), 1e-4);
    float pass = metallic < 1.0 ? w.view : 0.0;
    vec3 t = layers.diffuseTransmissionColor * (layers.diffuseTransmission * (1.0 - metallic) / kPi * pass) *
             irradianceBehind;
    if ((layers.flags & kMaterialSheen) != 0u)
        t *= max(1.0 - maxOf(layers.sheenColor) * ptAlbedoSheen(NdotV, layers.sheenRoughness), 0.0);
    if ((layers.flags & kMaterialClearcoat) != 0u) t *= 1.0 - layers.clearcoat * fresnelSchlick(vec3(0.04), NdotV).x;
    return t;
}

// n: unit shading normal on the viewer's side; v: unit direction to the eye. pointShadows: GpuPointShadow[] per
// light, or 0 when no light casts a shadow. layers: the material's extensions (noLayers() for none).
vec3 shadeSurface(GpuFrame f, uint64_t pointShadows, vec3 position, vec3 n, vec3 v, vec3 baseColor, float metallic,
                  float roughness, float occlusion, SurfaceLayers layers) {
    vec3 radiance = vec3(0.0);
    // The diffuse weight's light-independent part, hoisted out of the light loop (material_layers.glsl).
    DiffuseWeightView diffuseWeight = surfaceDiffuseWeightView(layers, roughness, n, v);
    LightBuffer lights = LightBuffer(f.lights);
    for (uint i = 0; i < f.lightCount; ++i) {
        vec3 l;
        vec3 incident = lightIncidence(lights.data[i], position, l);
        vec3 direct = layeredBrdfCosine(layers, diffuseWeight, baseColor, metallic, roughness, n, v, l) * incident;
        if (pointShadows != 0 && any(greaterThan(direct, vec3(0.0)))) {
            GpuPointShadow s = PointShadowBuffer(pointShadows).data[i];
            vec3 ns = dot(n, l) < 0.0 ? -n : n;  // diffuse transmission: the lit side is the back, offset toward it
            if (s.mapCount != 0u) direct *= mapShadowVisibility(pointShadows, s, position, ns, l);
            else if (s.cube == kRayTracedShadow) direct *= rtShadowVisibility(pointShadows, s);
            else if (s.cube != kNoShadow) direct *= pointShadowVisibility(s, position, ns, l);
        }
        radiance += direct;
    }

    float cr = clamp(layers.clearcoatRoughness, kMinRoughness, 1.0);
    vec3 r = reflect(-v, coatNormal(layers, n));  // the coat's reflection
    // KHR_materials_anisotropy: the isotropic split-sum at the rms roughness along the bent reflection.
    float ambientRoughness = anisotropicRoughness(layers, roughness);
    vec3 rBase = anisotropicReflection(layers, n, v, clamp(roughness, kMinRoughness, 1.0));
    vec3 ambient = ambientReflected(layers, n, v, baseColor, metallic, roughness, shIrradiance(f, n),
                                    environmentRadiance(f, rBase,
                                                        environmentLod(f, clamp(ambientRoughness, kMinRoughness, 1.0))),
                                    environmentRadiance(f, r, environmentLod(f, cr)));
    ambient += ambientTransmitted(layers, diffuseWeight, n, v, metallic, shIrradiance(f, -n));
    return radiance + ambient * occlusion;
}

#endif
