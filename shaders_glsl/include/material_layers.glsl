// material_layers.glsl: the rasterizer's side of the BSDF material extensions (KHR_materials_specular,
// _clearcoat, _sheen; the path tracers' side is shared/pt_bsdf_frame.h, whose lobe formulas these follow with the
// raster's Schlick Fresnel of f0 0.04), and the split-sum energy compensation. Direct light per punctual light:
//   coat   clearcoat * Fc(v.h) * D V (coat roughness) + (1 - clearcoat * Fc(n.v)) * [ sheen + base ]
//   sheen  sheenColor * Charlie D * V (shared/pt_sheen.h) + (1 - max(sheenColor) E_sheen(n.v)) * base
//   base   specular: F = f0 + (f90 - f0)(1 - v.h)^5 with f0 = mix(min(0.04 specularColor, 1) specular,
//          baseColor, metallic), f90 = mix(specular, 1, metallic); diffuse weighted 1 - max(F_dielectric)
// A material without extension flags takes pbr.glsl's brdfCosine unchanged (tests/support/pbr_oracle.cpp).
// Ambient: the split-sum E_s = f0 A + f90 B with A + B = E(n.v), the GGX directional albedo of the path tracer's
// tables (shared/pt_albedo_tables.h), times Turquin's multiple-scattering factor 1 + f0 (1 / E - 1), so a white
// rough metal in a uniform environment reflects it all, as the path tracer's compensation makes it.
#ifndef IDK_MATERIAL_LAYERS_GLSL
#define IDK_MATERIAL_LAYERS_GLSL
#include "pbr.glsl"
#include "pt_energy.h"
#include "pt_sheen.h"

struct SurfaceLayers {
    uint flags;  // kMaterialSpecular | kMaterialClearcoat | kMaterialSheen
    float specular;
    vec3 specularColor;
    float clearcoat;
    float clearcoatRoughness;
    vec3 sheenColor;
    float sheenRoughness;
};

SurfaceLayers noLayers() { return SurfaceLayers(0u, 1.0, vec3(1.0), 0.0, 0.0, vec3(0.0), 0.0); }

SurfaceLayers materialLayers(GpuMaterial m) {
    return SurfaceLayers(m.flags & kMaterialLayers, clamp(m.specular, 0.0, 1.0), max(m.specularColor, vec3(0.0)),
                         clamp(m.clearcoat, 0.0, 1.0), clamp(m.clearcoatRoughness, 0.0, 1.0),
                         clamp(m.sheenColor, vec3(0.0), vec3(1.0)), clamp(m.sheenRoughness, 0.0, 1.0));
}

// The extension textures' channels at a fragment (matA): specularTexture A, specularColorTexture RGB (linear,
// decoded from sRGB), clearcoatTexture R, clearcoatRoughnessTexture G, sheenColorTexture RGB, sheenRoughnessTexture
// A; 1 where a material has no such texture (white placeholder slots).
struct LayerTexels {
    float specular;
    vec3 specularColor;
    float clearcoat;
    float clearcoatRoughness;
    vec3 sheenColor;
    float sheenRoughness;
};

LayerTexels noLayerTexels() { return LayerTexels(1.0, vec3(1.0), 1.0, 1.0, vec3(1.0), 1.0); }

// The factors times the texels, as pathtrace::evaluateMaterial and wfEvaluateMaterial scale them.
SurfaceLayers texturedLayers(SurfaceLayers s, LayerTexels t) {
    s.specular = clamp(s.specular * t.specular, 0.0, 1.0);
    s.specularColor = max(s.specularColor * t.specularColor, vec3(0.0));
    s.clearcoat = clamp(s.clearcoat * t.clearcoat, 0.0, 1.0);
    s.clearcoatRoughness = clamp(s.clearcoatRoughness * t.clearcoatRoughness, 0.0, 1.0);
    s.sheenColor = clamp(s.sheenColor * t.sheenColor, vec3(0.0), vec3(1.0));
    s.sheenRoughness = clamp(s.sheenRoughness * t.sheenRoughness, 0.0, 1.0);
    return s;
}

vec3 layeredF0(SurfaceLayers s, vec3 baseColor, float metallic) {
    return mix(min(vec3(0.04) * s.specularColor, vec3(1.0)) * s.specular, baseColor, metallic);
}

