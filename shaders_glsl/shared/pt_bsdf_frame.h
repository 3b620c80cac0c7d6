// pt_bsdf_frame.h: the path tracers' BSDF prepared for one outgoing direction (C++ and GLSL, see pt_sampling.h):
// the shading frame, the sanitised inputs, the Fresnel terms, the layer weights of the material extensions and
// the energy compensation, and the lobe selection probabilities that pt_bsdf.h evaluates and samples with.
// The layering, outermost first (glTF's extension specifications, their reference formulas):
//   clearcoat  KHR_materials_clearcoat: GGX lobe of IOR 1.5 (Schlick f0 0.04), weight clearcoat * Fc(v.h); the
//              layers below are scaled by 1 - clearcoat * Fc(n.v) (Fc at the view, as the Khronos sample viewer).
//              With a clearcoatNormalTexture the lobe's D, G and cosines (and that n.v) use the coat's own normal
//              (ptCoatNormalSetup); its value is f_coat times the cosine to the coat normal.
//   sheen      KHR_materials_sheen: sheenColor * Charlie D * V (pt_sheen.h); the layers below are scaled by
//              1 - max(sheenColor) * E_sheen(n.v) (albedo scaling with the tabulated sheen albedo)
//   base       metal: GGX, Schlick F with f0 = baseColor. dielectric: GGX with KHR_materials_specular's
//              F = specular * (f0' + (1 - f0') w(v.h)), f0' = min(f0(ior) specularColor, 1), where w is the exact
//              Fresnel curve of the IOR remapped to [0, 1] (w = (F_exact - f0) / (1 - f0)), so without the
//              extension F is the exact dielectric Fresnel; beneath it the specular transmission weighted
//              1 - specular * max(F(v.h)), and the Lambert diffuse (and diffuse transmission) by albedo scaling
//              (Kelemen & Szirmay-Kalos 2001, Kulla & Conty 2017), reciprocal and energy conserving:
//                (1 - Es(mu_o)) (1 - Es(mu_i)) / (1 - Es_avg)
//              with Es the directional albedo of the dielectric's reflection lobe, its multiple scattering
//              included, so that a white "plastic" reflects exactly 1 (a per-half-vector 1 - F would not remove
//              the energy the rough lobe sends elsewhere: albedo 1.25 at roughness 0.2, grazing view). Es is
//              linear in F, so KHR_materials_specular's F = specular (f0' + (1 - f0') w) gives it exactly from
//              the F = 1 table and the exact-Fresnel reflection table (pt_energy.h): Es = specular (f0' E_metal +
//              (1 - f0') (E_refl - f0 E_metal) / (1 - f0)) + Fms (1 - E_metal); a coloured specularColor takes
//              its strongest channel (Es grows with f0' at every angle, so that channel is the same for all
//              mu: the weight stays reciprocal, and the weaker channels reflect a little less than 1). Light
//              inside a volume (eta < 1) reads the table at 1 / eta, an approximation (the table holds
//              reflection from outside). Multiple scattering: pt_energy.h.
//              KHR_materials_iridescence: both Fresnel terms become mix(F, F_film, iridescence), F_film the thin
//              film over the base's f0 (pt_iridescence.h; dielectric: f0' with KHR_materials_specular's weight,
//              metal: baseColor); the multiple-scattering lobe keeps the film-less average Fresnel (approximation).
//              The albedo-scaled diffuse weight reads the film-less Es (approximation).
//              KHR_materials_anisotropy: the GGX of the reflection and transmission lobes becomes anisotropic
//              (pt_anisotropy.h) in a frame whose tangent is the anisotropy direction; the energy compensation
//              reads the anisotropic albedo table at the view's and the light's azimuth in that frame (pt_energy.h;
//              white furnace in tests/unit/pathtrace/anisotropy_test.cpp); a thin-walled transmission is
//              compensated by the same table (its lobes are the F = 1 reflection and its mirror image), a refracting
//              volume still by the isotropic dielectric table at the rms alpha (there the furnace errs by up to
//              ~14% at strength 1, grazing view: an anisotropic dielectric table is not built yet); the
//              multiple-scattering lobe is sampled by the isotropic tables' density at the root-mean-square alpha
//              sqrt((alpha_t^2 + alpha_b^2) / 2) (a sampling choice only). Clearcoat and sheen stay isotropic.
//              KHR_materials_diffuse_transmission (pt_diffuse_transmission.h): the Lambert base splits into
//              reflection (1 - diffuseTransmission) and a Lambert lobe through the surface tinted by the
//              diffuseTransmissionColor, both beneath the dielectric Fresnel.
#ifndef IDK_PT_BSDF_FRAME_H
#define IDK_PT_BSDF_FRAME_H
#include "pt_microfacet.h"
#include "pt_energy.h"
#include "pt_sheen.h"
#include "pt_anisotropy.h"
#include "pt_diffuse_transmission.h"
#include "pt_iridescence.h"

