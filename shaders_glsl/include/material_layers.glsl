// material_layers.glsl: the rasterizer's side of the BSDF material extensions (KHR_materials_specular,
// _clearcoat, _sheen; the path tracers' side is shared/pt_bsdf_frame.h, whose lobe formulas these follow with the
// base dielectric's IOR fixed at 1.5), and the split-sum energy compensation. Direct light per punctual light:
//   coat   clearcoat * Fc(v.h) * D V (coat roughness) + (1 - clearcoat * Fc(n.v)) * [ sheen + base ]
//   sheen  sheenColor * Charlie D * V (shared/pt_sheen.h) + (1 - max(sheenColor) E_sheen(n.v)) * base
//   base   specular: F = mix(specular (f0' + (1 - f0') w(v.h)), Schlick(baseColor), metallic) with
//          f0' = min(0.04 specularColor, 1) and w the exact Fresnel curve of IOR 1.5 remapped to [0, 1] (the path
//          tracers' KHR_materials_specular form); diffuse weighted by the path tracers' albedo
//          scaling W = (1 - Es(n.v)) (1 - Es(n.l)) / (1 - Es_avg) (dielectricDiffuseWeight, shared/pt_energy.h),
//          Es the directional albedo of that reflection lobe from the path tracer's tables (its multiple
//          scattering included, which the raster's single-scattering lobe lacks: a white plastic reflects 1 within
//          0.23%, tests/unit/pbr/raster_plastic_test.cpp)
// A material without extension flags takes pbr.glsl's brdfCosine (tests/support/pbr_oracle.cpp).
// Ambient: the split-sum E_s = f0 A + f90 B with A + B = E(n.v), the GGX directional albedo of the path tracer's
// tables (shared/pt_albedo_tables.h), times Turquin's multiple-scattering factor 1 + f0 (1 / E - 1), so a white
// rough metal in a uniform environment reflects it all, as the path tracer's compensation makes it.
// KHR_materials_anisotropy: the base's GGX D and V become the extension's anisotropic ones (shared/pt_anisotropy.h,
// the path tracer's functions) in the frame of the anisotropy direction, which the forward pass builds from its
// tangent frame (withAnisotropyFrame). The deferred G-buffer stores no tangent, so there (and wherever no
// direction is known) an anisotropic material takes the isotropic lobe at the rms alpha sqrt((at^2 + ab^2) / 2),
// the roughness the path tracer's energy compensation reads too. Ambient: the isotropic split-sum at the rms alpha
// along the sample viewer's bent reflection vector (anisotropicReflection), an approximation of the lobe's shape.
// KHR_materials_diffuse_transmission, a thin-surface approximation: the diffuse term keeps 1 - diffuseTransmission
// of its weight and a light behind the surface (n.l < 0) gives diffuseTransmission * diffuseTransmissionColor / pi
// * W(n.v, |n.l|) * |n.l| (W the diffuse weight above), the path tracer's lobe for that light
// (shared/pt_diffuse_transmission.h); surface_lighting.glsl adds the SH irradiance from behind the same way. It
// omits what the path tracer has and one lookup per light cannot give: light scattered inside a thick volume
// (thickness, attenuation), the transmitted part of the specular ambient and of VXGI/SSR's traced light (they
// correct the reflected side only), and transmitted light from emissive surfaces.
#ifndef IDK_MATERIAL_LAYERS_GLSL
#define IDK_MATERIAL_LAYERS_GLSL
#include "pbr.glsl"
#include "pt_energy.h"
#include "pt_sheen.h"
#include "pt_anisotropy.h"

struct SurfaceLayers {
    uint flags;  // kMaterialSpecular | kMaterialClearcoat | kMaterialSheen
    float specular;
    vec3 specularColor;
    float clearcoat;
    float clearcoatRoughness;
    vec3 sheenColor;
    float sheenRoughness;
    // KHR_materials_anisotropy
    float anisotropyStrength;  // 0: isotropic
    vec3 anisotropyDirection;  // world, unit; 0: unknown (the isotropic lobe at the rms alpha)
    // KHR_materials_diffuse_transmission (read when flags has kMaterialDiffuseTransmission)
    float diffuseTransmission;
    vec3 diffuseTransmissionColor;
};

