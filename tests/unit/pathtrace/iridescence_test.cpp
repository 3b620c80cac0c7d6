// iridescence_test.cpp: KHR_materials_iridescence's thin-film Fresnel (shared/pt_iridescence.h) against an
// independent oracle computed here in double: the two-interface Airy sum of the film's complex amplitudes
// r = r12 + t12 t21 r23 e^(i delta) / (1 - r21 r23 e^(i delta)) (Stokes: r21 = -r12, t12 t21 = 1 - r12^2; the same
// Schlick interface reflectances and pi phase flips as the specification's model), wavelength by wavelength over
// 360..830 nm, integrated against the CIE 1931 matching functions (Wyman, Sloan and Shirley's 2013 multi-lobe fit,
// independent of the specification's Fourier-space Gaussians), in the specification's colour convention: the
// film's mean reflectance (the incoherent sum R12 + T^2 R23 / (1 - R12 R23)) passes uncoloured, the spectral
// oscillation around it goes through XYZ (normalised to Y of a flat spectrum) to linear sRGB. The formula keeps two
// harmonics of the series and integrates them in closed form, so the two differ by a stated tolerance. The bases
// are chosen with the same phase flip at the film/base interface in all channels: the specification's formula
// applies its per-channel phase to the X, Y, Z lobes, which only means the same thing when the phases agree.
// Also: thickness 0 or factor 0 give the plain Fresnel bit for bit (the BSDF and the shared hook), and the BSDF's
// reflection carries mix(F, F_film, factor).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "shared/pt_sampling.h"
#include "shared/pt_iridescence.h"
#include "support/pt_surface.hpp"

namespace idk::test {
namespace {

using namespace idk::gpu;
using glm::dvec3;

double schlick(double f0, double c) { return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0); }

// Piecewise Gaussian of the CIE fit.
double lobe(double x, double mu, double s1, double s2) {
    const double t = (x - mu) / (x < mu ? s1 : s2);
    return std::exp(-0.5 * t * t);
}
dvec3 cie1931(double l) {
    return dvec3(1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
                     0.065 * lobe(l, 501.1, 20.4, 26.2),
                 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1),
                 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8));
}
dvec3 xyzToSrgb(dvec3 c) {
    return dvec3(3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z,
                 -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
                 0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z);
}

// Film of IOR n2, thickness d (nm), over a base whose channel c has normal-incidence reflectance baseF0[c].
dvec3 airyOracle(double cos1, double n2, double d, dvec3 baseF0) {
    const double sin2 = (1.0 - cos1 * cos1) / (n2 * n2);
    const double cos2 = std::sqrt(1.0 - sin2);
    const double f12 = (n2 - 1.0) / (n2 + 1.0);
    const double R12 = schlick(f12 * f12, cos1);
    const double r12 = -std::sqrt(R12);  // into the denser film: phase pi
    dvec3 out;
    for (int ch = 0; ch < 3; ++ch) {
        const double s = std::sqrt(baseF0[ch]);
        const double n3 = (1.0 + s) / (1.0 - s);
        const double f23 = (n3 - n2) / (n3 + n2);
        const double R23 = schlick(f23 * f23, cos2);
        const double r23 = n3 > n2 ? -std::sqrt(R23) : std::sqrt(R23);
        const double mean = R12 + (1.0 - R12) * (1.0 - R12) * R23 / (1.0 - R12 * R23);
        dvec3 xyz(0.0), white(0.0);
        for (double l = 360.0; l <= 830.0; l += 0.5) {
            const double delta = 2.0 * 3.14159265358979 * (2.0 * n2 * d * cos2) / l;
            const std::complex<double> e = std::polar(1.0, delta);
            const std::complex<double> r = r12 + (1.0 - R12) * r23 * e / (1.0 + r12 * r23 * e);
            xyz += (std::norm(r) - mean) * cie1931(l);
            white += cie1931(l);
        }
        out[ch] = std::max(mean + xyzToSrgb(xyz / white.y)[ch], 0.0);  // out of gamut: clamped like the formula
    }
    return out;
}

PtSurface dielectric(glm::vec3 base, float roughness) {
    return plainPtSurface(base, 0.0f, roughness);
}

// The specification's series against the spectral Airy integral, at chosen angles, thicknesses and bases. The
// tolerance covers the truncated series (the dropped harmonics carry (R12 R23)^(3/2) and up) and the two
// colour-matching fits: 0.03 per channel (absolute reflectance) down to cos 0.5; at cos 0.2 Schlick's grazing
// reflectances make R12 R23 large and the truncation shows (bound 0.2). The measured worst is printed per cosine.
TEST(PtIridescence, ThinFilmMatchesSpectralAiry) {
    const double cosines[] = {1.0, 0.8, 0.5, 0.2};
    const double bounds[] = {0.03, 0.03, 0.03, 0.2};
    const double thicknesses[] = {100.0, 250.0, 400.0, 800.0};
    const dvec3 bases[] = {dvec3(0.04), dvec3(0.9, 0.6, 0.3), dvec3(0.1, 0.5, 0.95)};
    const double iors[] = {1.3, 1.8};
    for (int ci = 0; ci < 4; ++ci) {
        const double c = cosines[ci];
        double worst = 0.0;
        for (double ior : iors)
            for (double d : thicknesses)
                for (const dvec3& f0 : bases) {
                    const dvec3 want = airyOracle(c, ior, d, f0);
                    const vec3 got = ptThinFilmFresnel(float(c), float(ior), float(d), vec3(f0));
                    for (int ch = 0; ch < 3; ++ch) {
                        const double err = std::abs(double(got[ch]) - want[ch]);
                        worst = std::max(worst, err);
                        EXPECT_LT(err, bounds[ci]) << "cos " << c << " ior " << ior << " d " << d << " f0 " << f0[ch]
                                                   << " channel " << ch << ": " << got[ch] << " vs " << want[ch];
                    }
                }
        std::printf("thin film vs spectral Airy at cos %.1f: worst |error| %.4f (bound %.2f)\n", c, worst, bounds[ci]);
    }
}

