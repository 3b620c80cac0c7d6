// pt_energy.h: lookups into the precomputed directional-albedo tables (pt_albedo_tables.h; grids in
// pt_albedo_layout.h) and the multiple-scattering energy compensation built on them (C++ and GLSL, see
// pt_sampling.h). Single-scattering GGX loses the energy of light that bounces more than once between microfacets
// (up to ~60% for a rough metal at grazing view). The compensation follows Kulla & Conty 2017 ("Revisiting
// Physically Based Shading at Imageworks"): a reciprocal diffuse-like lobe (sampled by ptMsSample)
//   f_ms(o, i) = Fms (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - Eavg)),  Fms = Favg^2 Eavg / (1 - Favg (1 - Eavg))
// (exactly 1 - E(mu_o) more albedo for a white metal), and for refraction through a rough dielectric interface
// the single-scattering lobes are scaled by 1 / E_dielectric(mu_o) (not reciprocal, as refraction is not).
// KHR_materials_anisotropy: E(o) also depends on the view's azimuth in the anisotropy frame, and the same lobe with
// the anisotropic table's E(o), E(i) and its hemispherical mean Eavg stays reciprocal and adds exactly 1 - E(o) for
// a white metal (the integral of (1 - E(i)) cos / pi is 1 - Eavg for the interpolant the lookup reads).
// The tables are constant arrays: lookups here are bilinear/trilinear by hand so C++ and GLSL agree. On a
// discrete GPU a divergent index into a large constant array is served from local/constant memory one lane at a
// time; there a 2D/3D texture with hardware filtering would be the choice (lavapipe gains nothing from it).
#ifndef IDK_PT_ENERGY_H
#define IDK_PT_ENERGY_H
#include "pt_albedo_tables.h"
#include "pt_common.h"

// Table reads. C++: the constant arrays. GLSL: one storage buffer with every table packed at its k*Offset
// (render::albedoTableData uploads it), reached through gPtAlbedoTables, which each shader that shades sets from
// its scene or frame constants at the start of main() (a GLSL constant array indexed at run time would be copied
// into a local variable at every lookup by glslang: tens of kilobytes each).
// IDK_ALBEDO_TABLE is a table passed to a lookup function: a pointer in C++, its offset into the buffer in GLSL.
#ifdef __cplusplus
#define IDK_ALBEDO(table, i) table[i]
#define IDK_ALBEDO_TABLE const float*
#define IDK_ALBEDO_REF(table) table
#define IDK_ALBEDO_READ(ref, i) ref[i]
#else
#extension GL_EXT_buffer_reference : require
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer PtAlbedoTablesRef { float v[]; };
uint64_t gPtAlbedoTables = 0ul;
#define IDK_ALBEDO(table, i) PtAlbedoTablesRef(gPtAlbedoTables).v[table##Offset + (i)]
#define IDK_ALBEDO_TABLE uint
#define IDK_ALBEDO_REF(table) table##Offset
#define IDK_ALBEDO_READ(ref, i) PtAlbedoTablesRef(gPtAlbedoTables).v[(ref) + (i)]
#endif

IDK_GPU_BEGIN

// Cell index and fraction for coordinate t in [0, 1] on n nodes.
IDK_INLINE uint ptAlbedoCell(float t, uint n, IDK_OUT(float) frac) {
    float x = clamp(ptFinite(t) ? t : 0.0f, 0.0f, 1.0f) * float(n - 1u);
    uint i = min(uint(x), n - 2u);
    frac = x - float(i);
    return i;
}

// Bilinear lookup in a (mu, roughness) table of nMu x nRough nodes, mu fastest.
IDK_INLINE float ptAlbedoBilinear(IDK_ALBEDO_TABLE table, float mu, uint nMu, float roughness, uint nRough) {
    float fx;
    float fy;
    uint i = ptAlbedoCell(mu, nMu, fx);
    uint j = ptAlbedoCell(roughness, nRough, fy);
    uint k = j * nMu + i;
    float a = mix(IDK_ALBEDO_READ(table, k), IDK_ALBEDO_READ(table, k + 1u), fx);
    float b = mix(IDK_ALBEDO_READ(table, k + nMu), IDK_ALBEDO_READ(table, k + nMu + 1u), fx);
    return mix(a, b, fy);
}