IDK_GPU_BEGIN

struct PtBsdfFrame {
    vec3 t;
    vec3 b;
    vec3 n;             // shading normal on wo's side, with dot(wo, n) > 0
    vec3 ng;            // geometric normal on wo's side
    vec3 wo;            // local
    vec3 baseColor;     // sanitised
    float metallic;
    float transmission;
    float roughness;    // perceptual, sanitised
    float alpha;        // GGX alpha (>= kPtDeltaAlpha when not delta)
    bool delta;         // specular and transmission lobes are delta
    bool transDelta;    // the transmission lobe is delta (delta, or a volume of IOR ~1: refraction does not bend)
    bool thick;         // transmission refracts (volume); else thin-walled
    float eta;          // thick: IOR on the far side / IOR on wo's side
    float etaFresnel;   // the eta of the Fresnel term on wo's side (eta when thick, the IOR when thin)
    float f0Ior;        // ((etaFresnel - 1) / (etaFresnel + 1))^2
    float specular;     // KHR_materials_specular weight
    vec3 specularF0;    // min(f0Ior * specularColor, 1)
    float dielScale;    // energy compensation of the dielectric reflection: 1 + transmission (transScale - 1)
    float transScale;   // energy compensation of the transmission lobe (1 / E_dielectric(mu_o))
    vec3 msColor;       // multiple-scattering lobe: Fms / (pi (1 - Eavg)) * (1 - E(mu_o)); 0 when none
    float layer;        // (1 - clearcoat Fc(n.v)) (1 - max(sheen) E_sheen(n.v)): weight of the base lobes
    float coatLayer;    // 1 - clearcoat Fc(n.v): weight of the sheen lobe
    float clearcoat;
    float coatAlpha;
    bool coatDelta;
    vec3 sheenColor;
    float sheenAlpha;
    float sheenRoughness;
    float pSpec;        // lobe selection probabilities (sum 1)
    float pDiff;
    float pTrans;
    float pMs;
    float pSheen;
    float pCoat;
    // KHR_materials_anisotropy
    bool aniso;         // the GGX lobes are anisotropic: alphaT along t, alphaB along b (alpha is unused then)
    float alphaT;
    float alphaB;
    // KHR_materials_diffuse_transmission
    float diffTrans;       // diffuseTransmission factor, sanitised (0: the lobe is off)
    vec3 diffTransColor;   // diffuseTransmissionColor, sanitised
    float pDiffTrans;      // selection probability of the lobe (with the six above, sum 1)
    // KHR_materials_anisotropy
    float anisoRoughness;  // the material's perceptual roughness and anisotropy strength: the anisotropic table's
    float anisoStrength;   // coordinates (pt_energy.h)
    // KHR_materials_iridescence
    float iridescence;           // 0: no film (also when the thickness is 0)
    float iridescenceIor;
    float iridescenceThickness;  // nanometres
    // KHR_materials_clearcoat's clearcoatNormalTexture: the coat lobe's own normal
    bool coatTilted;    // the coat has its own normal: coatN (else the coat uses n, coatN = (0, 0, 1))
    vec3 coatN;         // local (in t, b, n), unit, dot(wo, coatN) >= kPtMinCos
    float coatCosO;     // dot(wo, coatN) (wo.z when not tilted)
    // The albedo-scaled diffuse weight (see the header): Es(mu) = specEF0 E_metal(mu) + specEK (E_refl(mu) -
    // f0Ior E_metal(mu)) + specEMs (1 - E_metal(mu)), the table read at specIor
    float specEF0;
    float specEK;
    float specEMs;
    float specIor;
    float diffScale;       // (1 - Es(mu_o)) / (1 - Es_avg)
};

