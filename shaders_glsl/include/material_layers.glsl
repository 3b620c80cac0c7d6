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
// clearcoatNormalTexture: the coat term (its D, V, cosines, and the n.v of its layer weight) uses the coat's own
// normal (SurfaceLayers::clearcoatNormal; the deferred G-buffer carries it octahedral in its layer texels).
// KHR_materials_iridescence: the base's dielectric and metal Fresnel become mix(F, F_film, iridescence) at v.h
// (shared/pt_iridescence.h, as the path tracer); ambient: f0 becomes the film's at n.v through Schlick's curve.
// KHR_materials_anisotropy: the base's GGX D and V become the extension's anisotropic ones (shared/pt_anisotropy.h,
// the path tracer's functions) in the frame of the anisotropy direction, which the forward pass builds from its
// tangent frame (withAnisotropyFrame) and the deferred pass reads back from the G-buffer (gbuffer_anisotropy.glsl);
// wherever no direction is known an anisotropic material takes the isotropic lobe at the rms alpha sqrt((at^2 + ab^2) / 2),
// the path tracer's sampling roughness too. Ambient: the isotropic split-sum at the rms alpha along the sample
// viewer's bent reflection vector (anisotropicReflection), an approximation of the lobe's shape, scaled to the
// anisotropic lobe's directional albedo E at the view's azimuth (shared/pt_energy.h's table, as the path tracer's
// compensation) wherever the direction is known.
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
#include "pt_iridescence.h"
#include "gbuffer_anisotropy.glsl"

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
    // KHR_materials_iridescence (shared/pt_iridescence.h)
    float iridescence;           // 0: no film
    float iridescenceIor;
    float iridescenceThickness;  // nanometres
    // KHR_materials_clearcoat's clearcoatNormalTexture
    vec3 clearcoatNormal;  // world, unit, on the viewer's side; 0: the coat uses the shading normal
};

SurfaceLayers noLayers() {
    return SurfaceLayers(0u, 1.0, vec3(1.0), 0.0, 0.0, vec3(0.0), 0.0, 0.0, vec3(0.0), 0.0, vec3(1.0), 0.0, 1.3, 0.0,
                         vec3(0.0));
}

// The factors; the iridescence thickness is the maximum (what a material without a thickness texture has).
SurfaceLayers materialLayers(GpuMaterial m) {
    bool film = (m.flags & kMaterialIridescence) != 0u;
    return SurfaceLayers(m.flags & (kMaterialLayers | kMaterialAnisotropy | kMaterialDiffuseTransmission |
                                    kMaterialIridescence),
                         clamp(m.specular, 0.0, 1.0), max(m.specularColor, vec3(0.0)), clamp(m.clearcoat, 0.0, 1.0),
                         clamp(m.clearcoatRoughness, 0.0, 1.0), clamp(m.sheenColor, vec3(0.0), vec3(1.0)),
                         clamp(m.sheenRoughness, 0.0, 1.0),
                         (m.flags & kMaterialAnisotropy) != 0u ? clamp(m.anisotropyStrength, 0.0, 1.0) : 0.0,
                         vec3(0.0),
                         (m.flags & kMaterialDiffuseTransmission) != 0u ? clamp(m.diffuseTransmission, 0.0, 1.0)
                                                                         : 0.0,
                         clamp(m.diffuseTransmissionColor, vec3(0.0), vec3(1.0)),
                         film ? clamp(m.iridescence, 0.0, 1.0) : 0.0, m.iridescenceIor,
                         film ? max(m.iridescenceThicknessMax, 0.0) : 0.0, vec3(0.0));
}

// The coat's normal: its own (clearcoatNormalTexture) or the shading normal n.
vec3 coatNormal(SurfaceLayers s, vec3 n) {
    return dot(s.clearcoatNormal, s.clearcoatNormal) > 0.5 ? s.clearcoatNormal : n;
}

// KHR_materials_iridescence's textures: texel.x (iridescenceTexture R) scales the factor, texel.y
// (iridescenceThicknessTexture G) picks the thickness between minimum and maximum (1 without a texture).
SurfaceLayers withIridescenceTexels(SurfaceLayers s, GpuMaterial m, vec2 texel) {
    if ((m.flags & kMaterialIridescence) != 0u) {
        s.iridescence = clamp(s.iridescence * texel.x, 0.0, 1.0);
        s.iridescenceThickness = max(mix(m.iridescenceThicknessMin, m.iridescenceThicknessMax, texel.y), 0.0);
    }
    return s;
}