// Trilinear lookup in a (mu, roughness, IOR coordinate) table of nMu x nRough x nIor nodes, mu fastest.
IDK_INLINE float ptAlbedoTrilinear(IDK_ALBEDO_TABLE table, float mu, uint nMu, float roughness, uint nRough,
                                   float iorCoord, uint nIor) {
    float fx;
    float fy;
    float fz;
    uint i = ptAlbedoCell(mu, nMu, fx);
    uint j = ptAlbedoCell(roughness, nRough, fy);
    uint k = ptAlbedoCell(iorCoord, nIor, fz);
    float e[2];
    for (uint dk = 0u; dk < 2u; ++dk) {
        uint row = ((k + dk) * nRough + j) * nMu + i;
        float a = mix(IDK_ALBEDO_READ(table, row), IDK_ALBEDO_READ(table, row + 1u), fx);
        float b = mix(IDK_ALBEDO_READ(table, row + nMu), IDK_ALBEDO_READ(table, row + nMu + 1u), fx);
        e[dk] = mix(a, b, fy);
    }
    return mix(e[0], e[1], fz);
}

// E(mu, roughness) of GGX reflection with F = 1.
IDK_INLINE float ptAlbedoMetal(float mu, float roughness) {
    return ptAlbedoBilinear(IDK_ALBEDO_REF(kPtAlbedoMetal), mu, kPtAlbedoMu, roughness, kPtAlbedoRough);
}

IDK_INLINE float ptAlbedoMetalAvg(float roughness) {
    float fy;
    uint j = ptAlbedoCell(roughness, kPtAlbedoRough, fy);
    return mix(IDK_ALBEDO(kPtAlbedoMetalAvg, j), IDK_ALBEDO(kPtAlbedoMetalAvg, j + 1u), fy);
}

// Directional albedo of the sheen lobe with sheen colour 1.
IDK_INLINE float ptAlbedoSheen(float mu, float roughness) {
    return ptAlbedoBilinear(IDK_ALBEDO_REF(kPtAlbedoSheen), mu, kPtAlbedoMu, roughness, kPtAlbedoRough);
}

// Reflection + refraction albedo of a rough dielectric interface; inside: light leaves into the denser side's
// interior (eta = 1 / ior). The table holds the outside half, then the inside half.
IDK_INLINE float ptAlbedoDielectric(float mu, float roughness, float ior, bool inside) {
    uint sideOffset = inside ? kPtAlbedoDielIor * kPtAlbedoDielRough * kPtAlbedoDielMu : 0u;
    return ptAlbedoTrilinear(IDK_ALBEDO_REF(kPtAlbedoDielectric) + sideOffset, mu, kPtAlbedoDielMu, roughness,
                             kPtAlbedoDielRough, ptAlbedoIorCoord(ior), kPtAlbedoDielIor);
}

// KHR_materials_anisotropy: E(wo) of the anisotropic GGX with F = 1 for a local direction (x along the anisotropy
// direction), perceptual base roughness and strength; quadrilinear in (mu, |cos phi|, roughness, strength).
IDK_INLINE uint ptAlbedoAnisoIndex(uint l, uint k, uint j, uint i) {
    return ((l * kPtAlbedoAnisoRough + k) * kPtAlbedoAnisoAz + j) * kPtAlbedoAnisoMu + i;
}