IDK_INLINE float ptCoatFresnel(float c) { return ptFresnelSchlick(vec3(0.04f), c).x; }

// The cosine of a local direction with the coat's normal.
IDK_INLINE float ptCoatCos(PtBsdfFrame f, vec3 w) { return f.coatTilted ? dot(w, f.coatN) : w.z; }

// clearcoatNormalTexture: the coat's normal (world, on the geometric normal's side like the shading normal) turned to
// wo's side and into the local frame; bent toward wo like the base normal when it faces away. Without one (zero
// vector, unusable, or below the geometric surface) the coat keeps the base frame's normal, bit for bit.
IDK_INLINE void ptCoatNormalSetup(PtSurface s, vec3 wo, bool outside, IDK_INOUT(PtBsdfFrame) f) {
    f.coatTilted = false;
    f.coatN = vec3(0.0f, 0.0f, 1.0f);
    f.coatCosO = f.wo.z;
    vec3 c = s.clearcoatNormal;
    if (!(f.clearcoat > 0.0f) || !ptFinite3(c) || !(dot(c, c) > 0.25f)) return;
    c = normalize(c);
    if (!outside) c = -c;
    if (dot(c, f.ng) <= 0.0f) return;
    float cosO = dot(wo, c);
    if (cosO < kPtMinCos) {
        vec3 bent = c + wo * (2.0f * kPtMinCos - cosO);
        if (!(dot(bent, bent) > 1.0e-12f)) return;
        c = normalize(bent);
    }
    vec3 local = ptToLocal(c, f.t, f.b, f.n);
    if (!(dot(local, local) > 0.25f)) return;
    f.coatN = normalize(local);
    f.coatTilted = true;
    f.coatCosO = max(dot(f.wo, f.coatN), kPtMinCos);
}

// Dielectric reflectance at v.h cosine c (KHR_materials_specular over the exact Fresnel curve).
IDK_INLINE vec3 ptDielectricFresnel(PtBsdfFrame f, float c) {
    float exact = ptFresnelDielectric(c, f.etaFresnel);
    float w = f.f0Ior < 1.0e-6f ? exact : clamp((exact - f.f0Ior) / (1.0f - f.f0Ior), 0.0f, 1.0f);
    vec3 plain = f.specular * (f.specularF0 + (vec3(1.0f) - f.specularF0) * w);
    return ptIridescentFresnel(plain, c, f.iridescence, f.iridescenceIor, f.iridescenceThickness, f.specularF0,
                               f.specular);
}

// What passes beneath the dielectric reflection (into diffuse or transmission).
IDK_INLINE float ptDielectricPass(PtBsdfFrame f, float c) {
    return max(1.0f - ptMaxComponent(ptDielectricFresnel(f, c)), 0.0f);
}

// The reflection lobe's Fresnel (energy compensation of refraction included), before the layer weight.
IDK_INLINE vec3 ptSpecularFresnel(PtBsdfFrame f, float c) {
    vec3 metal = ptIridescentFresnel(ptFresnelSchlick(f.baseColor, c), c, f.iridescence, f.iridescenceIor,
                                     f.iridescenceThickness, f.baseColor, 1.0f);
    return mix(ptDielectricFresnel(f, c) * f.dielScale, metal, f.metallic);
}

// Es(mu): the directional albedo of the dielectric reflection lobe (multiple scattering included).
IDK_INLINE float ptDielectricSpecAlbedo(PtBsdfFrame f, float mu) {
    float em = ptAlbedoMetal(mu, f.roughness);
    float er = ptAlbedoSpecular(mu, f.roughness, f.specIor);
    return ptDielectricAlbedoOf(vec3(f.specEF0, f.specEK, f.specEMs), f.f0Ior, em, er);
}

