// pt_iridescence.h: the thin-film Fresnel of KHR_materials_iridescence (C++ and GLSL, see pt_sampling.h), the
// extension specification's reference formulation (Belcour & Barla 2017, "A Practical Extension to Microfacet
// Theory for the Modeling of Varying Iridescence"): a film of IOR n2 and thickness d (nanometres) between air and
// a base whose reflectance at normal incidence is baseF0. Both interfaces reflect with Schlick's curve (air/film
// at f0 of n2, film/base at the f0 between n2 and the IOR baseF0 implies), the Airy series of the waves bouncing
// inside the film is kept to its constant term and its first two harmonics, and each harmonic is integrated over
// the visible spectrum against the CIE XYZ matching functions in closed form (their Gaussian fit's Fourier
// transform), then converted to linear sRGB (Rec. 709 primaries). The result replaces the Fresnel term of the
// reflection lobes, weighted by the iridescence factor (ptIridescentFresnel). IDKEngine has no iridescence.
// Exactness where the film vanishes: a thickness of 0 or a factor of 0 returns the plain Fresnel unchanged (the
// series itself does not: its truncation and clamps leave an error of about 1e-3 there).
#ifndef IDK_PT_IRIDESCENCE_H
#define IDK_PT_IRIDESCENCE_H
#include "pt_microfacet.h"

IDK_GPU_BEGIN

// cos(a) with a first brought into [-pi, pi]: Vulkan bounds cos's error only there, and the phases below reach
// tens of radians for micrometre films (lavapipe's libm reduces exactly; a GPU's hardware cos may not).
IDK_INLINE float ptCosReduced(float a) {
    float r = a - 2.0f * kPtPi * float(int(a * (0.5f / kPtPi)));
    if (r > kPtPi) r -= 2.0f * kPtPi;
    if (r < -kPtPi) r += 2.0f * kPtPi;
    return cos(r);
}

// The XYZ response of the m-th harmonic at optical path difference opd (nm) and phase shift, as linear sRGB. The
// Gaussian parameters are the spectral fit the specification gives (normalised so that opd 0, shift 0 is white).
IDK_INLINE vec3 ptThinFilmSensitivity(float opd, vec3 shift) {
    float phase = 2.0f * kPtPi * opd * 1.0e-9f;
    vec3 amplitude = vec3(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
    vec3 position = vec3(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
    vec3 variance = vec3(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
    vec3 xyz = vec3(0.0f);
    for (int i = 0; i < 3; ++i)
        xyz[i] = amplitude[i] * sqrt(2.0f * kPtPi * variance[i]) * ptCosReduced(position[i] * phase + shift[i]) *
                 exp(-phase * phase * variance[i]);
    xyz.x += 9.7470e-14f * sqrt(2.0f * kPtPi * 4.5282e+09f) * ptCosReduced(2.2399e+06f * phase + shift.x) *
             exp(-4.5282e+09f * phase * phase);
    xyz *= 1.0f / 1.0685e-7f;
    // XYZ -> linear sRGB (D65), rows of the standard matrix.
    return vec3(3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
                -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
                0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z);
}

IDK_INLINE float ptSchlick1(float f0, float c) {
    float m = ptSaturate(1.0f - c);
    float m2 = m * m;
    return f0 + (1.0f - f0) * m2 * m2 * m;
}

// The film's reflectance (linear sRGB) seen from air at cosine cosTheta1, film IOR filmIor (>= 1), thickness in
// nanometres (> 0), base reflectance baseF0 (per channel, in [0, 1)).
IDK_INLINE vec3 ptThinFilmFresnel(float cosTheta1, float filmIor, float thickness, vec3 baseF0) {
    float c1 = ptSaturate(cosTheta1);
    // Towards zero thickness the film's IOR fades to air's, so a vanishing film leaves only the base.
    float k = ptSaturate(thickness / 0.03f);
    float n2 = mix(1.0f, max(filmIor, 1.0f), k * k * (3.0f - 2.0f * k));  // smoothstep(0, 0.03, thickness)
    float sin2 = (1.0f - c1 * c1) / (n2 * n2);
    float cos2Sq = 1.0f - sin2;
    if (cos2Sq < 0.0f) return vec3(1.0f);  // total internal reflection (cannot happen from air; kept for safety)
    float c2 = sqrt(cos2Sq);
    // Air / film interface.
    float r0 = (n2 - 1.0f) / (n2 + 1.0f);
    float r12 = ptSchlick1(r0 * r0, c1);
    float t121 = 1.0f - r12;
    float phi21 = kPtPi;  // the film is at least as dense as air: reflection from above turns the phase by pi
    // Film / base interface: the base's IOR from its f0 (below 1: f0 = 1 would be an infinite IOR).
    vec3 r23 = vec3(0.0f);
    vec3 phi23 = vec3(0.0f);
    for (int i = 0; i < 3; ++i) {
        float s = sqrt(clamp(baseF0[i], 0.0f, 0.9999f));
        float baseIor = (1.0f + s) / (1.0f - s);
        float q = (baseIor - n2) / (baseIor + n2);
        r23[i] = ptSchlick1(q * q, c2);
        phi23[i] = baseIor < n2 ? kPtPi : 0.0f;
    }
    float opd = 2.0f * n2 * thickness * c2;
    vec3 phi = vec3(phi21) + phi23;
    vec3 r123 = clamp(r12 * r23, vec3(1.0e-5f), vec3(0.9999f));
    vec3 amp = sqrt(r123);
    vec3 rs = (t121 * t121) * r23 / (vec3(1.0f) - r123);
    vec3 result = vec3(r12) + rs;  // the series' constant term
    vec3 cm = rs - vec3(t121);
    for (int m = 1; m <= 2; ++m) {
        cm *= amp;
        result += cm * (2.0f * ptThinFilmSensitivity(float(m) * opd, float(m) * phi));
    }
    return max(result, vec3(0.0f));  // out-of-gamut colours come out negative
}

// plain: the Fresnel term without the film at cosine c (the base's own: dielectric or metal); baseF0 the base's
// reflectance at normal incidence; scale multiplies the film's reflectance (KHR_materials_specular's weight for
// dielectrics, 1 for metals). Exactly plain when the factor or the thickness is 0.
IDK_INLINE vec3 ptIridescentFresnel(vec3 plain, float c, float factor, float filmIor, float thickness, vec3 baseF0,
                                    float scale) {
    if (!(factor > 0.0f) || !(thickness > 0.0f)) return plain;
    return mix(plain, ptThinFilmFresnel(c, filmIor, thickness, baseF0) * scale, factor);
}

IDK_GPU_END

#endif
