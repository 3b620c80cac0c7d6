// pbr.glsl: the glTF 2.0 metallic-roughness BRDF (glTF spec, Appendix B): Trowbridge-Reitz/GGX D, Smith
// height-correlated visibility V, F = mix(F_dielectric, Schlick(baseColor), metallic) as the spec mixes its
// dielectric and metal BRDFs, with F_dielectric the exact Fresnel of IOR 1.5 (f0 0.04; the path tracers' curve,
// shared/pt_microfacet.h, where the spec's sample code takes Schlick's: the albedo-scaled diffuse weight below is
// built from the path tracers' tables of that lobe, and a Schlick lobe beside it left a white plastic 3.7% off
// its albedo of 1 at grazing view), Lambert diffuse
// c_diff / pi with c_diff = baseColor * (1 - metallic), weighted by the caller's diffuseWeight (the albedo-scaled
// W(n.v, n.l) of material_layers.glsl, as the path tracers weight their Lambert lobe; a per-half-vector 1 - F
// reflected up to 1.27 of the light for a white plastic at grazing view). KHR_lights_punctual attenuation.
// Ports IDKEngine's include/Pbr.glsl without its bugs (no 1/pi, f0 = 0 for dielectrics; reference section 5).
// tests/support/pbr_oracle.cpp is the C++ twin the GPU output is checked against; keep them in step.
#ifndef IDK_PBR_GLSL
#define IDK_PBR_GLSL
#include "scene_types.h"
#include "pt_microfacet.h"

const float kPi = 3.14159265358979;
const float kMinRoughness = 0.045;  // perceptual; keeps D finite for roughness 0 (as Filament's MIN_ROUGHNESS)

float distributionGgx(float NdotH, float alpha) {
    float a2 = alpha * alpha;
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

// V = G / (4 NdotL NdotV) for the height-correlated Smith G (Heitz 2014), as the glTF spec writes it.
float visibilitySmithGgxCorrelated(float NdotL, float NdotV, float alpha) {
    float a2 = alpha * alpha;
    float ggxV = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
    float ggxL = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
    float sum = ggxV + ggxL;
    return sum > 0.0 ? 0.5 / sum : 0.0;
}

vec3 fresnelSchlick(vec3 f0, float VdotH) {
    float m = clamp(1.0 - VdotH, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// f(l, v) * NdotL for unit n, v, l (zero when the light is below the surface).
vec3 brdfCosine(vec3 baseColor, float metallic, float perceptualRoughness, float diffuseWeight, vec3 n, vec3 v,
                vec3 l) {
    float NdotL = dot(n, l);
    if (NdotL <= 0.0) return vec3(0.0);
    float NdotV = max(dot(n, v), 1e-4);
    vec3 h = normalize(l + v);
    float NdotH = max(dot(n, h), 0.0);
    float VdotH = max(dot(v, h), 0.0);
    float roughness = clamp(perceptualRoughness, kMinRoughness, 1.0);
    float alpha = roughness * roughness;
    vec3 F = mix(vec3(ptFresnelDielectric(VdotH, 1.5)), fresnelSchlick(baseColor, VdotH), metallic);
    vec3 diffuse = diffuseWeight * baseColor * (1.0 - metallic) / kPi;
    vec3 specular = F * distributionGgx(NdotH, alpha) * visibilitySmithGgxCorrelated(NdotL, NdotV, alpha);
    return (diffuse + specular) * NdotL;
}

// KHR_lights_punctual: direction to the light and the illuminance factor (intensity * attenuation) at p.
vec3 lightIncidence(GpuLight light, vec3 p, out vec3 l) {
    if (light.type == kLightDirectional) {
        l = -light.direction;
        return light.intensity;
    }
    vec3 toLight = light.position - p;
    float d2 = max(dot(toLight, toLight), 1e-8);
    l = toLight * inversesqrt(d2);
    float attenuation = 1.0 / d2;
    if (light.range > 0.0) {  // the extension's recommended smooth window: clamp(1 - (d/range)^4, 0, 1)^2
        float r = d2 / (light.range * light.range);
        float w = clamp(1.0 - r * r, 0.0, 1.0);
        attenuation *= w * w;
    }
    if (light.type == kLightSpot) {
        float cd = dot(light.direction, -l);
        float a = clamp(cd * light.spotScale + light.spotOffset, 0.0, 1.0);
        attenuation *= a * a;
    }
    return light.intensity * attenuation;
}

// Split-sum environment BRDF (Karis 2013, "Real Shading in Unreal Engine 4") with its analytic fit
// (Karis 2014, "Physically Based Shading on Mobile", after Lazarov 2013): f0 * A + B.
vec3 environmentBrdfApprox(vec3 f0, float perceptualRoughness, float NdotV) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = perceptualRoughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NdotV)) * r.x + r.y;
    vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
    return f0 * ab.x + ab.y;
}

#endif