// The Lambert lobes' weight for a light direction of cosine mu (reflected or transmitted): diffScale (1 - Es(mu)).
IDK_INLINE float ptDiffuseWeight(PtBsdfFrame f, float mu) {
    return f.diffScale * max(1.0f - ptDielectricSpecAlbedo(f, mu), 0.0f);
}

// ---------------------------------------------------------------------------------------------------- GGX hooks
// The base layer's GGX (reflection and transmission), isotropic or anisotropic; local directions. The isotropic
// branch calls pt_microfacet.h exactly as before the extension existed.
IDK_INLINE float ptBaseD(PtBsdfFrame f, vec3 h) {
    return f.aniso ? ptGgxAnisoD(h, f.alphaT, f.alphaB) : ptGgxD(h.z, f.alpha);
}
IDK_INLINE float ptBaseG1(PtBsdfFrame f, vec3 w) {
    return f.aniso ? ptGgxAnisoG1(w, f.alphaT, f.alphaB) : ptGgxG1(w.z, f.alpha);
}
// wi may lie below the surface (refraction): Lambda depends on its cosine squared only.
IDK_INLINE float ptBaseG2(PtBsdfFrame f, vec3 wo, vec3 wi) {
    return f.aniso ? ptGgxAnisoG2(wo, wi, f.alphaT, f.alphaB) : ptGgxG2(wo.z, abs(wi.z), f.alpha);
}
IDK_INLINE vec3 ptBaseSampleVndf(PtBsdfFrame f, vec3 wo, float u1, float u2) {
    return f.aniso ? ptSampleGgxAnisoVndf(wo, f.alphaT, f.alphaB, u1, u2) : ptSampleGgxVndf(wo, f.alpha, u1, u2);
}
IDK_INLINE float ptBaseVndfPdf(PtBsdfFrame f, vec3 wo, vec3 h) {
    return f.aniso ? ptGgxAnisoVndfPdf(wo, h, f.alphaT, f.alphaB) : ptGgxVndfPdf(wo, h, f.alpha);
}

// The F = 1 albedo E of the base GGX lobe for a local direction: the multiple-scattering lobe's (1 - E) factors.
IDK_INLINE float ptBaseAlbedo(PtBsdfFrame f, vec3 w) {
    return f.aniso ? ptAlbedoAnisoMetal(w, f.anisoRoughness, f.anisoStrength) : ptAlbedoMetal(w.z, f.roughness);
}

// KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha, the frame's tangent turned to
// the anisotropy direction (projected onto the shading normal's plane; the basis's own tangent when the surface
// gives none), and f.roughness set to the root-mean-square alpha's (the mean over azimuths of the projected alpha^2
// that Lambda sees), which only picks the multiple-scattering lobe's sampling density.
IDK_INLINE void ptAnisotropySetup(PtSurface s, vec3 wo, IDK_INOUT(PtBsdfFrame) f) {
    f.aniso = false;
    f.alphaT = f.alpha;
    f.alphaB = f.alpha;
    float strength = ptSaturate(s.anisotropyStrength);
    if (!(strength > 0.0f)) return;
    float alpha = f.roughness * f.roughness;
    float alphaT = mix(alpha, 1.0f, strength * strength);
    if (alphaT < kPtDeltaAlpha) return;  // still a mirror: the delta lobes
    f.aniso = true;
    f.delta = false;
    f.transDelta = false;
    f.alphaT = alphaT;
    f.alphaB = max(alpha, kPtDeltaAlpha);
    f.anisoRoughness = f.roughness;
    f.anisoStrength = strength;
    f.alpha = sqrt(0.5f * (f.alphaT * f.alphaT + f.alphaB * f.alphaB));
    f.roughness = sqrt(f.alpha);
    vec3 d = ptFinite3(s.anisotropyDirection) ? s.anisotropyDirection : vec3(0.0f);
    vec3 t = d - f.n * dot(d, f.n);
    if (dot(t, t) > 1.0e-12f) {
        f.t = normalize(t);
        f.b = cross(f.n, f.t);
        f.wo = ptToLocal(wo, f.t, f.b, f.n);
        f.wo.z = max(f.wo.z, kPtMinCos);
    }
}