SurfaceLayers noLayers() {
    return SurfaceLayers(0u, 1.0, vec3(1.0), 0.0, 0.0, vec3(0.0), 0.0, 0.0, vec3(0.0), 0.0, vec3(1.0));
}

SurfaceLayers materialLayers(GpuMaterial m) {
    return SurfaceLayers(m.flags & (kMaterialLayers | kMaterialAnisotropy | kMaterialDiffuseTransmission),
                         clamp(m.specular, 0.0, 1.0),
                         max(m.specularColor, vec3(0.0)), clamp(m.clearcoat, 0.0, 1.0),
                         clamp(m.clearcoatRoughness, 0.0, 1.0), clamp(m.sheenColor, vec3(0.0), vec3(1.0)),
                         clamp(m.sheenRoughness, 0.0, 1.0),
                         (m.flags & kMaterialAnisotropy) != 0u ? clamp(m.anisotropyStrength, 0.0, 1.0) : 0.0,
                         vec3(0.0),
                         (m.flags & kMaterialDiffuseTransmission) != 0u ? clamp(m.diffuseTransmission, 0.0, 1.0)
                                                                         : 0.0,
                         clamp(m.diffuseTransmissionColor, vec3(0.0), vec3(1.0)));
}

// The anisotropy direction from a tangent frame (t, b: glTF's tangent and bitangent), turned by anisotropyRotation.
SurfaceLayers withAnisotropyFrame(SurfaceLayers s, GpuMaterial m, vec3 t, vec3 b) {
    if (s.anisotropyStrength > 0.0) {
        vec3 d = t * cos(m.anisotropyRotation) + b * sin(m.anisotropyRotation);
        s.anisotropyDirection = dot(d, d) > 1e-12 ? normalize(d) : vec3(0.0);
    }
    return s;
}

// alpha_t = mix(alpha, 1, strength^2) and alpha_b = alpha of KHR_materials_anisotropy.
vec2 anisotropicAlphas(SurfaceLayers s, float alpha) {
    return vec2(mix(alpha, 1.0, s.anisotropyStrength * s.anisotropyStrength), alpha);
}

// The perceptual roughness of the rms alpha (isotropic stand-in for ambient light, energy and unknown frames).
float anisotropicRoughness(SurfaceLayers s, float perceptualRoughness) {
    if (s.anisotropyStrength <= 0.0) return perceptualRoughness;
    float alpha = perceptualRoughness * perceptualRoughness;
    vec2 a = anisotropicAlphas(s, alpha);
    return sqrt(sqrt(0.5 * (a.x * a.x + a.y * a.y)));
}

// The reflection vector for the ambient lookup: the Khronos sample viewer's bent normal, tilted from n toward the
// plane across the anisotropy direction as strength grows and roughness falls.
vec3 anisotropicReflection(SurfaceLayers s, vec3 n, vec3 v, float perceptualRoughness) {
    if (s.anisotropyStrength <= 0.0 || dot(s.anisotropyDirection, s.anisotropyDirection) < 0.5) return reflect(-v, n);
    vec3 t = normalize(s.anisotropyDirection - n * dot(s.anisotropyDirection, n));
    vec3 b = cross(n, t);
    vec3 bent = cross(cross(b, v), b);
    if (dot(bent, bent) < 1e-12) return reflect(-v, n);
    float a = 1.0 - s.anisotropyStrength * (1.0 - perceptualRoughness);
    a *= a;
    a *= a;
    bent = normalize(mix(normalize(bent), n, a));
    return reflect(-v, bent);
}