// anisotropyTexture's B scales the strength (1 without a texture).
SurfaceLayers withAnisotropyStrengthTexel(SurfaceLayers s, float b) {
    s.anisotropyStrength = clamp(s.anisotropyStrength * b, 0.0, 1.0);
    return s;
}

// The anisotropy direction from a tangent frame (t, b: glTF's tangent and bitangent): anisotropyTexture's RG
// remapped to [-1, 1] ((1, 0.5) without a texture: the tangent), turned by anisotropyRotation.
SurfaceLayers withAnisotropyFrame(SurfaceLayers s, GpuMaterial m, vec3 t, vec3 b, vec2 textureRg) {
    if (s.anisotropyStrength > 0.0) {
        vec3 w = anisotropyDirection(m.anisotropyRotation, t, b, textureRg);
        s.anisotropyDirection = dot(w, w) > 1e-12 ? normalize(w) : vec3(0.0);
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

// The F = 1 directional albedo E of the base layer's GGX towards v (perceptual roughness): the anisotropic table at
// v's azimuth from the anisotropy direction, else the isotropic table (at the rms roughness when the material is
// anisotropic but no direction is known).
float baseLayerAlbedo(SurfaceLayers s, vec3 n, vec3 v, float perceptualRoughness) {
    float NdotV = max(dot(n, v), 1e-4);
    if (s.anisotropyStrength <= 0.0) return ptAlbedoMetal(NdotV, perceptualRoughness);
    vec3 d = s.anisotropyDirection - n * dot(s.anisotropyDirection, n);
    if (dot(d, d) < 1e-8) return ptAlbedoMetal(NdotV, anisotropicRoughness(s, perceptualRoughness));
    vec3 t = normalize(d);
    return ptAlbedoAnisoMetal(vec3(dot(v, t), dot(v, cross(n, t)), NdotV), perceptualRoughness, s.anisotropyStrength);
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

// W(n.v, n.l) = (1 - Es(n.v)) (1 - Es(n.l)) / (1 - Es_avg): the albedo-scaled weight of the base's Lambert lobe
// (shared/pt_energy.h), the path tracers' for the raster's dielectric (IOR 1.5, f0 0.04, KHR_materials_specular's
// specular and strongest f0'); perceptual roughness already clamped. Reciprocal, and a white base reflects exactly
// 1 - Es(n.v). DiffuseWeightView holds the part that does not depend on the light, computed once per pixel
// (surface_lighting.glsl shadeSurface): of the 30 table entries the whole weight reads (Es(n.v) and Es(n.l) 12
// each, Es_avg 6) only Es(n.l)'s 12 remain per light.
const float kDiffuseWeightIor = 1.5;
const float kDiffuseWeightF0 = 0.04;
struct DiffuseWeightView {
    vec3 coeffs;      // ptDielectricAlbedoCoeffs of the dielectric
    float roughness;  // perceptual, clamped
    float view;       // max(1 - Es(n.v), 0)
    float average;    // max(1 - Es_avg, 1e-4)
};

DiffuseWeightView diffuseWeightView(SurfaceLayers s, float roughness, float NdotV) {
    const float kIor = kDiffuseWeightIor;
    const float kF0 = kDiffuseWeightF0;
    vec3 f0 = min(vec3(kF0) * s.specularColor, vec3(1.0));
    float wAvg = clamp((ptFresnelDielectricAverage(kIor) - kF0) / (1.0 - kF0), 0.0, 1.0);
    float eAvg = ptAlbedoMetalAvg(roughness);
    vec3 c = ptDielectricAlbedoCoeffs(s.specular, f0, kF0, s.specular * (f0 + (1.0 - f0) * wAvg), eAvg, false);
    float esAvg = ptDielectricAlbedoOf(c, kF0, eAvg, ptAlbedoSpecularAvg(roughness, kIor));
    float esV = ptDielectricAlbedoOf(c, kF0, ptAlbedoMetal(NdotV, roughness), ptAlbedoSpecular(NdotV, roughness, kIor));
    return DiffuseWeightView(c, roughness, max(1.0 - esV, 0.0), max(1.0 - esAvg, 1e-4));
}

float dielectricDiffuseWeight(DiffuseWeightView w, float NdotL) {
    float esL = ptDielectricAlbedoOf(w.coeffs, kDiffuseWeightF0, ptAlbedoMetal(NdotL, w.roughness),
                                     ptAlbedoSpecular(NdotL, w.roughness, kDiffuseWeightIor));
    return w.view * max(1.0 - esL, 0.0) / w.average;
}


// KHR_materials_diffuse_transmission: f * |n.l| for a light behind the surface (n.l <= 0), beneath the clearcoat
// and sheen layers as the reflected base is (the layer weights depend on n.v only). What passes the dielectric is
// the Lambert lobes' albedo-scaled weight at |n.l| (dielectricDiffuseWeight), the path tracers' ptDiffuseWeight
// for this lobe, so a back-lit leaf is the front-lit Lambert mirrored, specular layer included. w: the weight's
// light-independent part (diffuseWeightView of s at the clamped roughness and n.v).
vec3 diffuseTransmissionCosine(SurfaceLayers s, DiffuseWeightView w, float metallic, vec3 n, vec3 v, vec3 l) {
    if ((s.flags & kMaterialDiffuseTransmission) == 0u || s.diffuseTransmission <= 0.0) return vec3(0.0);
    float NdotL = dot(n, l);
    float NdotV = max(dot(n, v), 1e-4);
    float pass = metallic < 1.0 ? dielectricDiffuseWeight(w, -NdotL) : 0.0;
    vec3 result = s.diffuseTransmissionColor * (s.diffuseTransmission * (1.0 - metallic) / kPi * pass);
    if ((s.flags & kMaterialSheen) != 0u)
        result *= max(1.0 - maxOf(s.sheenColor) * ptAlbedoSheen(NdotV, s.sheenRoughness), 0.0);
    if ((s.flags & kMaterialClearcoat) != 0u) result *= 1.0 - s.clearcoat * fresnelSchlick(vec3(0.04), NdotV).x;
    return result * -NdotL;
}

// The diffuse weight's light-independent part for layeredBrdfCosine, once per pixel: without extension flags the
// dielectric is the plain one (specular 1, colour 1) whatever the factors hold.
DiffuseWeightView surfaceDiffuseWeightView(SurfaceLayers s, float perceptualRoughness, vec3 n, vec3 v) {
    return diffuseWeightView(s.flags == 0u ? noLayers() : s, clamp(perceptualRoughness, kMinRoughness, 1.0),
                             max(dot(n, v), 1e-4));
}

// f(l, v) * NdotL with the material's extension layers; w: surfaceDiffuseWeightView(s, perceptualRoughness, n, v).
vec3 layeredBrdfCosine(SurfaceLayers s, DiffuseWeightView w, vec3 baseColor, float metallic, float perceptualRoughness,
                       vec3 n, vec3 v, vec3 l) {
    float NdotL = dot(n, l);
    if (NdotL <= 0.0) return diffuseTransmissionCosine(s, w, metallic, n, v, l);
    float NdotV = max(dot(n, v), 1e-4);
    float roughness = clamp(perceptualRoughness, kMinRoughness, 1.0);
    float wDiffuse = metallic < 1.0 ? dielectricDiffuseWeight(w, NdotL) : 0.0;
    if (s.flags == 0u) return brdfCosine(baseColor, metallic, perceptualRoughness, wDiffuse, n, v, l);
    vec3 h = normalize(l + v);
    float NdotH = max(dot(n, h), 0.0);
    float VdotH = max(dot(v, h), 0.0);
    float alpha = roughness * roughness;
    vec3 fDielectric = dielectricFresnel(s, VdotH);
    vec3 fMetal = fresnelSchlick(baseColor, VdotH);
    // KHR_materials_iridescence: the thin film's Fresnel at v.h replaces both (exactly these when there is none).
    fDielectric = ptIridescentFresnel(fDielectric, VdotH, s.iridescence, s.iridescenceIor, s.iridescenceThickness,
                                      min(vec3(0.04) * s.specularColor, vec3(1.0)), s.specular);
    fMetal = ptIridescentFresnel(fMetal, VdotH, s.iridescence, s.iridescenceIor, s.iridescenceThickness, baseColor,
                                 1.0);
    vec3 F = mix(fDielectric, fMetal, metallic);
    vec3 diffuse = wDiffuse * baseColor * (1.0 - metallic) * (1.0 - s.diffuseTransmission) / kPi;
    vec3 result = diffuse + F * baseDistributionVisibility(s, alpha, n, v, l, h, NdotL, NdotV, NdotH);
    if ((s.flags & kMaterialSheen) != 0u) {
        float sheenAlpha = ptSheenAlpha(s.sheenRoughness);
        result *= max(1.0 - maxOf(s.sheenColor) * ptAlbedoSheen(NdotV, s.sheenRoughness), 0.0);
        float vis = 1.0 / ((1.0 + ptSheenLambda(NdotV, sheenAlpha) + ptSheenLambda(NdotL, sheenAlpha)) * 4.0 * NdotV *
                           NdotL);
        result += s.sheenColor * (ptSheenD(NdotH, sheenAlpha) * vis);
    }
    vec3 coat = vec3(0.0);
    if ((s.flags & kMaterialClearcoat) != 0u) {  // in the coat normal's frame (clearcoatNormalTexture)
        vec3 nc = coatNormal(s, n);
        float NdotVc = max(dot(nc, v), 1e-4);
        float NdotLc = dot(nc, l);
        float coatRoughness = clamp(s.clearcoatRoughness, kMinRoughness, 1.0);
        float coatAlpha = coatRoughness * coatRoughness;
        result *= 1.0 - s.clearcoat * fresnelSchlick(vec3(0.04), NdotVc).x;
        if (NdotLc > 0.0)
            coat = vec3(s.clearcoat * fresnelSchlick(vec3(0.04), VdotH).x *
                        distributionGgx(max(dot(nc, h), 0.0), coatAlpha) *
                        visibilitySmithGgxCorrelated(NdotLc, NdotVc, coatAlpha) * NdotLc);
    }
    return result * NdotL + coat;
}

// Split-sum scale and bias (f0 A + f90 B) of environmentBrdfApprox, separately.
vec2 environmentBrdfAB(float perceptualRoughness, float NdotV) {
    vec3 e = environmentBrdfApprox(vec3(1.0), perceptualRoughness, NdotV);
    vec3 b = environmentBrdfApprox(vec3(0.0), perceptualRoughness, NdotV);
    return vec2(e.x - b.x, b.x);
}

// The ambient specular albedo of the base layer with the multiple-scattering compensation. The split-sum's
// total A + B is the tabulated GGX albedo E of the path tracer (height-correlated Smith, the same lobe the direct
// term uses; baseLayerAlbedo), its split into the f0 and f90 parts the analytic fit's (at the rms roughness when
// anisotropic); times 1 + f0 (1 / E - 1). roughness: the material's perceptual roughness (clamped).
vec3 ambientSpecularAlbedo(SurfaceLayers s, vec3 baseColor, float metallic, float roughness, vec3 n, vec3 v) {
    float NdotV = max(dot(n, v), 1e-4);
    vec3 f0 = layeredF0(s, baseColor, metallic);
    float f90 = mix(s.specular, 1.0, metallic);
    if (s.iridescence > 0.0 && s.iridescenceThickness > 0.0) {
        // KHR_materials_iridescence: the film's Fresnel at n.v turned into the f0 whose Schlick curve (with this
        // f90) passes through it there, as the Khronos sample viewer's ambient term does.
        float x = clamp(1.0 - NdotV, 0.0, 1.0);
        float x5 = min(x * x * x * x * x, 0.9999);
        vec3 filmD = s.specular * ptThinFilmFresnel(NdotV, s.iridescenceIor, s.iridescenceThickness,
                                                    min(vec3(0.04) * s.specularColor, vec3(1.0)));
        vec3 filmM = ptThinFilmFresnel(NdotV, s.iridescenceIor, s.iridescenceThickness, baseColor);
        vec3 filmF0 = mix((filmD - s.specular * x5) / (1.0 - x5), (filmM - x5) / (1.0 - x5), metallic);
        f0 = mix(f0, clamp(filmF0, vec3(0.0), vec3(1.0)), s.iridescence);
    }
    vec2 ab = environmentBrdfAB(anisotropicRoughness(s, roughness), NdotV);
    float e = max(baseLayerAlbedo(s, n, v, roughness), 0.05);
    ab *= e / max(ab.x + ab.y, 1e-4);
    vec3 albedo = f0 * ab.x + f90 * ab.y;
    return albedo * (1.0 + f0 * (1.0 / e - 1.0));
}

#endif