// Turns the shading frame to wo's side; false when wo or the normals are unusable.
IDK_INLINE bool ptBsdfOrient(PtSurface s, vec3 wo, IDK_INOUT(PtBsdfFrame) f, IDK_OUT(bool) outside) {
    outside = true;
    if (!ptFinite3(wo) || !(dot(wo, wo) > 0.5f)) return false;
    vec3 ng = s.geometricNormal;
    vec3 n = s.shadingNormal;
    bool ngValid = ptFinite3(ng) && dot(ng, ng) > 0.25f;
    bool nValid = ptFinite3(n) && dot(n, n) > 0.25f;
    if (!ngValid) ng = nValid ? n : wo;
    if (!nValid) n = ng;
    ng = normalize(ng);
    n = normalize(n);
    outside = dot(wo, ng) >= 0.0f;
    if (!outside) {
        ng = -ng;
        n = -n;
    }
    if (dot(n, ng) <= 0.0f) n = ng;
    float cosO = dot(wo, n);
    if (cosO < kPtMinCos) {  // a shading normal facing away from wo: tilt it toward wo just enough
        vec3 bent = n + wo * (2.0f * kPtMinCos - cosO);
        n = dot(bent, bent) > 1.0e-12f ? normalize(bent) : ng;
    }
    f.n = n;
    f.ng = ng;
    ptBasis(n, f.t, f.b);
    f.wo = ptToLocal(wo, f.t, f.b, n);
    f.wo.z = max(f.wo.z, kPtMinCos);
    return true;
}

