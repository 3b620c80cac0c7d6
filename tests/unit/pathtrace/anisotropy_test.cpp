// anisotropy_test.cpp: KHR_materials_anisotropy in the shared BSDF (shared/pt_anisotropy.h, the ptBase* hooks of
// pt_bsdf_frame.h) against values computed here in double from the extension specification's formulas (its
// D_GGX_anisotropic with f = (alpha_b T.H, alpha_t B.H, alpha_t alpha_b N.H) and V_GGX_anisotropic, written
// differently from the BSDF's), at chosen angles; strength 0 leaves the isotropic BSDF bit for bit; the anisotropic
// functions reduce to the isotropic ones at alpha_t = alpha_b; sampling agrees with evaluation (pdf, weight, and
// the mean weight with a quadrature of f cos); reciprocity; and the white furnace of a rough anisotropic white
// metal, whose energy compensation reads the isotropic tables at the mean roughness.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "shared/pt_sampling.h"

namespace idk::test {
namespace {

using namespace idk::gpu;
using glm::dvec3;

constexpr double kPi = 3.14159265358979;

PtSurface metal(glm::vec3 base, float roughness, float strength, glm::vec3 direction) {
    PtSurface s{};
    s.baseColor = base;
    s.alpha = 1.0f;
    s.metallic = 1.0f;
    s.roughness = roughness;
    s.ior = 1.5f;
    s.attenuationColor = glm::vec3(1.0f);
    s.shadingNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    s.geometricNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    s.specular = 1.0f;
    s.specularColor = glm::vec3(1.0f);
    s.anisotropyStrength = strength;
    s.anisotropyDirection = direction;
    return s;
}

dvec3 dir(double cosTheta, double phi) {
    const double s = std::sqrt(1.0 - cosTheta * cosTheta);
    return dvec3(s * std::cos(phi), s * std::sin(phi), cosTheta);
}

// The specification's reference formulas (KHR_materials_anisotropy, "Implementation").
double specD(dvec3 t, dvec3 b, dvec3 n, dvec3 h, double at, double ab) {
    const double a2 = at * ab;
    const dvec3 f(ab * glm::dot(t, h), at * glm::dot(b, h), a2 * glm::dot(n, h));
    const double w2 = a2 / glm::dot(f, f);
    return a2 * w2 * w2 / kPi;
}
double specV(dvec3 t, dvec3 b, dvec3 n, dvec3 v, dvec3 l, double at, double ab) {
    const double gv = glm::dot(n, l) * glm::length(dvec3(at * glm::dot(t, v), ab * glm::dot(b, v), glm::dot(n, v)));
    const double gl = glm::dot(n, v) * glm::length(dvec3(at * glm::dot(t, l), ab * glm::dot(b, l), glm::dot(n, l)));
    return 0.5 / (gv + gl);
}

TEST(PtAnisotropy, GgxByHand) {
    const double rot = 0.7;
    const dvec3 t(std::cos(rot), std::sin(rot), 0.0), n(0.0, 0.0, 1.0), b = glm::cross(n, t);
    const glm::vec3 base(0.9f, 0.6f, 0.3f);
    const PtSurface s = metal(base, 0.5f, 0.6f, glm::vec3(t));
    const double alpha = 0.25, at = alpha + (1.0 - alpha) * 0.36, ab = alpha;
    const double meanRoughness = std::sqrt(std::sqrt(0.5 * (at * at + ab * ab)));
    const double eavg = ptAlbedoMetalAvg(float(meanRoughness));
    int checked = 0;
    for (double cosO : {0.9, 0.5}) {
        for (double phiI : {0.7 + kPi, 0.7 + kPi / 2.0, 2.0}) {  // mirror plane along t, across it, in between
            const dvec3 wo = dir(cosO, 0.7), wi = dir(0.6, phiI);
            float pdf;
            const glm::vec3 got = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf);
            const dvec3 h = glm::normalize(wo + wi);
            const double m = std::pow(1.0 - glm::dot(wo, h), 5.0);
            const dvec3 F = dvec3(base) + (1.0 - dvec3(base)) * m;
            const dvec3 single = F * specD(t, b, n, h, at, ab) * specV(t, b, n, wo, wi, at, ab) * wi.z;
            // Kulla-Conty term with the isotropic tables at the rms alpha (pt_energy.h, energy_test).
            const double eo = ptAlbedoMetal(float(wo.z), float(meanRoughness));
            const double ei = ptAlbedoMetal(float(wi.z), float(meanRoughness));
            const dvec3 favg = dvec3(base) + (1.0 - dvec3(base)) / 21.0;
            const dvec3 fms = favg * favg * eavg / (1.0 - favg * (1.0 - eavg));
            const dvec3 ms = fms * (1.0 - eo) * (1.0 - ei) / (kPi * (1.0 - eavg)) * wi.z;
            const dvec3 expected = single + ms;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], expected[c], 2e-4 * std::max(1.0, expected[c])) << cosO << " " << phiI << " " << c;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 6);
    // Anisotropy is visible: the lobe is wider along t than across it (same half-vector tilt, 90 degrees apart).
    const dvec3 wo = dir(1.0 - 1e-7, 0.0);
    float pdf;
    const double along = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(glm::normalize(dvec3(0.0, 0.0, 1.0) + 0.8 * t)), pdf).x;
    const double across = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(glm::normalize(dvec3(0.0, 0.0, 1.0) + 0.8 * b)), pdf).x;
    EXPECT_GT(along, 2.0 * across);
}

