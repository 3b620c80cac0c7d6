// pt_microfacet.h: the microfacet and Fresnel building blocks of the path tracers' BSDF (pt_bsdf.h), one source
// for C++ and GLSL (see pt_sampling.h): the GGX / Trowbridge-Reitz distribution, Smith Lambda with the
// height-correlated masking-shadowing term (Heitz 2014, "Understanding the Masking-Shadowing Function"),
// visible-normal sampling (Heitz 2018) and its density, exact dielectric and Schlick Fresnel. IDKEngine's path
// tracer has none of these (it bends mirror directions toward the diffuse one by roughness, reference 2.1); its
// rasterizer has D, V and Schlick in include/Pbr.glsl, which include/pbr.glsl ports for our raster.
#ifndef IDK_PT_MICROFACET_H
#define IDK_PT_MICROFACET_H
#include "pt_common.h"

IDK_GPU_BEGIN

// ---------------------------------------------------------------------------------------------------- GGX
IDK_INLINE float ptGgxD(float cosH, float alpha) {
    float a2 = alpha * alpha;
    float d = cosH * cosH * (a2 - 1.0f) + 1.0f;
    return cosH > 0.0f ? a2 / (kPtPi * d * d) : 0.0f;
}

// Smith Lambda for GGX at a direction with |cos theta| = c.
IDK_INLINE float ptGgxLambda(float c, float alpha) {
    float c2 = c * c;
    if (!(c2 > 0.0f)) return 1.0e30f;
    float tan2 = max(1.0f - c2, 0.0f) / c2;
    return 0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

IDK_INLINE float ptGgxG1(float c, float alpha) { return 1.0f / (1.0f + ptGgxLambda(c, alpha)); }

// Height-correlated masking-shadowing (Heitz 2014).
IDK_INLINE float ptGgxG2(float cosO, float cosI, float alpha) {
    return 1.0f / (1.0f + ptGgxLambda(cosO, alpha) + ptGgxLambda(cosI, alpha));
}

// A visible normal for local wo (wo.z > 0), Heitz 2018, "Sampling the GGX Distribution of Visible Normals", with
// one alpha per axis (KHR_materials_anisotropy; pt_anisotropy.h): stretch to the unit-roughness configuration,
// sample its visible hemisphere, unstretch.
IDK_INLINE vec3 ptSampleGgxAnisoVndf(vec3 wo, float ax, float ay, float u1, float u2) {
    vec3 vh = normalize(vec3(ax * wo.x, ay * wo.y, wo.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u1);
    float phi = 2.0f * kPtPi * u2;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * sqrt(max(1.0f - p1 * p1, 0.0f)) + s * p2;
    vec3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(1.0f - p1 * p1 - p2 * p2, 0.0f));
    return normalize(vec3(ax * nh.x, ay * nh.y, max(nh.z, 1.0e-6f)));
}

// The isotropic case: the same arithmetic with ax = ay = alpha.
IDK_INLINE vec3 ptSampleGgxVndf(vec3 wo, float alpha, float u1, float u2) {
    return ptSampleGgxAnisoVndf(wo, alpha, alpha, u1, u2);
}

// Density of ptSampleGgxVndf's h (per solid angle of h).
IDK_INLINE float ptGgxVndfPdf(vec3 wo, vec3 h, float alpha) {
    return ptGgxG1(wo.z, alpha) * max(dot(wo, h), 0.0f) * ptGgxD(h.z, alpha) / wo.z;
}

// ---------------------------------------------------------------------------------------------------- Fresnel
// Unpolarised Fresnel reflectance for cosine cosI on the incident side and eta = eta_transmitted / eta_incident;
// 1 under total internal reflection.
IDK_INLINE float ptFresnelDielectric(float cosI, float eta) {
    float c = clamp(cosI, 0.0f, 1.0f);
    float sin2T = (1.0f - c * c) / (eta * eta);
    if (sin2T >= 1.0f) return 1.0f;
    float cosT = sqrt(1.0f - sin2T);
    float rs = (c - eta * cosT) / (c + eta * cosT);
    float rp = (eta * c - cosT) / (eta * c + cosT);
    return 0.5f * (rs * rs + rp * rp);
}

IDK_INLINE vec3 ptFresnelSchlick(vec3 f0, float c) {
    float m = clamp(1.0f - c, 0.0f, 1.0f);
    float m2 = m * m;
    return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}


IDK_GPU_END

#endif
