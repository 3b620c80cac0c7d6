// pt_bsdf.h: the path tracers' BSDF, evaluation and sampling (C++ and GLSL, see pt_sampling.h for the model and
// how it differs from IDKEngine's Shading.glsl; pt_bsdf_frame.h for the layers). Lobes, chosen by estimated albedo
// (one-sample MIS: a non-delta sample returns the pdf summed over all lobes, so ptSampleBsdf's pdf equals
// ptEvalBsdf's for the same direction):
//   specular     GGX reflection, F = mix(dielectric F (KHR_materials_specular), Schlick(baseColor), metallic)
//   diffuse      Lambert, (1 - metallic) (1 - transmission) (1 - diffuseTransmission) baseColor / pi times the
//                albedo-scaled weight (1 - Es(mu_o)) (1 - Es(mu_i)) / (1 - Es_avg) of pt_bsdf_frame.h
//   diffuse transmission  KHR_materials_diffuse_transmission (pt_diffuse_transmission.h): Lambert on the far side,
//                (1 - metallic) (1 - transmission) diffuseTransmission color / pi, the same weight at |mu_i|
//   transmission (1 - metallic) transmission (1 - max F_dielectric) baseColor: rough refraction (Walter 2007) when
//                the material has a volume (thickness > 0), else the reflection lobe mirrored through the surface
//   multiscatter GGX energy compensation (pt_energy.h), sampled by its own tabulated density
//   sheen        KHR_materials_sheen (pt_sheen.h), cosine-sampled
//   clearcoat    KHR_materials_clearcoat, GGX visible normals of the coat roughness (around the coat's own normal
//                with a clearcoatNormalTexture)
// KHR_materials_anisotropy makes the specular and transmission lobes' GGX anisotropic (the ptBase* hooks of
// pt_bsdf_frame.h, pt_anisotropy.h).
// The base lobes carry the layer weight of clearcoat and sheen. GGX alpha below kPtDeltaAlpha makes the specular
// and transmission lobes (and the clearcoat) delta: ptEvalBsdf leaves them out and ptSampleBsdf flags them.
#ifndef IDK_PT_BSDF_H
#define IDK_PT_BSDF_H
#include "pt_bsdf_frame.h"

IDK_GPU_BEGIN