IDK_INLINE float ptAlbedoAnisoMetal(vec3 w, float roughness, float strength) {
    float fx;
    float fq;
    float fr;
    float fs;
    float p2 = w.x * w.x + w.y * w.y;
    float q = p2 > 1.0e-12f ? abs(w.x) * inversesqrt(p2) : 1.0f;  // at the pole every azimuth gives the same E
    uint i = ptAlbedoCell(w.z, kPtAlbedoAnisoMu, fx);
    uint j = ptAlbedoCell(q, kPtAlbedoAnisoAz, fq);
    uint k = ptAlbedoCell(roughness, kPtAlbedoAnisoRough, fr);
    uint l = ptAlbedoCell(strength, kPtAlbedoAnisoStrength, fs);
    float e = 0.0f;
    for (uint corner = 0u; corner < 4u; ++corner) {  // the four (r, s) corners, bilinear in (mu, q) at each
        uint dk = corner & 1u;
        uint dl = corner >> 1u;
        uint base = ptAlbedoAnisoIndex(l + dl, k + dk, j, i);
        float a = mix(IDK_ALBEDO(kPtAlbedoAnisoMetal, base), IDK_ALBEDO(kPtAlbedoAnisoMetal, base + 1u), fx);
        float b = mix(IDK_ALBEDO(kPtAlbedoAnisoMetal, base + kPtAlbedoAnisoMu),
                      IDK_ALBEDO(kPtAlbedoAnisoMetal, base + kPtAlbedoAnisoMu + 1u), fx);
        e += mix(a, b, fq) * (dk == 1u ? fr : 1.0f - fr) * (dl == 1u ? fs : 1.0f - fs);
    }
    return e;
}

IDK_INLINE float ptAlbedoAnisoAvg(float roughness, float strength) {
    float fr;
    float fs;
    uint k = ptAlbedoCell(roughness, kPtAlbedoAnisoRough, fr);
    uint l = ptAlbedoCell(strength, kPtAlbedoAnisoStrength, fs);
    uint a = l * kPtAlbedoAnisoRough + k;
    uint b = a + kPtAlbedoAnisoRough;
    return mix(mix(IDK_ALBEDO(kPtAlbedoAnisoAvg, a), IDK_ALBEDO(kPtAlbedoAnisoAvg, a + 1u), fr),
               mix(IDK_ALBEDO(kPtAlbedoAnisoAvg, b), IDK_ALBEDO(kPtAlbedoAnisoAvg, b + 1u), fr), fs);
}

// Albedo of the GGX reflection lobe alone with the exact dielectric Fresnel of `ior` (>= 1; light from outside),
// single scattering.
IDK_INLINE float ptAlbedoSpecular(float mu, float roughness, float ior) {
    return ptAlbedoTrilinear(IDK_ALBEDO_REF(kPtAlbedoSpecular), mu, kPtAlbedoDielMu, roughness, kPtAlbedoSpecRough,
                             ptAlbedoIorCoord(ior), kPtAlbedoSpecIor);
}

// Its cosine-weighted average, of the interpolated rows (so that it is exactly the average of ptAlbedoSpecular).
IDK_INLINE float ptAlbedoSpecularAvg(float roughness, float ior) {
    float fy;
    float fz;
    uint j = ptAlbedoCell(roughness, kPtAlbedoSpecRough, fy);
    uint k = ptAlbedoCell(ptAlbedoIorCoord(ior), kPtAlbedoSpecIor, fz);
    uint r0 = k * kPtAlbedoSpecRough + j;
    uint r1 = r0 + kPtAlbedoSpecRough;
    float a = mix(IDK_ALBEDO(kPtAlbedoSpecularAvg, r0), IDK_ALBEDO(kPtAlbedoSpecularAvg, r0 + 1u), fy);
    float b = mix(IDK_ALBEDO(kPtAlbedoSpecularAvg, r1), IDK_ALBEDO(kPtAlbedoSpecularAvg, r1 + 1u), fy);
    return mix(a, b, fz);
}

// The multiple-scattering lobe's sampling density, ~ (1 - E(mu)) mu like the lobe itself (a cosine density
// would give weights up to ~(1 - E(0)) / (1 - Eavg): hundreds on smooth metals at grazing light): a mixture of the
// two roughness rows around `roughness`, each piecewise over kPtAlbedoMsBins bins of mu with density ~ mu inside
// a bin. Solid-angle pdf of a direction with cos theta mu.
IDK_INLINE float ptMsPdf(float mu, float roughness) {
    if (!(mu > 0.0f)) return 0.0f;
    float fy;
    uint j = ptAlbedoCell(roughness, kPtAlbedoRough, fy);
    uint k = min(uint(mu * float(kPtAlbedoMsBins)), kPtAlbedoMsBins - 1u);
    float a = float(k) / float(kPtAlbedoMsBins);
    float b = float(k + 1u) / float(kPtAlbedoMsBins);
    float p = mix(IDK_ALBEDO(kPtAlbedoMsBinTable, j * kPtAlbedoMsBins + k), IDK_ALBEDO(kPtAlbedoMsBinTable, (j + 1u) * kPtAlbedoMsBins + k), fy);
    return p * mu / (kPtPi * (b * b - a * a));
}

