// pt_anisotropy.h: anisotropic GGX for KHR_materials_anisotropy (C++ and GLSL, see pt_sampling.h), in a local
// frame whose x axis is the anisotropy direction: alpha_t (along x) = mix(alpha, 1, strength^2), alpha_b (along
// y) = alpha, the extension specification's reference BRDF:
//   D(h)       = 1 / (pi alpha_t alpha_b (x^2 / alpha_t^2 + y^2 / alpha_b^2 + z^2)^2)
//   Lambda(w)  = (sqrt(1 + (alpha_t^2 x^2 + alpha_b^2 y^2) / z^2) - 1) / 2, G2 height-correlated (Heitz 2014),
//                the specification's V_GGX_anisotropic = G2 / (4 |n.l| |n.v|)
//   sampling   visible normals of the stretched configuration (Heitz 2018), density G1(wo) max(wo.h, 0) D(h) / wo.z
// With alpha_t == alpha_b these are the isotropic functions of pt_microfacet.h (the BSDF still calls those when
// strength is 0, so an isotropic material renders bit for bit as before). IDKEngine has no anisotropy.
#ifndef IDK_PT_ANISOTROPY_H
#define IDK_PT_ANISOTROPY_H
#include "pt_microfacet.h"

IDK_GPU_BEGIN

IDK_INLINE float ptGgxAnisoD(vec3 h, float ax, float ay) {
    if (!(h.z > 0.0f)) return 0.0f;
    float x = h.x / ax;
    float y = h.y / ay;
    float d = x * x + y * y + h.z * h.z;
    return 1.0f / (kPtPi * ax * ay * d * d);
}

IDK_INLINE float ptGgxAnisoLambda(vec3 w, float ax, float ay) {
    float z2 = w.z * w.z;
    if (!(z2 > 0.0f)) return 1.0e30f;
    float t = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;
    return 0.5f * (sqrt(1.0f + t) - 1.0f);
}

IDK_INLINE float ptGgxAnisoG1(vec3 w, float ax, float ay) { return 1.0f / (1.0f + ptGgxAnisoLambda(w, ax, ay)); }

IDK_INLINE float ptGgxAnisoG2(vec3 wo, vec3 wi, float ax, float ay) {
    return 1.0f / (1.0f + ptGgxAnisoLambda(wo, ax, ay) + ptGgxAnisoLambda(wi, ax, ay));
}

// Visible-normal sampling with one alpha per axis: ptSampleGgxAnisoVndf (pt_microfacet.h, shared with the
// isotropic lobe).

// Density of ptSampleGgxAnisoVndf's h (per solid angle of h).
IDK_INLINE float ptGgxAnisoVndfPdf(vec3 wo, vec3 h, float ax, float ay) {
    return ptGgxAnisoG1(wo, ax, ay) * max(dot(wo, h), 0.0f) * ptGgxAnisoD(h, ax, ay) / wo.z;
}

// The anisotropy direction of KHR_materials_anisotropy in world space: the tangent-plane direction
// (cos rotation, sin rotation) rotated further by the texture's direction (RG remapped to [-1, 1]; (1, 0.5) when
// there is no texture), in the vertex frame T, B = cross(N, T) w. Zero when the vertex has no tangent (w == 0):
// the BSDF then takes its own basis around the normal.
IDK_INLINE vec3 ptAnisotropyDirection(vec4 tangent, vec3 n, float rotation, vec2 textureRg) {
    if (tangent.w == 0.0f) return vec3(0.0f);
    vec3 t = vec3(tangent.x, tangent.y, tangent.z);
    vec3 b = cross(n, t) * tangent.w;
    vec2 d = textureRg * 2.0f - vec2(1.0f);
    float c = cos(rotation);
    float s = sin(rotation);
    vec2 r = vec2(c * d.x - s * d.y, s * d.x + c * d.y);
    vec3 w = t * r.x + b * r.y;
    return ptFinite3(w) && dot(w, w) > 1.0e-20f ? normalize(w) : vec3(0.0f);
}

IDK_GPU_END

#endif