// The direction in the vertex frame: T rotated toward B = cross(N, T) w by the rotation, then by the texture's RG.
TEST(PtAnisotropy, DirectionFollowsTheTangentFrame) {
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    const glm::vec4 t(2.0f, 0.0f, 0.0f, 1.0f);  // not unit: the result is
    auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-5f; };
    EXPECT_TRUE(near(ptAnisotropyDirection(t, n, 0.0f, glm::vec2(1.0f, 0.5f)), glm::vec3(1.0f, 0.0f, 0.0f)));
    EXPECT_TRUE(near(ptAnisotropyDirection(t, n, 1.5707963f, glm::vec2(1.0f, 0.5f)), glm::vec3(0.0f, 1.0f, 0.0f)));
    EXPECT_TRUE(near(ptAnisotropyDirection(glm::vec4(2.0f, 0.0f, 0.0f, -1.0f), n, 1.5707963f, glm::vec2(1.0f, 0.5f)),
                     glm::vec3(0.0f, -1.0f, 0.0f)));  // mirrored UVs: B flips
    EXPECT_TRUE(near(ptAnisotropyDirection(t, n, 0.0f, glm::vec2(0.5f, 1.0f)), glm::vec3(0.0f, 1.0f, 0.0f)));
    const float r = 0.3f;  // rotation and texture direction add up
    EXPECT_TRUE(near(ptAnisotropyDirection(t, n, r, glm::vec2(0.5f + 0.5f * std::cos(0.4f), 0.5f + 0.5f * std::sin(0.4f))),
                     glm::vec3(std::cos(r + 0.4f), std::sin(r + 0.4f), 0.0f)));
    EXPECT_EQ(ptAnisotropyDirection(glm::vec4(1.0f, 0.0f, 0.0f, 0.0f), n, 0.0f, glm::vec2(1.0f, 0.5f)), glm::vec3(0.0f));
}

// Strength 0 is the isotropic BSDF exactly (the BSDF takes its old code path), whatever direction is set.
TEST(PtAnisotropy, StrengthZeroIsIsotropicExactly) {
    std::mt19937 gen(5);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (int i = 0; i < 3000; ++i) {
        PtSurface iso = metal(glm::vec3(uni(gen), uni(gen), uni(gen)), i % 7 == 0 ? 0.0f : uni(gen), 0.0f,
                              glm::vec3(0.0f));
        iso.metallic = i % 3 == 0 ? 1.0f : uni(gen);
        iso.transmission = i % 4 == 0 ? uni(gen) : 0.0f;
        iso.thickness = i % 8 == 0 ? 1.0f : 0.0f;
        iso.clearcoat = i % 5 == 0 ? uni(gen) : 0.0f;
        iso.clearcoatRoughness = uni(gen);
        PtSurface zero = iso;
        zero.anisotropyDirection = glm::normalize(glm::vec3(uni(gen) - 0.5f, uni(gen) - 0.5f, uni(gen) - 0.5f));
        const glm::vec3 wo(dir(0.05 + 0.95 * uni(gen), 6.2831853 * uni(gen)));
        const glm::vec3 wi(dir(-1.0 + 2.0 * uni(gen), 6.2831853 * uni(gen)));
        float p0, p1;
        const glm::vec3 f0 = ptEvalBsdf(iso, wo, wi, p0), f1 = ptEvalBsdf(zero, wo, wi, p1);
        ASSERT_EQ(f0, f1) << i;
        ASSERT_EQ(p0, p1) << i;
        const glm::vec3 u(uni(gen), uni(gen), uni(gen));
        glm::vec3 wi0, wi1, w0, w1;
        uint l0, l1;
        ptSampleBsdf(iso, wo, u, wi0, w0, p0, l0);
        ptSampleBsdf(zero, wo, u, wi1, w1, p1, l1);
        ASSERT_EQ(l0, l1) << i;
        ASSERT_EQ(wi0, wi1) << i;
        ASSERT_EQ(w0, w1) << i;
        ASSERT_EQ(p0, p1) << i;
    }
}