// ---------------------------------------------------------------------------------------------------- evaluate
// f * |cos(wi)| of the non-delta lobes for local directions, and the matching pdf. wiSide: dot(wi, ng) in world.
IDK_INLINE vec3 ptEvalLocal(PtBsdfFrame f, vec3 wi, float wiSide, IDK_OUT(float) pdf) {
    pdf = 0.0f;
    vec3 value = vec3(0.0f);
    vec3 wo = f.wo;
    if (wi.z > 0.0f && wiSide > 0.0f) {
        vec3 h = normalize(wo + wi);
        float cosOH = max(dot(wo, h), 0.0f);
        vec3 base = vec3(0.0f);
        if (f.pDiff > 0.0f)
            base = f.baseColor * ((1.0f - f.metallic) * (1.0f - f.transmission) * (1.0f - f.diffTrans) *
                                  ptDiffuseWeight(f, wi.z) * kPtInvPi * wi.z);
        pdf += f.pDiff * wi.z * kPtInvPi;
        if (!f.delta) {
            float d = ptBaseD(f, h);
            base += ptSpecularFresnel(f, cosOH) * (d * ptBaseG2(f, wo, wi) / (4.0f * wo.z));
            pdf += f.pSpec * ptBaseG1(f, wo) * d / (4.0f * wo.z);
            base += f.msColor * ((1.0f - ptBaseAlbedo(f, wi)) * wi.z);
            if (f.pMs > 0.0f) pdf += f.pMs * ptMsPdf(wi.z, f.roughness);
        }
        value += base * f.layer;
        if (f.pSheen > 0.0f) {
            value += f.sheenColor * (f.coatLayer * ptSheenCos(wo, wi, f.sheenAlpha));
            pdf += f.pSheen * wi.z * kPtInvPi;
        }
        float coatI = ptCoatCos(f, wi);
        if (f.pCoat > 0.0f && !f.coatDelta && coatI > 0.0f) {  // the coat in its own normal's frame
            float coatO = f.coatCosO;
            float d = ptGgxD(ptCoatCos(f, h), f.coatAlpha);
            value += vec3(f.clearcoat * ptCoatFresnel(cosOH) * d * ptGgxG2(coatO, coatI, f.coatAlpha) / (4.0f * coatO));
            pdf += f.pCoat * ptGgxG1(coatO, f.coatAlpha) * d / (4.0f * coatO);
        }
    } else if (wi.z < 0.0f && wiSide < 0.0f) {
        if (f.pDiffTrans > 0.0f) {  // KHR_materials_diffuse_transmission
            float pass = ptDiffuseWeight(f, -wi.z);
            float weight = (1.0f - f.metallic) * (1.0f - f.transmission) * f.diffTrans * f.layer;
            value += ptDiffTransValue(f.diffTransColor, weight, pass, wi);
            pdf += f.pDiffTrans * ptDiffTransPdf(wi);
        }
    }
    if (wi.z < 0.0f && wiSide < 0.0f && !f.transDelta && f.pTrans > 0.0f) {
        vec3 tint = f.baseColor * ((1.0f - f.metallic) * f.transmission * f.transScale * f.layer);
        if (f.thick) {
            vec3 h = normalize(wo + wi * f.eta);
            if (h.z < 0.0f) h = -h;
            float cosOH = dot(wo, h);
            float cosIH = dot(wi, h);
            if (cosOH > 0.0f && cosIH < 0.0f) {
                float denom = cosOH + f.eta * cosIH;
                float d = ptBaseD(f, h);
                float pass = ptDielectricPass(f, cosOH);
                float g2 = ptBaseG2(f, wo, wi);
                value += tint * (pass * d * g2 * (-cosIH) * cosOH / (wo.z * denom * denom));
                pdf += f.pTrans * ptBaseVndfPdf(f, wo, h) * f.eta * f.eta * (-cosIH) / (denom * denom);
            }
        } else {
            vec3 wr = vec3(wi.x, wi.y, -wi.z);
            vec3 h = normalize(wo + wr);
            float d = ptBaseD(f, h);
            float pass = ptDielectricPass(f, max(dot(wo, h), 0.0f));
            value += tint * (pass * d * ptBaseG2(f, wo, wr) / (4.0f * wo.z));
            pdf += f.pTrans * ptBaseG1(f, wo) * d / (4.0f * wo.z);
        }
    }
    if (!ptFinite3(value) || !ptFinite(pdf)) {
        pdf = 0.0f;
        return vec3(0.0f);
    }
    return value;
}

// f(wo, wi) * |dot(wi, shading normal)| of the non-delta lobes, and the pdf ptSampleBsdf would sample wi with.
// wo and wi are unit world-space directions pointing away from the surface.
IDK_INLINE vec3 ptEvalBsdf(PtSurface s, vec3 wo, vec3 wi, IDK_OUT(float) pdf) {
    pdf = 0.0f;
    PtBsdfFrame f;
    if (!ptBsdfSetup(s, wo, f) || !ptFinite3(wi)) return vec3(0.0f);
    return ptEvalLocal(f, ptToLocal(wi, f.t, f.b, f.n), dot(wi, f.ng), pdf);
}

// ---------------------------------------------------------------------------------------------------- sample
IDK_INLINE vec3 ptSampleCosine(float u1, float u2) {
    float r = sqrt(u1);
    float phi = 2.0f * kPtPi * u2;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0f - u1, 0.0f)));
}

