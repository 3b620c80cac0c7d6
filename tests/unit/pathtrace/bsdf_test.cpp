// bsdf_test.cpp: the shared BSDF of shared/pt_bsdf.h (C++ compilation): GGX sampling weights of a white metal
// (F = 1) stay bounded, sampled pdf = evaluated pdf and weight = f cos / pdf, the pdf integrates to 1 over the
// sphere (Monte Carlo), reflection is reciprocal, the Lambert lobe of an IOR-1 dielectric is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shared/pt_sampling.h"

namespace idk::test {
namespace {

using namespace idk::gpu;

PtSurface makeSurface(glm::vec3 base, float metallic, float roughness, float transmission = 0.0f, float ior = 1.5f,
                      float thickness = 0.0f) {
    PtSurface s{};
    s.baseColor = base;
    s.alpha = 1.0f;
    s.metallic = metallic;
    s.roughness = roughness;
    s.transmission = transmission;
    s.ior = ior;
    s.emission = glm::vec3(0.0f);
    s.thickness = thickness;
    s.attenuationColor = glm::vec3(1.0f);
    s.attenuationDistance = 0.0f;
    s.shadingNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    s.geometricNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    s.specular = 1.0f;
    s.specularColor = glm::vec3(1.0f);
    return s;
}

glm::vec3 directionAt(float cosTheta, float phi) {
    const float s = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    return glm::vec3(s * std::cos(phi), s * std::sin(phi), cosTheta);
}

glm::vec3 uniformSphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    return directionAt(z, 2.0f * 3.14159265f * u2);
}

// Single-scattering GGX sampled by visible normals has weights G2 / G1 <= 1; the multiple-scattering lobe
// (pt_energy.h) adds energy, so single weights may exceed 1 while their mean is the albedo, 1 (energy_test's white
// furnace). Sampled by its own density they stay below 2 (with cosine sampling they reached 448 on a 0.05-rough
// metal at grazing light: fireflies).
TEST(PtBsdf, WhiteMetalSamplingWeightsStayBounded) {
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (float roughness : {0.0f, 0.02f, 0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 0.9f, 1.0f}) {
        for (float cosO : {1.0f, 0.9f, 0.7f, 0.5f, 0.3f, 0.1f, 0.02f}) {
            const PtSurface s = makeSurface(glm::vec3(1.0f), 1.0f, roughness);
            const glm::vec3 wo = directionAt(cosO, 0.3f);
            for (int i = 0; i < 2000; ++i) {
                glm::vec3 wi, weight;
                float pdf;
                uint lobe;
                ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
                if (lobe == kPtLobeNone) continue;
                ASSERT_LE(ptMaxComponent(weight), 2.0f)
                    << "roughness " << roughness << " cosO " << cosO << " sample " << i;
                ASSERT_GE(weight.x, 0.0f);
            }
        }
    }
}

TEST(PtBsdf, SampledPdfAndWeightMatchEvaluation) {
    std::mt19937 gen(11);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const PtSurface surfaces[] = {
        makeSurface(glm::vec3(0.8f, 0.5f, 0.2f), 0.0f, 0.5f),         makeSurface(glm::vec3(0.9f), 1.0f, 0.3f),
        makeSurface(glm::vec3(0.7f), 0.4f, 0.8f),                     makeSurface(glm::vec3(1.0f), 0.0f, 0.4f, 1.0f),
        makeSurface(glm::vec3(0.9f), 0.0f, 0.3f, 0.8f, 1.5f, 1.0f),  // rough refraction
        makeSurface(glm::vec3(0.9f), 0.0f, 0.0f, 0.0f)};              // smooth coat over Lambert
    int checked = 0;
    for (const PtSurface& s : surfaces) {
        for (int i = 0; i < 4000; ++i) {
            const glm::vec3 wo = directionAt(0.05f + 0.95f * uni(gen), 6.2831853f * uni(gen));
            glm::vec3 wi, weight;
            float pdf;
            uint lobe;
            ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
            if (lobe == kPtLobeNone || (lobe & kPtLobeDeltaFlag) != 0u) continue;
            float evalPdf;
            const glm::vec3 f = ptEvalBsdf(s, wo, wi, evalPdf);
            ASSERT_NEAR(evalPdf, pdf, 1e-4f * std::max(1.0f, pdf)) << "sample " << i;
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(weight[c], f[c] / evalPdf, 1e-3f * std::max(1.0f, weight[c]));
            ++checked;
        }
    }
    EXPECT_GT(checked, 15000);
}

// Monte Carlo over the sphere with uniform directions: E[pdf(w) * 4 pi] = integral of the pdf = the probability
// that ptSampleBsdf returns a direction at all (GGX reflections that fall below the horizon are dropped, so rough
// lobes lose some mass), which is measured by sampling. Rough lobes only, so uniform directions see their mass.
TEST(PtBsdf, PdfIntegratesToTheSamplingProbability) {
    std::mt19937 gen(3);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const PtSurface surfaces[] = {makeSurface(glm::vec3(0.8f), 0.0f, 0.6f), makeSurface(glm::vec3(0.9f), 1.0f, 0.5f),
                                  makeSurface(glm::vec3(0.6f), 0.3f, 0.7f, 0.5f),
                                  makeSurface(glm::vec3(0.9f), 0.0f, 0.6f, 0.9f, 1.4f, 1.0f),
                                  makeSurface(glm::vec3(0.7f), 0.0f, 1.0f, 0.0f, 1.0f)};
    for (const PtSurface& s : surfaces) {
        for (float cosO : {0.9f, 0.5f}) {
            const glm::vec3 wo = directionAt(cosO, 1.0f);
            const int n = 200000;
            double sum = 0.0, sum2 = 0.0;
            int valid = 0;
            for (int i = 0; i < n; ++i) {
                float pdf;
                ptEvalBsdf(s, wo, uniformSphere(uni(gen), uni(gen)), pdf);
                const double x = double(pdf) * 4.0 * 3.14159265358979;
                sum += x;
                sum2 += x * x;
                glm::vec3 wi, weight;
                uint lobe;
                ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
                valid += lobe != kPtLobeNone ? 1 : 0;
            }
            const double mean = sum / n;
            const double sigma = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
            const double expected = double(valid) / n;
            EXPECT_GT(expected, 0.8);
            EXPECT_NEAR(mean, expected, 4.0 * sigma + 0.005) << "metallic " << s.metallic << " cosO " << cosO;
            if (s.metallic == 0.0f && s.transmission == 0.0f && s.ior == 1.0f) {
                EXPECT_EQ(valid, n) << "pure Lambert never fails";
            }
        }
    }
}

TEST(PtBsdf, ReflectionIsReciprocal) {
    std::mt19937 gen(5);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const PtSurface surfaces[] = {makeSurface(glm::vec3(0.8f, 0.4f, 0.1f), 0.0f, 0.5f),
                                  makeSurface(glm::vec3(0.9f), 1.0f, 0.2f), makeSurface(glm::vec3(0.5f), 0.5f, 0.9f)};
    for (const PtSurface& s : surfaces) {
        for (int i = 0; i < 5000; ++i) {
            const glm::vec3 a = directionAt(0.05f + 0.95f * uni(gen), 6.2831853f * uni(gen));
            const glm::vec3 b = directionAt(0.05f + 0.95f * uni(gen), 6.2831853f * uni(gen));
            float pab, pba;
            const glm::vec3 fab = ptEvalBsdf(s, a, b, pab) / b.z;  // f(a, b)
            const glm::vec3 fba = ptEvalBsdf(s, b, a, pba) / a.z;  // f(b, a)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(fab[c], fba[c], 1e-4f * std::max(1.0f, fab[c])) << i;
        }
    }
}

// An IOR-1 dielectric has no Fresnel reflection: exactly Lambert, weight = base colour.
TEST(PtBsdf, IorOneDielectricIsLambert) {
    const PtSurface s = makeSurface(glm::vec3(0.6f, 0.3f, 0.9f), 0.0f, 0.5f, 0.0f, 1.0f);
    const glm::vec3 wo = directionAt(0.7f, 0.0f), wi = directionAt(0.4f, 2.0f);
    float pdf;
    const glm::vec3 f = ptEvalBsdf(s, wo, wi, pdf);
    EXPECT_NEAR(pdf, 0.4f / 3.14159265f, 1e-6f);
    EXPECT_NEAR(f.y, 0.3f * 0.4f / 3.14159265f, 1e-6f);
    glm::vec3 w2, weight;
    float p2;
    uint lobe;
    ptSampleBsdf(s, wo, glm::vec3(0.5f, 0.3f, 0.7f), w2, weight, p2, lobe);
    EXPECT_EQ(lobe, kPtLobeDiffuse);
    EXPECT_NEAR(weight.z, 0.9f, 1e-5f);
}

}  // namespace
}  // namespace idk::test