// At alpha_t = alpha_b the anisotropic functions are the isotropic ones of pt_microfacet.h.
TEST(PtAnisotropy, EqualAlphasReduceToIsotropic) {
    std::mt19937 gen(9);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        const float a = 0.05f + 0.95f * uni(gen);
        const glm::vec3 wo(dir(0.05 + 0.95 * uni(gen), 6.2831853 * uni(gen)));
        const glm::vec3 wi(dir(0.05 + 0.95 * uni(gen), 6.2831853 * uni(gen)));
        const glm::vec3 h = glm::normalize(wo + wi);
        // float rounding: both D forms cancel to ~alpha^2 near the peak (relative error ~1e-7 / alpha^2).
        auto near = [](float x, float y) { return std::abs(x - y) <= 1e-4f * std::max(1.0f, std::abs(y)); };
        ASSERT_TRUE(near(ptGgxAnisoD(h, a, a), ptGgxD(h.z, a))) << i;
        ASSERT_TRUE(near(ptGgxAnisoG2(wo, wi, a, a), ptGgxG2(wo.z, wi.z, a))) << i;
        ASSERT_TRUE(near(ptGgxAnisoVndfPdf(wo, h, a, a), ptGgxVndfPdf(wo, h, a))) << i;
        const float u1 = uni(gen), u2 = uni(gen);
        const glm::vec3 ha = ptSampleGgxAnisoVndf(wo, a, a, u1, u2), hi = ptSampleGgxVndf(wo, a, u1, u2);
        ASSERT_LT(glm::length(ha - hi), 1e-5f) << i;
    }
}

