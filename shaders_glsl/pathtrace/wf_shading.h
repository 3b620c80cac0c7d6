// wf_shading.h (GLSL include): the estimator of the wavefront stages, a per-vertex split of PT-A's reference
// integrator pathtrace::traceRadiance (engine/pathtrace/cpu_path_tracer.cpp) using the same shared maths
// (shared/pt_sampling.h) and the same random-number draw order, so that on scenes without alpha both tracers
// compute the same samples: path start (camera ray), then per vertex: medium transmittance, environment or
// emission with MIS, next-event estimation (as a shadow ray the shadow stage resolves), BSDF sampling, medium
// change, Russian roulette. Material evaluation is the twin of pathtrace::evaluateMaterial (pt_material.cpp).
#ifndef IDK_WF_SHADING_H
#define IDK_WF_SHADING_H
#include "wf_common.h"
#include "pt_sampling.h"
#include "bvh_traverse.glsl"

struct WfShadeResult {
    bool extend;
    bool hasShadowRay;
    GpuPtShadowRay shadowRay;
    GpuPtGuide guide;
};

// The path's sampler (shared/pt_sampler.h) resumed in a stage: its PCG state lives in GpuPtPath::rngState; the
// sobol sampler's scrambling seed and index are rebuilt from the pixel and the push block.
uint wfSampler(uint flags) { return (flags & kPtPushSobol) != 0u ? kPtSamplerSobol : kPtSamplerIndependent; }
PtRng wfResumeRng(uint state, uint pixel, uint sampleIndex, uint seed, uint flags) {
    PtRng rng = ptRngInitSampler(pixel, sampleIndex, seed, wfSampler(flags));
    rng.state = state;
    return rng;
}

GpuPtPath wfStartPath(GpuPtCamera cam, uint pixel, uvec2 extent, uint sampleIndex, uint seed, uint flags) {
    GpuPtPath p;
    PtRng rng = ptRngInitSampler(pixel, sampleIndex, seed, wfSampler(flags));
    // DRAW ORDER: the same draws in the same order and dimensions as pathtrace::renderReference (x jitter,
    // y jitter; the light's choice, slot, alias, ux, uy; the BSDF's u0, u1, u2; roulette), so equal seeds give
    // equal samples (tests/gpu/pathtrace SameSeedGivesTheCpuSamples).
    float jx = ptSample(rng, kPtDimJitterX);
    float jy = ptSample(rng, kPtDimJitterY);
    vec2 pos = vec2(float(pixel % extent.x) + jx, float(pixel / extent.x) + jy);
    ptCameraRay(cam.inverseViewProjection, pos, vec2(extent), p.origin, p.direction);
    p.depth = 0u;
    p.flags = kPtPathDeltaBounce;  // what the camera sees directly is counted in full
    p.throughput = vec3(1.0);
    p.bsdfPdf = 0.0;
    p.radiance = vec3(0.0);
    p.rngState = rng.state;
    p.previousPosition = p.origin;
    p.attenuationDistance = 0.0;
    p.attenuationColor = vec3(1.0);
    p.pad = 0.0;
    return p;
}

// pathtrace::emissionAt.
vec3 wfEmissionAt(GpuMaterial m, WfHitPoint h, vec3 wo) {
    if (m.emissiveFactor == vec3(0.0)) return vec3(0.0);
    if ((m.flags & kMaterialDoubleSided) == 0u && dot(wo, h.geometricNormal) <= 0.0) return vec3(0.0);
    return m.emissiveFactor * wfSampleSlot(m.slots[kSlotEmissive], h).rgb;
}

// pathtrace::mapNormal: normal mapping in the vertex tangent frame (B = cross(N, T) * w), z rebuilt from the
// remapped xy; the interpolated normal when the hit has no usable tangent.
vec3 wfMapNormal(WfHitPoint hit, vec4 texel, float scale) {
    vec3 n = hit.normal;
    if (hit.tangent.w == 0.0) return n;
    vec3 t = hit.tangent.xyz - n * dot(n, hit.tangent.xyz);
    float len2 = dot(t, t);
    if (!(len2 > 1e-20)) return n;
    t /= sqrt(len2);
    vec3 b = cross(n, t) * hit.tangent.w;
    vec2 xy = texel.xy * 2.0 - 1.0;
    vec3 tn = vec3(xy * scale, sqrt(max(1.0 - dot(xy, xy), 0.0)));
    return wfSafeNormalize(t * tn.x + b * tn.y + n * tn.z, n);
}