float maxOf(vec3 c) { return max(c.r, max(c.g, c.b)); }

// f(l, v) * NdotL with the material's extension layers.
vec3 layeredBrdfCosine(SurfaceLayers s, vec3 baseColor, float metallic, float perceptualRoughness, vec3 n, vec3 v,
                       vec3 l) {
    if (s.flags == 0u) return brdfCosine(baseColor, metallic, perceptualRoughness, n, v, l);
    float NdotL = dot(n, l);
    if (NdotL <= 0.0) return vec3(0.0);
    float NdotV = max(dot(n, v), 1e-4);
    vec3 h = normalize(l + v);
    float NdotH = max(dot(n, h), 0.0);
    float VdotH = max(dot(v, h), 0.0);
    float roughness = clamp(perceptualRoughness, kMinRoughness, 1.0);
    float alpha = roughness * roughness;
    float m5 = pow(1.0 - VdotH, 5.0);
    vec3 f0d = min(vec3(0.04) * s.specularColor, vec3(1.0)) * s.specular;
    vec3 fDielectric = f0d + (vec3(s.specular) - f0d) * m5;
    vec3 F = mix(fDielectric, baseColor + (1.0 - baseColor) * m5, metallic);
    vec3 diffuse = (1.0 - maxOf(fDielectric)) * baseColor * (1.0 - metallic) / kPi;
    vec3 result = diffuse + F * distributionGgx(NdotH, alpha) * visibilitySmithGgxCorrelated(NdotL, NdotV, alpha);
    if ((s.flags & kMaterialSheen) != 0u) {
        float sheenAlpha = ptSheenAlpha(s.sheenRoughness);
        result *= max(1.0 - maxOf(s.sheenColor) * ptAlbedoSheen(NdotV, s.sheenRoughness), 0.0);
        float vis = 1.0 / ((1.0 + ptSheenLambda(NdotV, sheenAlpha) + ptSheenLambda(NdotL, sheenAlpha)) * 4.0 * NdotV *
                           NdotL);
        result += s.sheenColor * (ptSheenD(NdotH, sheenAlpha) * vis);
    }
    if ((s.flags & kMaterialClearcoat) != 0u) {
        float coatRoughness = clamp(s.clearcoatRoughness, kMinRoughness, 1.0);
        float coatAlpha = coatRoughness * coatRoughness;
        result *= 1.0 - s.clearcoat * fresnelSchlick(vec3(0.04), NdotV).x;
        result += vec3(s.clearcoat * fresnelSchlick(vec3(0.04), VdotH).x * distributionGgx(NdotH, coatAlpha) *
                       visibilitySmithGgxCorrelated(NdotL, NdotV, coatAlpha));
    }
    return result * NdotL;
}

// Split-sum scale and bias (f0 A + f90 B) of environmentBrdfApprox, separately.
vec2 environmentBrdfAB(float perceptualRoughness, float NdotV) {
    vec3 e = environmentBrdfApprox(vec3(1.0), perceptualRoughness, NdotV);
    vec3 b = environmentBrdfApprox(vec3(0.0), perceptualRoughness, NdotV);
    return vec2(e.x - b.x, b.x);
}

// The ambient specular albedo of the base layer with the multiple-scattering compensation. The split-sum's
// total A + B is the tabulated GGX albedo E of the path tracer (height-correlated Smith, the same lobe the direct
// term uses), its split into the f0 and f90 parts the analytic fit's; times 1 + f0 (1 / E - 1).
vec3 ambientSpecularAlbedo(SurfaceLayers s, vec3 baseColor, float metallic, float roughness, float NdotV) {
    vec3 f0 = layeredF0(s, baseColor, metallic);
    float f90 = mix(s.specular, 1.0, metallic);
    vec2 ab = environmentBrdfAB(roughness, NdotV);
    float e = max(ptAlbedoMetal(NdotV, roughness), 0.05);
    ab *= e / max(ab.x + ab.y, 1e-4);
    vec3 albedo = f0 * ab.x + f90 * ab.y;
    return albedo * (1.0 + f0 * (1.0 / e - 1.0));
}

#endif