PtSurface anisotropicCase(int k) {
    PtSurface s = metal(glm::vec3(0.8f, 0.7f, 0.5f), 0.4f, 0.8f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
    if (k == 1) {  // rough dielectric over Lambert
        s.metallic = 0.0f;
        s.roughness = 0.6f;
        s.anisotropyStrength = 0.5f;
    } else if (k == 2) {  // rough glass with a volume: anisotropic refraction
        s.metallic = 0.0f;
        s.transmission = 1.0f;
        s.thickness = 1.0f;
        s.roughness = 0.3f;
        s.anisotropyStrength = 0.9f;
    } else if (k == 3) {  // a smooth base made rough along one axis only
        s.roughness = 0.0f;
        s.anisotropyStrength = 0.7f;
        s.anisotropyDirection = glm::vec3(0.0f);  // no tangent: the BSDF's basis
    }
    return s;
}

double quadratureAlbedo(const PtSurface& s, glm::vec3 wo, int channel) {
    const int nz = 1000, nphi = 400;
    double sum = 0.0;
    for (int a = 0; a < nz; ++a) {
        const float z = -1.0f + 2.0f * (float(a) + 0.5f) / float(nz);
        const float sr = std::sqrt(std::max(0.0f, 1.0f - z * z));
        for (int b = 0; b < nphi; ++b) {
            const float phi = 6.2831853f * (float(b) + 0.5f) / float(nphi);
            float pdf;
            sum += ptEvalBsdf(s, wo, glm::vec3(sr * std::cos(phi), sr * std::sin(phi), z), pdf)[channel];
        }
    }
    return sum * 4.0 * kPi / (double(nz) * nphi);
}

// Samples carry pdf = the evaluated pdf and weight = f cos / pdf; their mean (the albedo) equals the quadrature of
// f cos, so the visible-normal sampler draws the density its pdf states.
TEST(PtAnisotropy, SamplingMatchesEvaluation) {
    std::mt19937 gen(13);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (int k = 0; k < 4; ++k) {
        const PtSurface s = anisotropicCase(k);
        const glm::vec3 wo(dir(0.6, 1.1));
        const int n = 200000;
        double sum = 0.0;
        int specular = 0;
        for (int i = 0; i < n; ++i) {
            glm::vec3 wi, weight;
            float pdf;
            uint lobe;
            ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
            if (lobe == kPtLobeNone) continue;
            ASSERT_EQ(lobe & kPtLobeDeltaFlag, 0u) << k;
            float evalPdf;
            const glm::vec3 f = ptEvalBsdf(s, wo, wi, evalPdf);
            ASSERT_NEAR(evalPdf, pdf, 1e-3f * std::max(1.0f, pdf)) << k << " " << i;
            ASSERT_NEAR(weight.y, f.y / evalPdf, 1e-3f * std::max(1.0f, weight.y)) << k << " " << i;
            sum += weight.y;
            specular += lobe == kPtLobeSpecular || lobe == kPtLobeTransmission;
        }
        const double sampled = sum / n, quadrature = quadratureAlbedo(s, wo, 1);
        std::printf("anisotropic case %d: albedo sampled %.4f quadrature %.4f\n", k, sampled, quadrature);
        EXPECT_NEAR(sampled, quadrature, 0.01 * quadrature) << k;
        EXPECT_GT(specular, n / 20) << k;
    }
}

TEST(PtAnisotropy, ReflectionIsReciprocal) {
    std::mt19937 gen(21);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (int k : {0, 1, 3}) {
        const PtSurface s = anisotropicCase(k);
        for (int i = 0; i < 500; ++i) {
            const glm::vec3 a(dir(0.05 + 0.95 * uni(gen), 6.2831853 * uni(gen)));
            const glm::vec3 b(dir(0.05 + 0.95 * uni(gen), 6.2831853 * uni(gen)));
            float p;
            const glm::vec3 fab = ptEvalBsdf(s, a, b, p) / b.z, fba = ptEvalBsdf(s, b, a, p) / a.z;
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(fab[c], fba[c], 2e-3f * std::max(1.0f, fab[c])) << k << " " << i;
        }
    }
}

// White furnace of a white anisotropic metal: the single-scattering lobe is exact; the multiple-scattering lobe
// reads the isotropic tables at the rms alpha, so the albedo is 1 only approximately: too high viewed along the
// anisotropy direction, too low across it. Measured (40000 samples each, roughness 0.2..1, strength 0.25..1, four
// view angles along and across): |albedo - 1| <= 1.2% for strength 0.25 at roughness >= 0.5 (the isotropic
// tolerance is 1%), <= 18.4% at roughness >= 0.5 (strength 1, mu 0.15 across), and up to 25% for a smooth base
// stretched to alpha_t = 1 (roughness 0.2, strength 1, mu 0.15 across); asserted with a little margin over those,
// the worst printed.
// Mean sampling weight (= albedo); the lobes here are too narrow across the anisotropy for a quadrature grid.
double sampledAlbedo(const PtSurface& s, glm::vec3 wo, std::mt19937& gen) {
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const int n = 40000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
        if (lobe != kPtLobeNone) sum += weight.y;
    }
    return sum / n;
}

TEST(PtAnisotropy, WhiteFurnaceRoughAnisotropicMetal) {
    std::mt19937 gen(3);
    double worst = 0.0;
    for (float r : {0.2f, 0.5f, 0.8f, 1.0f}) {
        for (float strength : {0.25f, 0.6f, 1.0f}) {
            for (float mu : {0.95f, 0.7f, 0.4f, 0.15f}) {
                PtSurface s = metal(glm::vec3(1.0f), r, strength, glm::vec3(1.0f, 0.0f, 0.0f));
                for (float phi : {0.0f, 1.5707963f}) {
                    const glm::vec3 wo(std::sqrt(1.0f - mu * mu) * std::cos(phi),
                                       std::sqrt(1.0f - mu * mu) * std::sin(phi), mu);
                    const double albedo = sampledAlbedo(s, wo, gen);
                    const double tolerance = r < 0.5f ? 0.26 : (strength <= 0.25f ? 0.015 : 0.2);
                    EXPECT_NEAR(albedo, 1.0, tolerance) << "roughness " << r << " strength " << strength << " mu " << mu
                                                   << " phi " << phi;
                    worst = std::max(worst, std::abs(albedo - 1.0));
                }
            }
        }
    }
    std::printf("anisotropic white furnace worst |albedo - 1| %.4f\n", worst);
}

}  // namespace
}  // namespace idk::test