// D * V of the base layer's GGX: anisotropic in the frame of the anisotropy direction, else isotropic (at the rms
// alpha when the material is anisotropic but no direction is known).
float baseDistributionVisibility(SurfaceLayers s, float alpha, vec3 n, vec3 v, vec3 l, vec3 h, float NdotL,
                                 float NdotV, float NdotH) {
    if (s.anisotropyStrength <= 0.0)
        return distributionGgx(NdotH, alpha) * visibilitySmithGgxCorrelated(NdotL, NdotV, alpha);
    vec2 a = anisotropicAlphas(s, alpha);
    vec3 d = s.anisotropyDirection - n * dot(s.anisotropyDirection, n);
    if (dot(d, d) < 1e-8) {
        float rms = sqrt(0.5 * (a.x * a.x + a.y * a.y));
        return distributionGgx(NdotH, rms) * visibilitySmithGgxCorrelated(NdotL, NdotV, rms);
    }
    vec3 t = normalize(d);
    vec3 b = cross(n, t);
    vec3 hl = vec3(dot(h, t), dot(h, b), NdotH);
    vec3 vl = vec3(dot(v, t), dot(v, b), NdotV);
    vec3 ll = vec3(dot(l, t), dot(l, b), NdotL);
    return ptGgxAnisoD(hl, a.x, a.y) * ptGgxAnisoG2(vl, ll, a.x, a.y) / (4.0 * NdotL * NdotV);
}

// The extension textures' channels at a fragment: specularTexture A, specularColorTexture RGB (linear,
// decoded from sRGB), clearcoatTexture R, clearcoatRoughnessTexture G, sheenColorTexture RGB, sheenRoughnessTexture
// A, diffuseTransmissionTexture A, diffuseTransmissionColorTexture RGB; 1 where a material has no such texture
// (white placeholder slots).
struct LayerTexels {
    float specular;
    vec3 specularColor;
    float clearcoat;
    float clearcoatRoughness;
    vec3 sheenColor;
    float sheenRoughness;
    float diffuseTransmission;
    vec3 diffuseTransmissionColor;
};

LayerTexels noLayerTexels() { return LayerTexels(1.0, vec3(1.0), 1.0, 1.0, vec3(1.0), 1.0, 1.0, vec3(1.0)); }

// The factors times the texels, as pathtrace::evaluateMaterial and wfEvaluateMaterial scale them.
SurfaceLayers texturedLayers(SurfaceLayers s, LayerTexels t) {
    s.specular = clamp(s.specular * t.specular, 0.0, 1.0);
    s.specularColor = max(s.specularColor * t.specularColor, vec3(0.0));
    s.clearcoat = clamp(s.clearcoat * t.clearcoat, 0.0, 1.0);
    s.clearcoatRoughness = clamp(s.clearcoatRoughness * t.clearcoatRoughness, 0.0, 1.0);
    s.sheenColor = clamp(s.sheenColor * t.sheenColor, vec3(0.0), vec3(1.0));
    s.sheenRoughness = clamp(s.sheenRoughness * t.sheenRoughness, 0.0, 1.0);
    s.diffuseTransmission = clamp(s.diffuseTransmission * t.diffuseTransmission, 0.0, 1.0);
    s.diffuseTransmissionColor = clamp(s.diffuseTransmissionColor * t.diffuseTransmissionColor, vec3(0.0), vec3(1.0));
    return s;
}

vec3 layeredF0(SurfaceLayers s, vec3 baseColor, float metallic) {
    return mix(min(vec3(0.04) * s.specularColor, vec3(1.0)) * s.specular, baseColor, metallic);
}

float maxOf(vec3 c) { return max(c.r, max(c.g, c.b)); }

// The dielectric Fresnel of the base layer at v.h: KHR_materials_specular over the exact curve of IOR 1.5
// (shared/pt_bsdf_frame.h ptDielectricFresnel with the IOR fixed).
vec3 dielectricFresnel(SurfaceLayers s, float VdotH) {
    vec3 f0 = min(vec3(0.04) * s.specularColor, vec3(1.0));
    float w = clamp((ptFresnelDielectric(VdotH, 1.5) - 0.04) / (1.0 - 0.04), 0.0, 1.0);
    return s.specular * (f0 + (1.0 - f0) * w);
}