// Hand values: a film whose optical thickness is a quarter of 550 nm at normal incidence (n2 d = 137.5 nm, the
// anti-reflection coating when n2 lies between air and the base) reflects less green than the bare base, and a
// half-wave film (n2 d = 275 nm) leaves green at the bare base's reflectance (the film is "absent" at that
// wavelength); checked against the oracle's own monochromatic Airy value at 550 nm.
TEST(PtIridescence, QuarterAndHalfWave) {
    const double n2 = 1.3;
    const dvec3 f0(0.2);  // base IOR ~2.6: n2 between air and base, the classic coating
    const vec3 quarter = ptThinFilmFresnel(1.0f, float(n2), float(137.5 / n2), vec3(f0));
    const vec3 half = ptThinFilmFresnel(1.0f, float(n2), float(275.0 / n2), vec3(f0));
    EXPECT_LT(quarter.y, 0.6 * f0.y) << quarter.y;
    EXPECT_NEAR(half.y, f0.y, 0.03) << half.y;
}

// Thickness 0 and factor 0 leave the BSDF exactly as without the extension.
TEST(PtIridescence, VanishingFilmIsPlainFresnel) {
    const vec3 wo = glm::normalize(vec3(0.3f, -0.2f, 0.8f));
    const vec3 wi = glm::normalize(vec3(-0.5f, 0.4f, 0.6f));
    for (float metallic : {0.0f, 1.0f})
        for (float roughness : {0.0f, 0.4f}) {
            PtSurface plain = dielectric(vec3(0.7f, 0.5f, 0.2f), roughness);
            plain.metallic = metallic;
            PtSurface thin = plain;
            thin.iridescence = 1.0f;
            thin.iridescenceIor = 1.3f;
            thin.iridescenceThickness = 0.0f;
            PtSurface off = plain;
            off.iridescence = 0.0f;
            off.iridescenceIor = 1.8f;
            off.iridescenceThickness = 400.0f;
            float p0, p1, p2;
            const vec3 a = ptEvalBsdf(plain, wo, wi, p0);
            const vec3 b = ptEvalBsdf(thin, wo, wi, p1);
            const vec3 c = ptEvalBsdf(off, wo, wi, p2);
            EXPECT_EQ(a, b);
            EXPECT_EQ(a, c);
            EXPECT_EQ(p0, p1);
            EXPECT_EQ(p0, p2);
            vec3 w0, w1, f0, f1;
            float q0, q1;
            uint l0, l1;
            ptSampleBsdf(plain, wo, vec3(0.01f, 0.3f, 0.6f), w0, f0, q0, l0);
            ptSampleBsdf(thin, wo, vec3(0.01f, 0.3f, 0.6f), w1, f1, q1, l1);
            EXPECT_EQ(w0, w1);
            EXPECT_EQ(f0, f1);
        }
    const vec3 plainF(0.1f, 0.2f, 0.3f);
    EXPECT_EQ(ptIridescentFresnel(plainF, 0.5f, 0.0f, 1.3f, 300.0f, vec3(0.04f), 1.0f), plainF);
    EXPECT_EQ(ptIridescentFresnel(plainF, 0.5f, 1.0f, 1.3f, 0.0f, vec3(0.04f), 1.0f), plainF);
}

// The BSDF's specular reflection carries the film: a smooth dielectric's mirror weight at normal-ish incidence
// equals mix(F_plain, F_film, factor) with F_film the film over the dielectric's f0 (0.04 for IOR 1.5), and a
// metal's the film over its base colour.
TEST(PtIridescence, BsdfReflectionUsesTheFilm) {
    const vec3 wo = glm::normalize(vec3(0.0f, 0.1f, 1.0f));
    for (float metallic : {0.0f, 1.0f}) {
        PtSurface s = dielectric(vec3(0.9f, 0.6f, 0.3f), 0.0f);
        s.metallic = metallic;
        PtSurface film = s;
        film.iridescence = 0.5f;
        film.iridescenceIor = 1.3f;
        film.iridescenceThickness = 300.0f;
        vec3 wi, w0, w1;
        float pdf0, pdf1;
        uint l0, l1;
        // u.x = 0: the first lobe with non-zero probability is the specular (no coat, no sheen).
        ptSampleBsdf(s, wo, vec3(0.0f, 0.5f, 0.5f), wi, w0, pdf0, l0);
        ptSampleBsdf(film, wo, vec3(0.0f, 0.5f, 0.5f), wi, w1, pdf1, l1);
        ASSERT_EQ(l0, kPtLobeSpecular | kPtLobeDeltaFlag);
        ASSERT_EQ(l1, kPtLobeSpecular | kPtLobeDeltaFlag);
        // weight = F / pSpec: compare F = weight * pdf.
        const vec3 plainF = w0 * pdf0;
        const float c = wo.z;
        const vec3 base = metallic > 0.5f ? s.baseColor : vec3(0.04f);
        const vec3 filmF = ptThinFilmFresnel(c, 1.3f, 300.0f, base);
        const vec3 want = plainF * 0.5f + filmF * 0.5f;
        const vec3 got = w1 * pdf1;
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], want[ch], 2e-3f * std::max(want[ch], 1.0f)) << ch;
    }
}

}  // namespace
}  // namespace idk::test