// False when nothing can scatter (invalid input or a black surface).
IDK_INLINE bool ptBsdfSetup(PtSurface s, vec3 wo, IDK_OUT(PtBsdfFrame) f) {
    f.t = vec3(1.0f, 0.0f, 0.0f);
    f.b = vec3(0.0f, 1.0f, 0.0f);
    f.n = vec3(0.0f, 0.0f, 1.0f);
    f.ng = f.n;
    f.wo = f.n;
    f.baseColor = vec3(ptSaturate(s.baseColor.x), ptSaturate(s.baseColor.y), ptSaturate(s.baseColor.z));
    f.metallic = ptSaturate(s.metallic);
    f.transmission = ptSaturate(s.transmission);
    f.roughness = ptSaturate(s.roughness);
    f.alpha = f.roughness * f.roughness;
    f.delta = f.alpha < kPtDeltaAlpha;
    f.transDelta = f.delta;
    f.alpha = max(f.alpha, kPtDeltaAlpha);
    f.aniso = false;
    f.alphaT = f.alpha;
    f.alphaB = f.alpha;
    f.anisoRoughness = f.roughness;
    f.anisoStrength = 0.0f;
    f.specular = ptSaturate(s.specular);
    f.clearcoat = ptSaturate(s.clearcoat);
    float coatRoughness = ptSaturate(s.clearcoatRoughness);
    f.coatAlpha = coatRoughness * coatRoughness;
    f.coatDelta = f.coatAlpha < kPtDeltaAlpha;
    f.coatAlpha = max(f.coatAlpha, kPtDeltaAlpha);
    f.sheenColor = vec3(ptSaturate(s.sheenColor.x), ptSaturate(s.sheenColor.y), ptSaturate(s.sheenColor.z));
    f.sheenRoughness = ptSaturate(s.sheenRoughness);
    f.sheenAlpha = ptSheenAlpha(f.sheenRoughness);
    // KHR_materials_iridescence (pt_iridescence.h): the film's Fresnel replaces the dielectric and metal ones,
    // weighted by the factor; seen from air on whichever side wo is (inside a refracting volume an approximation).
    f.iridescenceThickness = ptFinite(s.iridescenceThickness) ? max(s.iridescenceThickness, 0.0f) : 0.0f;
    f.iridescence = f.iridescenceThickness > 0.0f ? ptSaturate(s.iridescence) : 0.0f;
    f.iridescenceIor = ptFinite(s.iridescenceIor) ? clamp(s.iridescenceIor, 1.0f, 4.0f) : 1.3f;
    f.pSpec = 0.0f;
    f.pDiff = 0.0f;
    f.pTrans = 0.0f;
    f.pMs = 0.0f;
    f.pSheen = 0.0f;
    f.pCoat = 0.0f;
    f.diffTrans = ptDiffTransFactor(s);
    f.diffTransColor = ptDiffTransColor(s);
    f.pDiffTrans = 0.0f;
    f.dielScale = 1.0f;
    f.transScale = 1.0f;
    f.msColor = vec3(0.0f);
    f.specEF0 = 0.0f;
    f.specEK = 0.0f;
    f.specEMs = 0.0f;
    f.specIor = 1.0f;
    f.diffScale = 1.0f;
    f.layer = 1.0f;
    f.coatLayer = 1.0f;
    float ior = ptFinite(s.ior) ? clamp(s.ior, 1.0f, 4.0f) : 1.5f;
    f.thick = s.thickness > 0.0f;
    f.eta = 1.0f;
    f.etaFresnel = ior;
    bool outside;
    if (!ptBsdfOrient(s, wo, f, outside)) return false;
    ptAnisotropySetup(s, wo, f);
    ptCoatNormalSetup(s, wo, outside, f);
    if (f.thick) {
        f.eta = outside ? ior : 1.0f / ior;
        f.etaFresnel = f.eta;
    }
    // With eta ~1 rough refraction degenerates (the generalized half vector wo + eta wi vanishes): every facet
    // passes the ray straight on, a delta lobe.
    f.transDelta = f.delta || (f.thick && abs(f.eta - 1.0f) < 1.0e-3f);
    float r0 = (f.etaFresnel - 1.0f) / (f.etaFresnel + 1.0f);
    f.f0Ior = r0 * r0;
    vec3 specularColor = vec3(ptFinite(s.specularColor.x) ? max(s.specularColor.x, 0.0f) : 1.0f,
                              ptFinite(s.specularColor.y) ? max(s.specularColor.y, 0.0f) : 1.0f,
                              ptFinite(s.specularColor.z) ? max(s.specularColor.z, 0.0f) : 1.0f);
    f.specularF0 = min(vec3(f.f0Ior) * specularColor, vec3(1.0f));
    float mu = f.wo.z;
    float msAlbedo = 0.0f;
    // The dielectric's average Fresnel: the exact curve's average remapped like ptDielectricFresnel.
    float favgExact = ptFresnelDielectricAverage(f.etaFresnel);
    float wAvg = f.f0Ior < 1.0e-6f ? favgExact : clamp((favgExact - f.f0Ior) / (1.0f - f.f0Ior), 0.0f, 1.0f);
    vec3 favgDielectric = f.specular * (f.specularF0 + (vec3(1.0f) - f.specularF0) * wAvg);
    float eAvg = ptAlbedoMetalAvg(f.roughness);  // isotropic: the diffuse weight's Es reads isotropic tables

    // Energy compensation (pt_energy.h). Refraction: both single-scattering lobes of the transmitted part
    // scaled by 1 / E_dielectric (thin-walled: reflection + mirrored reflection = the F = 1 GGX albedo).
    if (!f.delta) {
        float eMetal = ptBaseAlbedo(f, f.wo);
        float eLobeAvg = f.aniso ? ptAlbedoAnisoAvg(f.anisoRoughness, f.anisoStrength) : eAvg;
        if (f.transmission > 0.0f && !f.transDelta) {
            float e = f.thick ? ptAlbedoDielectric(mu, f.roughness, ior, !outside) : eMetal;
            f.transScale = 1.0f / max(e, 0.05f);
            f.dielScale = 1.0f + f.transmission * (f.transScale - 1.0f);
        }
        vec3 fms = f.metallic * ptMultiScatterColor(ptSchlickAverage(f.baseColor), eLobeAvg) +
                   ((1.0f - f.metallic) * (1.0f - f.transmission)) * ptMultiScatterColor(favgDielectric, eLobeAvg);
        f.msColor = fms * ((1.0f - eMetal) / (kPtPi * max(1.0f - eLobeAvg, 1.0e-4f)));
        msAlbedo = ptAverage(fms) * (1.0f - eMetal);
    }
    // The diffuse weight's albedo scaling (header): the reflection lobe's albedo as a function of F is linear.
    vec3 specE = ptDielectricAlbedoCoeffs(f.specular, f.specularF0, f.f0Ior, favgDielectric, eAvg, f.delta);
    f.specEF0 = specE.x;
    f.specEK = specE.y;
    f.specEMs = specE.z;
    f.specIor = max(f.etaFresnel, 1.0f / f.etaFresnel);
    float specAvg = ptDielectricAlbedoOf(specE, f.f0Ior, eAvg, ptAlbedoSpecularAvg(f.roughness, f.specIor));
    float diffOut = max(1.0f - ptDielectricSpecAlbedo(f, mu), 0.0f);  // the diffuse albedo (white base)
    f.diffScale = diffOut / max(1.0f - specAvg, 1.0e-4f);
    float coatF = f.clearcoat * ptCoatFresnel(f.coatCosO);
    f.coatLayer = 1.0f - coatF;
    float sheenMax = ptMaxComponent(f.sheenColor);
    float sheenAlbedo = sheenMax > 0.0f ? ptAlbedoSheen(mu, f.sheenRoughness) : 0.0f;
    f.layer = f.coatLayer * max(1.0f - sheenMax * sheenAlbedo, 0.0f);

    // Selection probabilities estimate each lobe's albedo from the Fresnel term at the macro normal. They are
    // floored wherever the lobe can still scatter (microfacets see other angles: total internal reflection at the
    // macro normal does not stop refraction through tilted facets, a black metal still has a grazing Schlick
    // term), so that every direction with f > 0 keeps a pdf > 0 and BSDF sampling stays unbiased.
    float dielectric = 1.0f - f.metallic;
    float base = dielectric * max(ptDielectricPass(f, mu), 0.05f) * ptAverage(f.baseColor);
    float pSpec = ptAverage(ptSpecularFresnel(f, mu));
    if (f.metallic > 0.0f || (f.etaFresnel != 1.0f && f.specular > 0.0f)) pSpec = max(pSpec, 1.0e-3f);
    float diffuseBase = dielectric * max(diffOut, 0.05f) * (1.0f - f.transmission);
    float pDiff = diffuseBase * ptAverage(f.baseColor);
    float pDiffTrans = 0.0f;
    if (f.diffTrans > 0.0f) {  // split the diffuse base; its transmitted half is weighted by its own colour
        pDiffTrans = diffuseBase * f.diffTrans * max(ptAverage(f.diffTransColor), 1.0e-3f);
        pDiff *= 1.0f - f.diffTrans;
    }
    float pTrans = base * f.transmission;
    float pMs = msAlbedo;
    float pSheen = sheenMax > 0.0f ? max(sheenMax * sheenAlbedo, 1.0e-3f) * f.coatLayer : 0.0f;
    float pCoat = f.clearcoat > 0.0f ? max(coatF, 1.0e-3f) : 0.0f;
    pSpec *= f.layer;
    pDiff *= f.layer;
    pTrans *= f.layer;
    pMs *= f.layer;
    pDiffTrans *= f.layer;
    float sum = pSpec + pDiff + pTrans + pMs + pSheen + pCoat + pDiffTrans;
    if (!(sum > 0.0f) || !ptFinite(sum)) return false;
    f.pSpec = pSpec / sum;
    f.pDiff = pDiff / sum;
    f.pTrans = pTrans / sum;
    f.pMs = pMs / sum;
    f.pSheen = pSheen / sum;
    f.pCoat = pCoat / sum;
    f.pDiffTrans = pDiffTrans / sum;
    return true;
}

IDK_GPU_END

#endif