// W(n.v, n.l): the albedo-scaled weight of the base's Lambert lobe (shared/pt_energy.h), the path tracers' for the
// raster's dielectric (IOR 1.5, f0 0.04, KHR_materials_specular's specular and strongest f0'); perceptual roughness
// already clamped. Reciprocal, and a white base reflects exactly 1 - Es(n.v). Per light here; on a real GPU the
// n.v and average terms (and their eight table reads) would be hoisted out of the light loop.
float dielectricDiffuseWeight(SurfaceLayers s, float roughness, float NdotV, float NdotL) {
    const float kIor = 1.5;
    const float kF0 = 0.04;
    vec3 f0 = min(vec3(kF0) * s.specularColor, vec3(1.0));
    float wAvg = clamp((ptFresnelDielectricAverage(kIor) - kF0) / (1.0 - kF0), 0.0, 1.0);
    float eAvg = ptAlbedoMetalAvg(roughness);
    vec3 c = ptDielectricAlbedoCoeffs(s.specular, f0, kF0, s.specular * (f0 + (1.0 - f0) * wAvg), eAvg, false);
    float esAvg = ptDielectricAlbedoOf(c, kF0, eAvg, ptAlbedoSpecularAvg(roughness, kIor));
    float esV = ptDielectricAlbedoOf(c, kF0, ptAlbedoMetal(NdotV, roughness), ptAlbedoSpecular(NdotV, roughness, kIor));
    float esL = ptDielectricAlbedoOf(c, kF0, ptAlbedoMetal(NdotL, roughness), ptAlbedoSpecular(NdotL, roughness, kIor));
    return max(1.0 - esV, 0.0) * max(1.0 - esL, 0.0) / max(1.0 - esAvg, 1e-4);
}

// KHR_materials_diffuse_transmission: f * |n.l| for a light behind the surface (n.l <= 0), beneath the clearcoat
// and sheen layers as the reflected base is (the layer weights depend on n.v only). What passes the dielectric is
// the Lambert lobes' albedo-scaled weight at |n.l| (dielectricDiffuseWeight), the path tracers' ptDiffuseWeight
// for this lobe, so a back-lit leaf is the front-lit Lambert mirrored, specular layer included.
vec3 diffuseTransmissionCosine(SurfaceLayers s, float metallic, float perceptualRoughness, vec3 n, vec3 v, vec3 l) {
    if ((s.flags & kMaterialDiffuseTransmission) == 0u || s.diffuseTransmission <= 0.0) return vec3(0.0);
    float NdotL = dot(n, l);
    float NdotV = max(dot(n, v), 1e-4);
    float roughness = clamp(perceptualRoughness, kMinRoughness, 1.0);
    float pass = metallic < 1.0 ? dielectricDiffuseWeight(s, roughness, NdotV, -NdotL) : 0.0;
    vec3 result = s.diffuseTransmissionColor * (s.diffuseTransmission * (1.0 - metallic) / kPi * pass);
    if ((s.flags & kMaterialSheen) != 0u)
        result *= max(1.0 - maxOf(s.sheenColor) * ptAlbedoSheen(NdotV, s.sheenRoughness), 0.0);
    if ((s.flags & kMaterialClearcoat) != 0u) result *= 1.0 - s.clearcoat * fresnelSchlick(vec3(0.04), NdotV).x;
    return result * -NdotL;
}

// f(l, v) * NdotL with the material's extension layers.
vec3 layeredBrdfCosine(SurfaceLayers s, vec3 baseColor, float metallic, float perceptualRoughness, vec3 n, vec3 v,
                       vec3 l) {
    float NdotL = dot(n, l);
    if (NdotL <= 0.0) return diffuseTransmissionCosine(s, metallic, perceptualRoughness, n, v, l);
    float NdotV = max(dot(n, v), 1e-4);
    float roughness = clamp(perceptualRoughness, kMinRoughness, 1.0);
    // Without extension flags the dielectric is the plain one (specular 1, colour 1) whatever the factors hold.
    float wDiffuse = metallic < 1.0 ? dielectricDiffuseWeight(s.flags == 0u ? noLayers() : s, roughness, NdotV, NdotL)
                                    : 0.0;
    if (s.flags == 0u) return brdfCosine(baseColor, metallic, perceptualRoughness, wDiffuse, n, v, l);
    vec3 h = normalize(l + v);
    float NdotH = max(dot(n, h), 0.0);
    float VdotH = max(dot(v, h), 0.0);
    float alpha = roughness * roughness;
    vec3 F = mix(dielectricFresnel(s, VdotH), fresnelSchlick(baseColor, VdotH), metallic);
    vec3 diffuse = wDiffuse * baseColor * (1.0 - metallic) * (1.0 - s.diffuseTransmission) / kPi;
    vec3 result = diffuse + F * baseDistributionVisibility(s, alpha, n, v, l, h, NdotL, NdotV, NdotH);
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