// pathtrace::evaluateMaterial (passThrough/blendAlpha are the trace stages' business).
PtSurface wfEvaluateMaterial(GpuPtSceneDesc sc, WfHitPoint hit, vec3 wo, out bool unlit) {
    GpuMaterial m = WfMaterialRef(sc.materials).m[hit.material];
    GpuPtMaterial pm = WfPtMaterialRef(sc.ptMaterials).m[hit.material];
    PtSurface s;
    vec4 base = m.baseColorFactor * wfSampleSlot(m.slots[kSlotBaseColor], hit) * hit.color;
    vec4 mr = wfSampleSlot(m.slots[kSlotMetallicRoughness], hit);
    s.baseColor = base.rgb;
    s.alpha = base.a;
    s.metallic = clamp(m.metallicFactor * mr.b, 0.0, 1.0);
    s.roughness = clamp(m.roughnessFactor * mr.g, 0.0, 1.0);
    float transmissionTexel = 1.0;
    if (pm.transmissionTexture != 0xFFFFFFFFu) {
        vec3 q = vec3(pm.transmissionTexCoord == 1u ? hit.uv1 : hit.uv0, 1.0);
        vec2 st = vec2(dot(pm.transmissionRow0, q), dot(pm.transmissionRow1, q));
        uint samplerIndex = WfUintRef(sc.ptSamplers).u[hit.material];
        transmissionTexel = textureLod(sampler2D(gTextures2D[nonuniformEXT(pm.transmissionTexture)],
                                                 gSamplers[nonuniformEXT(samplerIndex)]), st, 0.0).r;
    }
    s.transmission = clamp(pm.transmission * transmissionTexel, 0.0, 1.0);
    s.ior = pm.ior;
    s.thickness = pm.thickness;
    s.attenuationColor = pm.attenuationColor;
    s.attenuationDistance = pm.attenuationDistance;
    s.emission = wfEmissionAt(m, hit, wo);
    s.geometricNormal = hit.geometricNormal;
    // KHR_materials_specular / _clearcoat / _sheen: factor x texture channel (white placeholder slots
    // leave the factor). Only materials with the extension's flag sample: the rest keep the defaults.
    s.specular = pm.specular;
    s.specularColor = pm.specularColor;
    s.clearcoat = pm.clearcoat;
    s.clearcoatRoughness = pm.clearcoatRoughness;
    s.sheenColor = pm.sheenColor;
    s.sheenRoughness = pm.sheenRoughness;
    if ((m.flags & kMaterialSpecular) != 0u) {
        s.specular *= wfSampleSlot(m.slots[kSlotSpecular], hit).a;
        s.specularColor *= wfSampleSlot(m.slots[kSlotSpecularColor], hit).rgb;
    }
    if ((m.flags & kMaterialClearcoat) != 0u) {
        s.clearcoat *= wfSampleSlot(m.slots[kSlotClearcoat], hit).r;
        s.clearcoatRoughness *= wfSampleSlot(m.slots[kSlotClearcoatRoughness], hit).g;
    }
    if ((m.flags & kMaterialSheen) != 0u) {
        s.sheenColor *= wfSampleSlot(m.slots[kSlotSheenColor], hit).rgb;
        s.sheenRoughness *= wfSampleSlot(m.slots[kSlotSheenRoughness], hit).a;
    }
    // KHR_materials_diffuse_transmission, KHR_materials_dispersion (pathtrace::evaluateMaterial's twin).
    s.diffuseTransmission = 0.0;
    s.diffuseTransmissionColor = vec3(1.0);
    if ((m.flags & kMaterialDiffuseTransmission) != 0u) {
        s.diffuseTransmission = clamp(m.diffuseTransmission * wfSampleSlot(m.slots[kSlotDiffuseTransmission], hit).a,
                                      0.0, 1.0);
        s.diffuseTransmissionColor =
            m.diffuseTransmissionColor * wfSampleSlot(m.slots[kSlotDiffuseTransmissionColor], hit).rgb;
    }
    s.dispersion = (m.flags & kMaterialDispersion) != 0u ? m.dispersion : 0.0;
    // KHR_materials_iridescence: factor x R, thickness = mix(min, max, G) (white placeholder: the maximum).
    s.iridescence = 0.0;
    s.iridescenceIor = 1.3;
    s.iridescenceThickness = 0.0;
    s.clearcoatNormal = vec3(0.0);
    if ((m.flags & kMaterialIridescence) != 0u) {
        s.iridescence = clamp(m.iridescence * wfSampleSlot(m.slots[kSlotIridescence], hit).r, 0.0, 1.0);
        s.iridescenceIor = m.iridescenceIor;
        s.iridescenceThickness = mix(m.iridescenceThicknessMin, m.iridescenceThicknessMax,
                                     wfSampleSlot(m.slots[kSlotIridescenceThickness], hit).g);
    }
    // Normal mapping in the vertex tangent frame (B = cross(N, T) * w), z rebuilt from the remapped xy. A slot
    // without a normal texture samples the flat placeholder (xy = 0), which leaves n unchanged.
    vec3 n = hit.normal;
    if (hit.tangent.w != 0.0) n = wfMapNormal(hit, wfSampleSlot(m.slots[kSlotNormal], hit), m.normalScale);
    if (dot(n, hit.geometricNormal) < 0.0) n = -n;
    s.shadingNormal = n;
    // clearcoatNormalTexture (pathtrace::evaluateMaterial's twin; 0: the coat uses the shading normal).
    if ((m.flags & kMaterialClearcoatNormal) != 0u && s.clearcoat > 0.0 && hit.tangent.w != 0.0) {
        vec3 c = wfMapNormal(hit, wfSampleSlot(m.slots[kSlotClearcoatNormal], hit), m.clearcoatNormalScale);
        s.clearcoatNormal = dot(c, hit.geometricNormal) < 0.0 ? -c : c;
    }
    // KHR_materials_anisotropy (pathtrace::evaluateMaterial's twin): anisotropyTexture RG turns the direction, B
    // scales the strength.
    vec3 anisotropyTexel = vec3(1.0, 0.5, 1.0);
    if ((m.flags & kMaterialAnisotropyTexture) != 0u && pm.anisotropyStrength > 0.0)
        anisotropyTexel = wfSampleSlot(m.slots[kSlotAnisotropy], hit).rgb;
    s.anisotropyStrength = clamp(pm.anisotropyStrength * anisotropyTexel.b, 0.0, 1.0);
    s.anisotropyDirection = s.anisotropyStrength > 0.0
                                ? ptAnisotropyDirection(hit.tangent, hit.normal, pm.anisotropyRotation,
                                                        anisotropyTexel.rg)
                                : vec3(0.0);
    unlit = (m.flags & kMaterialUnlit) != 0u;
    if (unlit) {
        s.emission = base.rgb;
        s.baseColor = vec3(0.0);
        s.metallic = 0.0;
        s.transmission = 0.0;
        s.ior = 1.0;
        s.clearcoat = 0.0;
        s.sheenColor = vec3(0.0);
        s.anisotropyStrength = 0.0;
        s.diffuseTransmission = 0.0;
        s.dispersion = 0.0;
        s.iridescence = 0.0;
    }
    return s;
}

