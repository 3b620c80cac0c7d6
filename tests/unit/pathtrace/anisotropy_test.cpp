// anisotropy_test.cpp: KHR_materials_anisotropy in the shared BSDF (shared/pt_anisotropy.h, the ptBase* hooks of
// pt_bsdf_frame.h) against values computed here in double from the extension specification's formulas (its
// D_GGX_anisotropic with f = (alpha_b T.H, alpha_t B.H, alpha_t alpha_b N.H) and V_GGX_anisotropic, written
// differently from the BSDF's), at chosen angles; strength 0 leaves the isotropic BSDF bit for bit; the anisotropic
// functions reduce to the isotropic ones at alpha_t = alpha_b; sampling agrees with evaluation (pdf, weight, and
// the mean weight with a quadrature of f cos); reciprocity; the anisotropic albedo table (shared/pt_energy.h) against
// a quadrature of the specification's f cos and its hemispherical mean against the lookup's; and the white furnace
// of rough anisotropic white metals and thin-walled dielectrics, compensated from that table.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "pathtrace/albedo_integrator.hpp"
#include "shared/pt_sampling.h"
#include "support/pt_surface.hpp"

namespace idk::test {
namespace {

using namespace idk::gpu;
using glm::dvec3;

constexpr double kPi = 3.14159265358979;

PtSurface metal(glm::vec3 base, float roughness, float strength, glm::vec3 direction) {
    PtSurface s = plainPtSurface(base, 1.0f, roughness);
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
    const double eavg = ptAlbedoAnisoAvg(0.5f, 0.6f);
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
            // Kulla-Conty term with the anisotropic table at wo's and wi's directions in the frame (t, b, n).
            const double eo = ptAlbedoAnisoMetal(glm::vec3(glm::dot(wo, t), glm::dot(wo, b), wo.z), 0.5f, 0.6f);
            const double ei = ptAlbedoAnisoMetal(glm::vec3(glm::dot(wi, t), glm::dot(wi, b), wi.z), 0.5f, 0.6f);
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

// The anisotropic albedo table against a direct quadrature of the specification's D V (n.l) over the light's
// hemisphere (midpoint rule in cos theta and phi, double), at points between the table's nodes and moderately rough
// lobes (a grid resolves them): the integrator's entries and the quadrilinear lookup both within 1%.
TEST(PtAnisotropyAlbedo, TableMatchesQuadratureOfTheSpecificationBrdf) {
    const dvec3 t(1.0, 0.0, 0.0), b(0.0, 1.0, 0.0), n(0.0, 0.0, 1.0);
    int checked = 0;
    for (float r : {0.45f, 0.8f}) {
        for (float strength : {0.35f, 0.9f}) {
            for (float q : {0.3f, 0.85f}) {
                for (float mu : {0.25f, 0.6f, 0.95f}) {
                    const double alpha = double(r) * r;
                    const double at = alpha + (1.0 - alpha) * double(strength) * strength, ab = alpha;
                    const double so = std::sqrt(1.0 - double(mu) * mu);
                    const dvec3 v(so * q, so * std::sqrt(1.0 - double(q) * q), mu);
                    const int nt = 600, np = 600;
                    double sum = 0.0;
                    for (int i = 0; i < nt; ++i) {
                        const double c = (i + 0.5) / nt;
                        for (int j = 0; j < np; ++j) {
                            const dvec3 l = dir(c, 2.0 * kPi * (j + 0.5) / np);
                            const dvec3 h = glm::normalize(v + l);
                            sum += specD(t, b, n, h, at, ab) * specV(t, b, n, v, l, at, ab) * c;
                        }
                    }
                    const double expected = sum * 2.0 * kPi / (double(nt) * np);
                    const double integrated = pathtrace::ggxAnisoReflectionAlbedo(mu, q, r, strength, 48);
                    const double looked = ptAlbedoAnisoMetal(glm::vec3(v), r, strength);
                    EXPECT_NEAR(integrated, expected, 0.01 * expected) << r << " " << strength << " " << q << " " << mu;
                    EXPECT_NEAR(looked, expected, 0.01 * expected) << r << " " << strength << " " << q << " " << mu;
                    ++checked;
                }
            }
        }
    }
    EXPECT_EQ(checked, 24);
}

// Eavg (what makes the multiple-scattering lobe add exactly 1 - E(wo)) equals the hemispherical mean of E cos / pi
// of the lookup itself, integrated here on a fine midpoint grid, at nodes and between them; and at strength 0 the
// anisotropic table is the isotropic integrator's albedo (same lobe).
TEST(PtAnisotropyAlbedo, AverageIsTheLookupsHemisphericalMean) {
    for (float r : {0.0f, 0.3f, 0.6f, 1.0f}) {
        for (float strength : {0.0f, 0.5f, 0.77f, 1.0f}) {
            const int nt = 400, np = 200;
            double sum = 0.0;
            for (int i = 0; i < nt; ++i) {
                const double c = (i + 0.5) / nt;
                for (int j = 0; j < np; ++j)
                    sum += ptAlbedoAnisoMetal(glm::vec3(dir(c, 0.5 * kPi * (j + 0.5) / np)), r, strength) * c;
            }
            const double mean = 2.0 * sum / (double(nt) * np);  // (1 / pi) * 4 quarter-hemispheres * (pi / 2) / np
            EXPECT_NEAR(ptAlbedoAnisoAvg(r, strength), mean, 2e-4) << r << " " << strength;
        }
    }
    for (uint32_t k = 0; k < kPtAlbedoAnisoRough; k += 3) {
        const float r = ptAlbedoNodeRough(k, kPtAlbedoAnisoRough);
        for (float mu : {0.1f, 0.5f, 0.9f})
            EXPECT_NEAR(ptAlbedoAnisoMetal(glm::vec3(dir(mu, 0.3)), r, 0.0f), pathtrace::ggxReflectionAlbedo(mu, r, 48), 2e-3)
                << r << " " << mu;
    }
}

// White furnace of white anisotropic surfaces (mean sampling weight = albedo, the lobes are too narrow across the
// anisotropy for a quadrature grid): a grid of roughness 0..1 x strength 0..1 x anisotropy rotation against the
// view x four view angles. Metal and thin-walled dielectric are compensated from the anisotropic table: both within
// 1% of 1, like the isotropic furnace (measured: metal 0.30%, thin 0.31%; with the isotropic tables at the
// rms roughness, before the table, 40000 independent samples: metal 25.3%, thin 32.8%, at roughness 0.25, strength 1, viewed across the
// direction at mu 0.15). A refracting volume still reads the isotropic dielectric table at the rms roughness:
// its error is printed and bounded, not held to 1%.
// The uniforms are a Halton sequence (bases 2, 3, 5) rotated by a random shift per configuration (Cranley-Patterson,
// unbiased): ~10x less error than independent samples at equal count, so the grid fits in a few seconds.
float radicalInverse(uint32_t i, uint32_t base) {
    double inv = 1.0 / base, f = inv, r = 0.0;
    for (; i > 0; i /= base, f *= inv) r += f * double(i % base);
    return float(r);
}

double sampledAlbedo(const PtSurface& s, glm::vec3 wo, std::mt19937& gen, int n) {
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const glm::vec3 shift(uni(gen), uni(gen), uni(gen));
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        glm::vec3 u = glm::fract(glm::vec3(radicalInverse(uint32_t(i), 2), radicalInverse(uint32_t(i), 3),
                                           radicalInverse(uint32_t(i), 5)) + shift);
        ptSampleBsdf(s, wo, glm::min(u, glm::vec3(0.99999994f)), wi, weight, pdf, lobe);
        if (lobe == kPtLobeNone) continue;
        double w = weight.y;
        if (s.thickness > 0.0f && wi.z < 0.0f) w *= double(s.ior) * s.ior;  // energy, not radiance, through the volume
        sum += w;
    }
    return sum / n;
}

double worstFurnace(float metallic, float thickness, double tolerance, int samples) {
    std::mt19937 gen(3);
    double worst = 0.0;
    for (float r : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        for (float strength : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
            for (float rotation : {0.0f, 0.6f, 1.5707963f}) {
                PtSurface s = metal(glm::vec3(1.0f), r, strength, glm::vec3(std::cos(rotation), std::sin(rotation), 0.0f));
                s.metallic = metallic;
                s.transmission = 1.0f - metallic;
                s.thickness = thickness;
                for (float mu : {0.95f, 0.7f, 0.4f, 0.15f}) {
                    const double albedo = sampledAlbedo(s, glm::vec3(std::sqrt(1.0f - mu * mu), 0.0f, mu), gen, samples);
                    EXPECT_NEAR(albedo, 1.0, tolerance) << "metallic " << metallic << " thickness " << thickness
                                                        << " roughness " << r << " strength " << strength
                                                        << " rotation " << rotation << " mu " << mu;
                    worst = std::max(worst, std::abs(albedo - 1.0));
                }
            }
        }
    }
    return worst;
}

TEST(PtAnisotropy, WhiteFurnaceRoughAnisotropicMetal) {
    std::printf("anisotropic white furnace, metal: worst |albedo - 1| %.4f\n", worstFurnace(1.0f, 0.0f, 0.01, 8000));
}

TEST(PtAnisotropy, WhiteFurnaceRoughAnisotropicThinDielectric) {
    std::printf("anisotropic white furnace, thin-walled dielectric: worst |albedo - 1| %.4f\n",
                worstFurnace(0.0f, 0.0f, 0.01, 8000));
}

TEST(PtAnisotropy, WhiteFurnaceRoughAnisotropicGlassIsBounded) {
    std::printf("anisotropic white furnace, glass (isotropic dielectric table at the rms roughness): worst "
                "|albedo - 1| %.4f\n", worstFurnace(0.0f, 1.0f, 0.16, 4000));
}

}  // namespace
}  // namespace idk::test
