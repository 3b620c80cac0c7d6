// pt_bsdf.h: the glTF metallic-roughness BSDF for the path tracers (C++ and GLSL, see pt_sampling.h for the
// model and how it differs from IDKEngine's Shading.glsl). Three lobes, chosen by estimated albedo:
//   specular     GGX reflection, F = mix(exact dielectric Fresnel(IOR), Schlick(baseColor), metallic)
//   diffuse      Lambert, (1 - metallic) (1 - transmission) (1 - F_dielectric) baseColor / pi
//   transmission (1 - metallic) transmission (1 - F_dielectric) baseColor: rough refraction (Walter 2007) when the
//                material has a volume (thickness > 0), else the reflection lobe mirrored through the surface.
// Non-delta samples return the full one-sample-MIS pdf (sum over lobes), so ptSampleBsdf's pdf equals
// ptEvalBsdf's pdf for the same direction. GGX alpha below kPtDeltaAlpha makes the specular and transmission
// lobes delta (perfect mirror / refraction): ptEvalBsdf leaves them out and ptSampleBsdf flags them.
#ifndef IDK_PT_BSDF_H
#define IDK_PT_BSDF_H
#include "pt_microfacet.h"

IDK_GPU_BEGIN

// ---------------------------------------------------------------------------------------------------- setup
// A surface prepared for one outgoing direction: the shading frame turned to wo's side, the lobe probabilities.
struct PtBsdfFrame {
    vec3 t;
    vec3 b;
    vec3 n;             // shading normal on wo's side, with dot(wo, n) > 0
    vec3 ng;            // geometric normal on wo's side
    vec3 wo;            // local
    vec3 baseColor;     // sanitised
    float metallic;
    float transmission;
    float alpha;        // GGX alpha (>= kPtDeltaAlpha when not delta)
    bool delta;         // specular and transmission lobes are delta
    bool transDelta;    // the transmission lobe is delta (delta, or a volume of IOR ~1: refraction does not bend)
    bool thick;         // transmission refracts (volume); else thin-walled
    float eta;          // thick: IOR on the far side / IOR on wo's side
    float etaFresnel;   // the eta of the Fresnel term on wo's side (eta when thick, the IOR when thin)
    float pSpec;        // lobe selection probabilities (sum 1)
    float pDiff;
    float pTrans;
};

IDK_INLINE vec3 ptSpecularFresnel(PtBsdfFrame f, float c) {
    return mix(vec3(ptFresnelDielectric(c, f.etaFresnel)), ptFresnelSchlick(f.baseColor, c), f.metallic);
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
    float roughness = ptSaturate(s.roughness);
    f.alpha = roughness * roughness;
    f.delta = f.alpha < kPtDeltaAlpha;
    f.transDelta = f.delta;
    f.alpha = max(f.alpha, kPtDeltaAlpha);
    f.pSpec = 0.0f;
    f.pDiff = 0.0f;
    f.pTrans = 0.0f;
    float ior = ptFinite(s.ior) ? clamp(s.ior, 1.0f, 4.0f) : 1.5f;
    f.thick = s.thickness > 0.0f;
    f.eta = 1.0f;
    f.etaFresnel = ior;
    if (!ptFinite3(wo) || !(dot(wo, wo) > 0.5f)) return false;

    vec3 ng = s.geometricNormal;
    vec3 n = s.shadingNormal;
    bool ngValid = ptFinite3(ng) && dot(ng, ng) > 0.25f;
    bool nValid = ptFinite3(n) && dot(n, n) > 0.25f;
    if (!ngValid) ng = nValid ? n : wo;
    if (!nValid) n = ng;
    ng = normalize(ng);
    n = normalize(n);
    bool outside = dot(wo, ng) >= 0.0f;
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
    if (f.thick) {
        f.eta = outside ? ior : 1.0f / ior;
        f.etaFresnel = f.eta;
    }
    // With eta ~1 rough refraction degenerates (the generalized half vector wo + eta wi vanishes): every facet
    // passes the ray straight on, a delta lobe.
    f.transDelta = f.delta || (f.thick && abs(f.eta - 1.0f) < 1.0e-3f);

    // Selection probabilities estimate each lobe's albedo from the Fresnel term at the macro normal. They are
    // floored wherever the lobe can still scatter (microfacets see other angles: total internal reflection at the
    // macro normal does not stop refraction through tilted facets, a black metal still has a grazing Schlick
    // term), so that every direction with f > 0 keeps a pdf > 0 and BSDF sampling stays unbiased.
    float fo = ptFresnelDielectric(f.wo.z, f.etaFresnel);
    float dielectric = 1.0f - f.metallic;
    float base = dielectric * max(1.0f - fo, 0.05f) * ptAverage(f.baseColor);
    float pSpec = ptAverage(ptSpecularFresnel(f, f.wo.z));
    if (f.metallic > 0.0f || f.etaFresnel != 1.0f) pSpec = max(pSpec, 1.0e-3f);
    float pDiff = base * (1.0f - f.transmission);
    float pTrans = base * f.transmission;
    float sum = pSpec + pDiff + pTrans;
    if (!(sum > 0.0f) || !ptFinite(sum)) return false;
    f.pSpec = pSpec / sum;
    f.pDiff = pDiff / sum;
    f.pTrans = pTrans / sum;
    return true;
}

