// pt_sheen.h: the KHR_materials_sheen lobe (C++ and GLSL, see pt_sampling.h), written from the extension's
// specification: the "Charlie" distribution of Estevez & Kulla 2017 ("Production Friendly Microfacet Sheen BRDF"),
// D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi), alpha = sheenRoughness^2, and their visibility
// V = 1 / ((1 + lambda(NdotV) + lambda(NdotL)) 4 NdotV NdotL) with the fitted lambda the specification gives.
// The lobe is sheenColor * D * V; its directional albedo (sheen colour 1) is tabulated in pt_albedo_tables.h and
// scales the layers beneath it (albedo scaling, as the specification's implementation notes describe).
#ifndef IDK_PT_SHEEN_H
#define IDK_PT_SHEEN_H
#include "pt_common.h"

#ifdef __cplusplus
namespace idk::gpu {
using glm::pow;
}  // namespace idk::gpu
#endif

IDK_GPU_BEGIN

// Roughness below this makes D a needle the float range cannot hold (sin^(1/alpha)); the specification leaves
// the floor to the implementation.
IDK_CONST(float, kPtSheenMinRoughness, 0.07f);

IDK_INLINE float ptSheenAlpha(float roughness) {
    float r = max(roughness, kPtSheenMinRoughness);
    return r * r;
}

IDK_INLINE float ptSheenD(float cosH, float alpha) {
    float sin2 = max(1.0f - cosH * cosH, 0.0f);
    float invAlpha = 1.0f / alpha;
    return (2.0f + invAlpha) * pow(sin2, 0.5f * invAlpha) / (2.0f * kPtPi);
}

IDK_INLINE float ptSheenL(float x, float alpha) {
    float t = (1.0f - alpha) * (1.0f - alpha);
    float a = mix(21.5473f, 25.3245f, t);
    float b = mix(3.82987f, 3.32435f, t);
    float c = mix(0.19823f, 0.16801f, t);
    float d = mix(-1.97760f, -1.27393f, t);
    float e = mix(-4.32054f, -4.85967f, t);
    return a / (1.0f + b * pow(x, c)) + d * x + e;
}

IDK_INLINE float ptSheenLambda(float cosTheta, float alpha) {
    float c = clamp(cosTheta, 0.0f, 1.0f);
    return c < 0.5f ? exp(ptSheenL(c, alpha)) : exp(2.0f * ptSheenL(0.5f, alpha) - ptSheenL(1.0f - c, alpha));
}

// D * V * NdotL for unit local directions (z = normal) on the same side; 0 otherwise. Sheen colour excluded.
IDK_INLINE float ptSheenCos(vec3 wo, vec3 wi, float alpha) {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
    vec3 h = normalize(wo + wi);
    float v = 1.0f / ((1.0f + ptSheenLambda(wo.z, alpha) + ptSheenLambda(wi.z, alpha)) * 4.0f * wo.z);
    return ptSheenD(h.z, alpha) * v;
}

IDK_GPU_END

#endif