vec3 wfTransmittance(GpuPtPath path, float distance) {
    if ((path.flags & kPtPathInMedium) == 0u) return vec3(1.0);
    return ptVolumeTransmittance(path.attenuationColor, path.attenuationDistance, min(distance, 1e30));
}

// pathtrace::offsetOrigin.
vec3 wfOffsetOrigin(vec3 p, vec3 ng, vec3 towards) { return bvhOffsetRayOrigin(p, dot(towards, ng) >= 0.0 ? ng : -ng); }

vec3 wfEnvironmentRadiance(GpuPtSceneDesc s, uint texel) {
    WfFloatRef r = WfFloatRef(s.envRadiance);
    return vec3(r.f[3u * texel], r.f[3u * texel + 1u], r.f[3u * texel + 2u]);
}

// The sampleDirect half of pathtrace::traceRadiance: draws the same five numbers and builds the shadow ray whose
// visibility the shadow stage tests (the CPU tests it at once). False: no contribution.
bool wfSampleDirect(GpuPtSceneDesc s, GpuPtPath path, PtSurface surface, vec3 position, vec3 wo, uint dim,
                    inout PtRng rng, out GpuPtShadowRay ray) {
    ray.origin = position;
    ray.tMax = 0.0;
    ray.direction = vec3(0.0, 0.0, 1.0);
    ray.pixel = 0u;
    ray.contribution = vec3(0.0);
    ray.pad = 0.0;
    float envSelect = s.envSelectProbability;
    bool lights = s.lightCount > 0u;
    if (!lights && !(envSelect > 0.0)) return false;
    float choose = ptSample(rng, dim + kPtDimLightChoice);
    float uSlot = ptSample(rng, dim + kPtDimLightSlot);
    float uAlias = ptSample(rng, dim + kPtDimLightAlias);
    float ux = ptSample(rng, dim + kPtDimLightX);  // DRAW ORDER (see wfStartPath)
    float uy = ptSample(rng, dim + kPtDimLightY);
    vec2 u = vec2(ux, uy);
    vec3 direction;
    vec3 radiance;
    float distance;
    float pdf;
    bool isDelta = false;
    if (choose < envSelect || !lights) {
        WfAliasRef table = WfAliasRef(s.envAlias);
        uint slot = ptAliasSlot(uSlot, s.envWidth * s.envHeight);
        uint texel = ptAliasResolve(table.e[slot], slot, uAlias);
        float p = ptSampleEnvironment(texel, table.e[texel].probability, s.envWidth, s.envHeight, u, direction);
        if (!(p > 0.0)) return false;
        radiance = wfEnvironmentRadiance(s, texel);
        distance = kPtFar;
        pdf = envSelect * p;
    } else {
        WfAliasRef table = WfAliasRef(s.lightAlias);
        uint slot = ptAliasSlot(uSlot, s.lightCount);
        uint index = ptAliasResolve(table.e[slot], slot, uAlias);
        GpuPtLight light = WfLightRef(s.lights).l[index];
        PtLightSample ls;
        if (!ptSampleLight(light, position, u, ls)) return false;
        radiance = ls.radiance;
        if (light.type == kPtLightTriangle) {
            WfHitPoint lp = wfHitPoint(s, light.instance, light.triangle, ls.u, ls.v);
            radiance = wfEmissionAt(WfMaterialRef(s.materials).m[lp.material], lp, -ls.direction);
        }
        direction = ls.direction;
        distance = ls.distance;
        isDelta = ls.isDelta;
        pdf = (1.0 - envSelect) * table.e[index].probability * ls.pdf;
    }
    if (!(pdf > 0.0) || radiance == vec3(0.0)) return false;
    float bsdfPdf;
    vec3 f = ptEvalBsdf(surface, wo, direction, bsdfPdf);
    if (f == vec3(0.0)) return false;
    float w = isDelta ? 1.0 : ptPowerHeuristic(pdf, bsdfPdf);
    ray.origin = wfOffsetOrigin(position, surface.geometricNormal, direction);
    ray.direction = direction;
    ray.tMax = distance >= kPtFar ? uintBitsToFloat(0x7F800000u) : distance * (1.0 - 1e-4);
    ray.contribution = path.throughput * f * radiance * wfTransmittance(path, distance) * (w / pdf);
    return true;
}

