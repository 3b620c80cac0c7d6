// screen_transmission.glsl: KHR_materials_transmission (+ _ior, _volume, _dispersion) in the rasterizer, screen-space:
// the light a transmissive surface sends to the eye is its reflected lobes (surface_lighting.glsl's shadeSurface with
// the diffuse lobes scaled by 1 - transmission, as the glTF BSDF mixes them) plus the lit opaque frame behind it.
// The view ray refracts through the surface: thin-walled (no volume) it goes straight through; with a volume it
// bends at the IOR (per channel with dispersion, shared/pt_dispersion.h's IOR) and leaves the volume after
// thicknessFactor (x thicknessTexture G) along the refracted direction, in the instance's scale. That exit point is
// projected to the screen and the opaque colour chain (transmission/downsample.comp) read there, at a level growing
// with roughness scaled by clamp(2 ior - 2, 0, 1) (the extension's reference renderer does the same); off screen or
// behind the camera, the environment in that direction at the roughness's level. The colour is tinted by the base
// colour and by Beer-Lambert over the thickness, and weighted by transmission (1 - metallic) (1 - E_s), E_s the
// split-sum albedo of the dielectric specular the deferred pass reflects with (the weight its diffuse gets too).
// Screen space cannot see what the frame does not hold: surfaces behind the exit point that are hidden or off
// screen, other transmissive surfaces (they refract only the opaque frame), the back wall's second refraction
// (one interface, a straight exit), and light focused through glass onto other surfaces (no caustics). Not in
// IDKEngine (its rasterizer has no transmission).
#ifndef IDK_SCREEN_TRANSMISSION_GLSL
#define IDK_SCREEN_TRANSMISSION_GLSL
#include "surface_lighting.glsl"
#include "environment.glsl"
#include "pt_dispersion.h"
#include "transmission_types.h"
#include "storage_bilinear.glsl"

// The chain's level k: ceil-halved k times from the frame size.
uvec2 transmissionLevelSize(uvec2 extent, uint level) {
    uvec2 s = extent;
    for (uint k = 0u; k < level; ++k) s = max((s + 1u) / 2u, uvec2(1u));
    return s;
}

// The opaque colour at screen uv, trilinear between the chain's levels around lod (bilinear in each with storage
// loads, see passes/transmission.cpp for why; a real GPU would sample one mipmapped image through a linear sampler).
vec3 opaqueColorAt(GpuFrame f, TransmissionPush tp, vec2 uv, float lod) {
    float l = clamp(lod, 0.0, float(tp.levelCount - 1u));
    uint l0 = uint(floor(l)), l1 = min(l0 + 1u, tp.levelCount - 1u);
    uvec2 s0 = transmissionLevelSize(f.extent, l0), s1 = transmissionLevelSize(f.extent, l1);
    vec3 a = storageBilinear(tp.levels[l0], uv * vec2(s0), s0);
    vec3 b = storageBilinear(tp.levels[l1], uv * vec2(s1), s1);
    return mix(a, b, l - float(l0));
}

// What the view ray (towards -v) refracted at `ior` sees: the opaque frame at its exit point, or the environment.
// travelled: the distance inside the volume (Beer-Lambert).
vec3 refractedRadiance(GpuFrame f, TransmissionPush tp, vec3 position, vec3 n, vec3 v, float ior, vec3 thickness,
                       float lod, float envLod, out float travelled) {
    vec3 d = thickness == vec3(0.0) ? -v : normalize(refract(-v, n, 1.0 / ior));
    vec3 offset = normalize(d) * thickness;  // thickness in the instance's scale, per axis
    travelled = length(offset);
    vec4 clip = f.viewProjection * vec4(position + offset, 1.0);
    if (clip.w > 1e-6) {
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))))
            return opaqueColorAt(f, tp, uv, lod);
    }
    return environmentRadiance(f, d, envLod);
}

// Radiance of a transmissive surface towards v. texels: transmissionTexture R, thicknessTexture G.
vec3 shadeTransmissive(GpuFrame f, uint64_t pointShadows, TransmissionPush tp, GpuInstance instance, GpuMaterial m,
                       vec3 position, vec3 n, vec3 v, vec3 baseColor, float metallic, float roughness, float occlusion,
                       SurfaceLayers layers, vec2 texels) {
    float t = tp.levelCount == 0u ? 0.0 : clamp(m.transmission * texels.x, 0.0, 1.0);
    // The diffuse lobes are linear in the base and diffuse-transmission colours and the dielectric specular does
    // not depend on them, so the dielectric's mix(diffuse, transmission, t) reflects what shadeSurface gives for the
    // colours scaled by 1 - t; metals do not transmit (the glTF mix(dielectric, metal, metallic)).
    SurfaceLayers dielectric = layers;
    dielectric.diffuseTransmissionColor *= 1.0 - t;
    vec3 radiance = shadeSurface(f, pointShadows, position, n, v, baseColor * (1.0 - t), 0.0, roughness, occlusion,
                                 dielectric);
    if (metallic > 0.0)
        radiance = mix(radiance, shadeSurface(f, pointShadows, position, n, v, baseColor, 1.0, roughness, occlusion,
                                              layers), metallic);
    if (t <= 0.0 || metallic >= 1.0) return radiance;

    float r = clamp(roughness, kMinRoughness, 1.0);
    vec3 specularAlbedo = ambientSpecularAlbedo(layers, baseColor, 0.0, r, n, v);
    vec3 weight = t * (1.0 - metallic) * (1.0 - clamp(specularAlbedo, 0.0, 1.0)) * baseColor;
    float NdotV = max(dot(n, v), 1e-4);
    if ((layers.flags & kMaterialSheen) != 0u)
        weight *= max(1.0 - maxOf(layers.sheenColor) * ptAlbedoSheen(NdotV, layers.sheenRoughness), 0.0);
    if ((layers.flags & kMaterialClearcoat) != 0u)
        weight *= 1.0 - layers.clearcoat * fresnelSchlick(vec3(0.04), max(dot(coatNormal(layers, n), v), 1e-4)).x;

    bool volume = (m.flags & kMaterialVolume) != 0u;
    vec3 scale = vec3(length(instance.model[0].xyz), length(instance.model[1].xyz), length(instance.model[2].xyz));
    vec3 thickness = volume ? m.thickness * texels.y * scale : vec3(0.0);
    float lod = log2(float(max(f.extent.x, f.extent.y))) * roughness * clamp(2.0 * m.ior - 2.0, 0.0, 1.0);
    float envLod = environmentLod(f, r);
    vec3 behind;
    float travelled = 0.0;
    if (volume && (m.flags & kMaterialDispersion) != 0u && m.dispersion > 0.0) {
        // KHR_materials_dispersion: each channel at the IOR of the wavelength it stands for, at its own exit point.
        for (uint c = 0u; c < 3u; ++c) {
            float iorC = ptDispersionIor(m.ior, m.dispersion, ptChannelWavelength(c));
            float travelledC;
            behind[c] = refractedRadiance(f, tp, position, n, v, iorC, thickness, lod, envLod, travelledC)[c];
            if (c == 1u) travelled = travelledC;
        }
    } else {
        behind = refractedRadiance(f, tp, position, n, v, max(m.ior, 1.0), thickness, lod, envLod, travelled);
    }
    if (volume && m.attenuationDistance > 0.0)  // Beer-Lambert: attenuationColor at attenuationDistance
        behind *= exp(log(max(m.attenuationColor, vec3(1e-6))) * (travelled / m.attenuationDistance));
    return radiance + weight * behind;
}

#endif