// Samples wi for wo with three uniforms (u.x picks the lobe, u.y/u.z the direction). weight = f |cos| / pdf,
// pdf is the solid-angle density (for a delta lobe: the lobe's discrete probability, with kPtLobeDeltaFlag set).
// Returns the lobe (kPtLobe*, kPtLobeNone with zero weight when the path is absorbed).
IDK_INLINE uint ptSampleBsdf(PtSurface s, vec3 wo, vec3 u, IDK_OUT(vec3) wi, IDK_OUT(vec3) weight,
                             IDK_OUT(float) pdf, IDK_OUT(uint) lobe) {
    wi = -wo;
    weight = vec3(0.0f);
    pdf = 0.0f;
    lobe = kPtLobeNone;
    PtBsdfFrame f;
    if (!ptBsdfSetup(s, wo, f)) return lobe;
    vec3 o = f.wo;
    vec3 l = vec3(0.0f);
    uint chosen = kPtLobeNone;
    bool isDelta = false;
    vec3 deltaWeight = vec3(0.0f);
    float deltaPdf = 0.0f;
    float c0 = f.pCoat;
    float c1 = c0 + f.pSheen;
    float c2 = c1 + f.pSpec;
    float c3 = c2 + f.pMs;
    float c4 = c3 + f.pDiff;
    float c5 = c4 + f.pDiffTrans;
    if (u.x < c0) {
        chosen = kPtLobeClearcoat;
        if (f.coatDelta) {
            l = f.coatTilted ? f.coatN * (2.0f * dot(o, f.coatN)) - o : vec3(-o.x, -o.y, o.z);
            isDelta = true;
            deltaPdf = f.pCoat;
            deltaWeight = vec3(f.clearcoat * ptCoatFresnel(f.coatCosO) / f.pCoat);
        } else if (f.coatTilted) {  // visible normals around the coat's normal
            vec3 ct;
            vec3 cb;
            ptBasis(f.coatN, ct, cb);
            vec3 oc = ptToLocal(o, ct, cb, f.coatN);
            oc.z = f.coatCosO;  // dot(o, coatN), floored as the evaluation's cosine
            vec3 h = ptToWorld(ptSampleGgxVndf(oc, f.coatAlpha, u.y, u.z), ct, cb, f.coatN);
            l = h * (2.0f * dot(o, h)) - o;
        } else {
            vec3 h = ptSampleGgxVndf(o, f.coatAlpha, u.y, u.z);
            l = h * (2.0f * dot(o, h)) - o;
        }
    } else if (u.x < c1) {
        chosen = kPtLobeSheen;
        l = ptSampleCosine(u.y, u.z);
    } else if (u.x < c2) {
        chosen = kPtLobeSpecular;
        if (f.delta) {
            l = vec3(-o.x, -o.y, o.z);
            isDelta = true;
            deltaPdf = f.pSpec;
            deltaWeight = ptSpecularFresnel(f, o.z) * (f.layer / f.pSpec);
        } else {
            vec3 h = ptBaseSampleVndf(f, o, u.y, u.z);
            l = h * (2.0f * dot(o, h)) - o;
        }
    } else if (u.x < c3) {
        chosen = kPtLobeMultiScatter;
        l = ptMsSample(f.roughness, (u.x - c2) / f.pMs, u.y, u.z);
    } else if (u.x < c4) {
        chosen = kPtLobeDiffuse;
        l = ptSampleCosine(u.y, u.z);
    } else if (u.x < c5) {
        chosen = kPtLobeDiffuseTransmission;
        l = ptDiffTransMirror(ptSampleCosine(u.y, u.z));
    } else if (f.pTrans > 0.0f) {
        chosen = kPtLobeTransmission;
        vec3 h = f.transDelta ? vec3(0.0f, 0.0f, 1.0f) : ptBaseSampleVndf(f, o, u.y, u.z);
        float cosOH = dot(o, h);
        float pass = ptDielectricPass(f, cosOH);
        if (f.thick) {
            float sin2T = (1.0f - cosOH * cosOH) / (f.eta * f.eta);
            if (sin2T >= 1.0f) return lobe;  // total internal reflection: the specular lobe covers it
            float cosT = sqrt(1.0f - sin2T);
            l = -o / f.eta + h * (cosOH / f.eta - cosT);
        } else {
            vec3 r = h * (2.0f * cosOH) - o;
            l = vec3(r.x, r.y, -r.z);
        }
        if (f.transDelta) {
            isDelta = true;
            deltaPdf = f.pTrans;
            float radianceScale = f.thick ? 1.0f / (f.eta * f.eta) : 1.0f;
            deltaWeight = f.baseColor * ((1.0f - f.metallic) * f.transmission * pass * radianceScale * f.transScale *
                                         f.layer / f.pTrans);
        }
    } else {
        return lobe;
    }
    l = normalize(l);
    vec3 w = ptToWorld(l, f.t, f.b, f.n);
    float side = dot(w, f.ng);
    if (!ptFinite3(w)) return lobe;
    bool reflects = chosen != kPtLobeTransmission && chosen != kPtLobeDiffuseTransmission;
    if ((reflects && (l.z <= 0.0f || side <= 0.0f)) || (!reflects && (l.z >= 0.0f || side >= 0.0f))) return lobe;
    if (isDelta) {
        if (!ptFinite3(deltaWeight)) return lobe;
        wi = w;
        weight = deltaWeight;
        pdf = deltaPdf;
        lobe = chosen | kPtLobeDeltaFlag;
        return lobe;
    }
    float p;
    vec3 value = ptEvalLocal(f, l, side, p);
    if (!(p > 0.0f)) return lobe;
    wi = w;
    weight = value / p;
    pdf = p;
    lobe = chosen;
    return lobe;
}

IDK_GPU_END

#endif