// One path vertex: what the ray of segment bounce + 1 found, and the next segment.
WfShadeResult wfShade(GpuPtSceneDesc s, inout GpuPtPath path, GpuPtHit hit, PtRng rng, uint bounce, uint maxDepth,
                      uint rouletteDepth, bool nee) {
    WfShadeResult r;
    r.extend = false;
    r.hasShadowRay = false;
    r.guide.albedo = vec3(1.0);
    r.guide.normal = vec3(0.0);
    r.guide.depth = 0.0;
    r.guide.pad = 0.0;
    uint depth = bounce + 1u;
    path.depth = depth;
    path.flags &= ~kPtPathAlive;
    bool found = hit.triangle != kPtInvalid;
    path.throughput *= wfTransmittance(path, found ? hit.t : kPtFar);
    bool mis = nee && (path.flags & kPtPathDeltaBounce) == 0u;
    float envSelect = s.envSelectProbability;
    if (!found) {
        vec3 le = vec3(0.0);
        float w = 1.0;
        if (s.envWidth > 0u) {
            uint texel = ptEnvironmentTexel(path.direction, s.envWidth, s.envHeight);
            le = wfEnvironmentRadiance(s, texel);
            if (mis && envSelect > 0.0) {
                float lightPdf = envSelect * ptEnvironmentPdf(WfAliasRef(s.envAlias).e[texel].probability,
                                                              path.direction, s.envWidth, s.envHeight);
                w = ptPowerHeuristic(path.bsdfPdf, lightPdf);
            }
        }
        path.radiance += path.throughput * le * w;
        path.rngState = rng.state;
        return r;
    }
    WfHitPoint hp = wfHitPoint(s, hit.instance, hit.triangle, hit.u, hit.v);
    vec3 wo = -path.direction;
    bool unlit;
    PtSurface surface = wfEvaluateMaterial(s, hp, wo, unlit);
    vec3 position = hp.position;
    r.guide.albedo = unlit ? surface.emission : surface.baseColor;
    r.guide.normal = surface.shadingNormal;
    r.guide.depth = hit.t;
    if (surface.emission != vec3(0.0)) {
        float w = 1.0;
        uint first = WfInstanceRef(s.instances).i[hit.instance].firstLight;
        if (mis && first != kPtNoLight && s.lightCount > 0u) {
            uint index = first + hit.triangle;
            float lightPdf = (1.0 - envSelect) * WfAliasRef(s.lightAlias).e[index].probability *
                             ptLightPdf(WfLightRef(s.lights).l[index], path.previousPosition, position);
            w = ptPowerHeuristic(path.bsdfPdf, lightPdf);
        }
        path.radiance += path.throughput * surface.emission * w;
    }
    if (depth >= maxDepth || unlit) {
        path.rngState = rng.state;
        return r;
    }
    uint dim = ptDimVertexBase(depth);
    if (ptIsDispersive(surface)) {  // KHR_materials_dispersion (pathtrace::traceRadiance's twin)
        uint stored = (path.flags & kPtPathChannelMask) >> kPtPathChannelShift;
        uint channel = stored - 1u;
        if (stored == 0u) {
            channel = ptPickChannel(ptSample(rng, dim + kPtDimDispersion));  // DRAW ORDER: before NEE
            path.throughput *= ptChannelWeight(channel);
            path.flags = (path.flags & ~kPtPathChannelMask) | ((channel + 1u) << kPtPathChannelShift);
        }
        surface = ptDispersedSurface(surface, channel);
    }
    if (nee) r.hasShadowRay = wfSampleDirect(s, path, surface, position, wo, dim, rng, r.shadowRay);

    float u0 = ptSample(rng, dim + kPtDimBsdfLobe);  // DRAW ORDER (see wfStartPath)
    float u1 = ptSample(rng, dim + kPtDimBsdfX);
    float u2 = ptSample(rng, dim + kPtDimBsdfY);
    vec3 wi;
    vec3 weight;
    float pdf;
    uint lobe;
    ptSampleBsdf(surface, wo, vec3(u0, u1, u2), wi, weight, pdf, lobe);
    path.rngState = rng.state;
    if (lobe == kPtLobeNone) return r;
    path.throughput *= weight;
    if (!ptFinite3(path.throughput) || path.throughput == vec3(0.0)) return r;
    path.flags = (lobe & kPtLobeDeltaFlag) != 0u ? (path.flags | kPtPathDeltaBounce) : (path.flags & ~kPtPathDeltaBounce);
    path.bsdfPdf = pdf;
    path.previousPosition = position;
    uint through = lobe & ~kPtLobeDeltaFlag;  // into (or out of) a volume: both transmissions
    if ((through == kPtLobeTransmission || through == kPtLobeDiffuseTransmission) && surface.thickness > 0.0) {
        bool inside = dot(wi, surface.geometricNormal) < 0.0;  // into the volume: against its outside
        path.flags = inside ? (path.flags | kPtPathInMedium) : (path.flags & ~kPtPathInMedium);
        path.attenuationColor = surface.attenuationColor;
        path.attenuationDistance = surface.attenuationDistance;
    }
    path.origin = wfOffsetOrigin(position, surface.geometricNormal, wi);
    path.direction = wi;
    if (depth >= rouletteDepth) {
        float q = ptSurvivalProbability(path.throughput);
        bool survive = ptSample(rng, dim + kPtDimRoulette) < q;
        path.rngState = rng.state;
        if (!survive) return r;
        path.throughput /= q;
    }
    r.extend = true;
    path.flags |= kPtPathAlive;
    return r;
}

#endif