// ---------------------------------------------------------------------------------------------------- evaluate
// f * |cos(wi)| of the non-delta lobes for local directions, and the matching pdf. wiSide: dot(wi, ng) in world.
IDK_INLINE vec3 ptEvalLocal(PtBsdfFrame f, vec3 wi, float wiSide, IDK_OUT(float) pdf) {
    pdf = 0.0f;
    vec3 value = vec3(0.0f);
    vec3 wo = f.wo;
    if (wi.z > 0.0f && wiSide > 0.0f) {
        vec3 h = normalize(wo + wi);
        float cosOH = max(dot(wo, h), 0.0f);
        float fd = ptFresnelDielectric(cosOH, f.etaFresnel);
        value += f.baseColor * ((1.0f - f.metallic) * (1.0f - f.transmission) * (1.0f - fd) * kPtInvPi * wi.z);
        pdf += f.pDiff * wi.z * kPtInvPi;
        if (!f.delta) {
            float d = ptGgxD(h.z, f.alpha);
            value += ptSpecularFresnel(f, cosOH) * (d * ptGgxG2(wo.z, wi.z, f.alpha) / (4.0f * wo.z));
            pdf += f.pSpec * ptGgxG1(wo.z, f.alpha) * d / (4.0f * wo.z);
        }
    } else if (wi.z < 0.0f && wiSide < 0.0f && !f.transDelta && f.pTrans > 0.0f) {
        vec3 tint = f.baseColor * ((1.0f - f.metallic) * f.transmission);
        if (f.thick) {
            vec3 h = normalize(wo + wi * f.eta);
            if (h.z < 0.0f) h = -h;
            float cosOH = dot(wo, h);
            float cosIH = dot(wi, h);
            if (cosOH > 0.0f && cosIH < 0.0f) {
                float denom = cosOH + f.eta * cosIH;
                float d = ptGgxD(h.z, f.alpha);
                float fd = ptFresnelDielectric(cosOH, f.eta);
                float g2 = ptGgxG2(wo.z, -wi.z, f.alpha);
                value += tint * ((1.0f - fd) * d * g2 * (-cosIH) * cosOH / (wo.z * denom * denom));
                pdf += f.pTrans * ptGgxVndfPdf(wo, h, f.alpha) * f.eta * f.eta * (-cosIH) / (denom * denom);
            }
        } else {
            vec3 wr = vec3(wi.x, wi.y, -wi.z);
            vec3 h = normalize(wo + wr);
            float d = ptGgxD(h.z, f.alpha);
            float fd = ptFresnelDielectric(max(dot(wo, h), 0.0f), f.etaFresnel);
            value += tint * ((1.0f - fd) * d * ptGgxG2(wo.z, wr.z, f.alpha) / (4.0f * wo.z));
            pdf += f.pTrans * ptGgxG1(wo.z, f.alpha) * d / (4.0f * wo.z);
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
    if (u.x < f.pSpec) {
        chosen = kPtLobeSpecular;
        if (f.delta) {
            l = vec3(-o.x, -o.y, o.z);
            isDelta = true;
            deltaPdf = f.pSpec;
            deltaWeight = ptSpecularFresnel(f, o.z) / f.pSpec;
        } else {
            vec3 h = ptSampleGgxVndf(o, f.alpha, u.y, u.z);
            l = h * (2.0f * dot(o, h)) - o;
        }
    } else if (u.x < f.pSpec + f.pDiff) {
        chosen = kPtLobeDiffuse;
        float r = sqrt(u.y);
        float phi = 2.0f * kPtPi * u.z;
        l = vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0f - u.y, 0.0f)));
    } else if (f.pTrans > 0.0f) {
        chosen = kPtLobeTransmission;
        vec3 h = f.transDelta ? vec3(0.0f, 0.0f, 1.0f) : ptSampleGgxVndf(o, f.alpha, u.y, u.z);
        float cosOH = dot(o, h);
        float fd = ptFresnelDielectric(cosOH, f.etaFresnel);
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
            deltaWeight = f.baseColor * ((1.0f - f.metallic) * f.transmission * (1.0f - fd) * radianceScale / f.pTrans);
        }
    } else {
        return lobe;
    }
    l = normalize(l);
    vec3 w = ptToWorld(l, f.t, f.b, f.n);
    float side = dot(w, f.ng);
    if (!ptFinite3(w)) return lobe;
    bool reflects = chosen != kPtLobeTransmission;
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