// Samples the local direction of ptMsPdf from three uniforms (row choice, bin choice reused inside the bin, phi).
IDK_INLINE vec3 ptMsSample(float roughness, float uRow, float uBin, float uPhi) {
    float fy;
    uint j = ptAlbedoCell(roughness, kPtAlbedoRough, fy);
    uint row = (uRow < fy ? j + 1u : j) * kPtAlbedoMsBins;
    uint k = kPtAlbedoMsBins - 1u;
    float acc = 0.0f;
    float inside = 0.5f;
    for (uint i = 0u; i < kPtAlbedoMsBins; ++i) {
        float p = IDK_ALBEDO(kPtAlbedoMsBinTable, row + i);
        if (uBin < acc + p && p > 0.0f) {
            k = i;
            inside = clamp((uBin - acc) / p, 0.0f, 1.0f);
            break;
        }
        acc += p;
    }
    float a = float(k) / float(kPtAlbedoMsBins);
    float b = float(k + 1u) / float(kPtAlbedoMsBins);
    float mu = sqrt(a * a + inside * (b * b - a * a));
    float s = sqrt(max(1.0f - mu * mu, 0.0f));
    float phi = 2.0f * kPtPi * uPhi;
    return vec3(s * cos(phi), s * sin(phi), max(mu, 1.0e-6f));
}

// Kulla-Conty's colour of the multiple-scattering lobe for an average Fresnel reflectance favg.
IDK_INLINE vec3 ptMultiScatterColor(vec3 favg, float eavg) {
    return favg * favg * eavg / max(vec3(1.0f) - favg * (1.0f - eavg), vec3(1.0e-4f));
}

// Average (cosine-weighted hemispherical) exact dielectric Fresnel reflectance for relative IOR eta (Kulla &
// Conty 2017's fit for eta >= 1; eta < 1 takes 1 / eta, the outside's average, an approximation).
IDK_INLINE float ptFresnelDielectricAverage(float eta) {
    float e = max(eta, 1.0f / max(eta, 1.0e-3f));
    return (e - 1.0f) / (4.08567f + 1.00071f * e);
}

// The albedo-scaled Lambert weight beneath a dielectric reflection lobe (shared/pt_bsdf_frame.h's header; the
// path tracers and the raster's direct light, include/material_layers.glsl, share these two): the lobe's albedo
// Es(mu) is linear in its Fresnel F = specular (f0' + (1 - f0') w(v.h)), w the exact curve of the IOR remapped to
// [0, 1]: Es = eF0 E_metal + eK (E_refl - f0Ior E_metal) + eMs (1 - E_metal) with the coefficients below (f0' its
// strongest channel, eMs the Kulla-Conty multiple scattering of the average Fresnel favg; none for a delta lobe).
IDK_INLINE vec3 ptDielectricAlbedoCoeffs(float specular, vec3 specularF0, float f0Ior, vec3 favg, float eAvg,
                                         bool delta) {
    float f0Max = ptMaxComponent(specularF0);
    return vec3(specular * f0Max, specular * (1.0f - f0Max) / max(1.0f - f0Ior, 1.0e-4f),
                delta ? 0.0f : ptMaxComponent(ptMultiScatterColor(favg, eAvg)));
}

// Es from the coefficients and the table values E_metal (em) and E_refl (er) at one mu (or their averages).
IDK_INLINE float ptDielectricAlbedoOf(vec3 c, float f0Ior, float em, float er) {
    return c.x * em + c.y * (er - f0Ior * em) + c.z * (1.0f - em);
}

// Average (cosine-weighted hemispherical) Schlick reflectance: f0 + (1 - f0) / 21.
IDK_INLINE vec3 ptSchlickAverage(vec3 f0) { return f0 + (vec3(1.0f) - f0) * (1.0f / 21.0f); }

IDK_GPU_END

#endif
