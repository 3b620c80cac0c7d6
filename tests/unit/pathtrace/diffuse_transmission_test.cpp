// diffuse_transmission_test.cpp: KHR_materials_diffuse_transmission in the shared BSDF
// (shared/pt_diffuse_transmission.h through pt_bsdf.h) against values computed here by hand, in double, from the
// extension specification's formula: the transmitted lobe diffuseTransmission (1 - metallic) W color / pi |cos|
// at chosen angles (W: the Lambert lobes' albedo-scaled weight, support/plastic_weight.hpp), the reflected Lambert
// reduced by 1 - diffuseTransmission; sampling the lobe agrees with evaluation (pdf and weight); the white
// furnace (factor 1, white colour): reflected + transmitted albedo equals the factor-0 material's albedo within
// 1%, and the transmitted part alone equals a quadrature of W cos / pi written here; a factor of 0 ignores the
// colour bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/plastic_weight.hpp"
#include "shared/pt_sampling.h"
#include "support/pt_surface.hpp"

namespace idk::test {
namespace {

using namespace idk::gpu;
using glm::dvec3;

constexpr double kPi = 3.14159265358979;

PtSurface surface(glm::vec3 base, float metallic, float roughness) {
    return plainPtSurface(base, metallic, roughness);
}

dvec3 dir(double cosTheta, double phi) {  // cosTheta < 0: below the surface
    const double s = std::sqrt(1.0 - cosTheta * cosTheta);
    return dvec3(s * std::cos(phi), s * std::sin(phi), cosTheta);
}

void expectNear(glm::vec3 got, dvec3 expected, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], expected[c], 2e-4 * std::max(1.0, std::abs(expected[c]))) << what << " channel " << c;
}

TEST(PtDiffuseTransmission, TransmittedLobeByHand) {
    PtSurface s = surface(glm::vec3(0.5f, 0.4f, 0.3f), 0.25f, 0.5f);
    s.diffuseTransmission = 0.6f;
    s.diffuseTransmissionColor = glm::vec3(0.9f, 0.5f, 0.2f);
    for (const double cosI : {-0.9, -0.6, -0.15}) {
        const dvec3 wo = dir(0.8, 0.0), wi = dir(cosI, 2.5);
        float pdf;
        const glm::vec3 got = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf);
        // Below the surface only the diffuse transmission lives (no specular transmission), with the Lambert
        // lobes' albedo-scaled weight at |cos wi|.
        const double pass = plasticDiffuseWeight({0.5f, 1.5}, wo.z, -wi.z);
        const dvec3 expected = dvec3(0.9, 0.5, 0.2) * (0.75 * 0.6 * pass / kPi * -wi.z);
        expectNear(got, expected, "transmitted");
        EXPECT_GT(pdf, 0.0f);
    }
    // Above the surface the Lambert term keeps 1 - 0.6 of its weight; specular and multiple scattering unchanged.
    const dvec3 wo = dir(0.8, 0.0), wi = dir(0.6, 2.5);
    float pdf;
    const glm::vec3 with = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf);
    PtSurface none = s;
    none.diffuseTransmission = 0.0f;
    const glm::vec3 without = ptEvalBsdf(none, glm::vec3(wo), glm::vec3(wi), pdf);
    const double pass = plasticDiffuseWeight({0.5f, 1.5}, wo.z, wi.z);
    expectNear(without - with, dvec3(0.5, 0.4, 0.3) * (0.75 * 0.6 * pass / kPi * wi.z), "reflected Lambert share");
    // Nothing goes through a factor-0 surface.
    expectNear(ptEvalBsdf(none, glm::vec3(wo), glm::vec3(dir(-0.6, 2.5)), pdf), dvec3(0.0), "factor 0 below");
    EXPECT_EQ(pdf, 0.0f);
}

TEST(PtDiffuseTransmission, FactorZeroIgnoresTheColour) {
    std::mt19937 gen(5);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    PtSurface a = surface(glm::vec3(0.6f, 0.3f, 0.2f), 0.1f, 0.4f);
    a.clearcoat = 0.5f;
    a.sheenColor = glm::vec3(0.3f);
    a.sheenRoughness = 0.5f;
    PtSurface b = a;
    b.diffuseTransmissionColor = glm::vec3(0.2f, 0.9f, 0.0f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 wo = glm::normalize(glm::vec3(uni(gen) - 0.5f, uni(gen) - 0.5f, uni(gen)));
        const glm::vec3 u(uni(gen), uni(gen), uni(gen));
        glm::vec3 wiA, wiB, weightA, weightB;
        float pdfA, pdfB;
        uint lobeA, lobeB;
        ptSampleBsdf(a, wo, u, wiA, weightA, pdfA, lobeA);
        ptSampleBsdf(b, wo, u, wiB, weightB, pdfB, lobeB);
        ASSERT_EQ(lobeA, lobeB);
        ASSERT_EQ(wiA, wiB);
        ASSERT_EQ(weightA, weightB);
        ASSERT_EQ(pdfA, pdfB);
        ASSERT_NE(lobeA, kPtLobeDiffuseTransmission);
    }
}

TEST(PtDiffuseTransmission, SamplingAgreesWithEvaluation) {
    std::mt19937 gen(11);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    PtSurface s = surface(glm::vec3(0.7f, 0.5f, 0.3f), 0.2f, 0.45f);
    s.diffuseTransmission = 0.7f;
    s.diffuseTransmissionColor = glm::vec3(0.4f, 0.8f, 0.6f);
    s.transmission = 0.3f;  // thin-walled specular transmission below the surface too: both lobes share the side
    s.clearcoat = 0.4f;
    s.clearcoatRoughness = 0.3f;
    int transmitted = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const glm::vec3 wo = glm::normalize(glm::vec3(uni(gen) - 0.5f, uni(gen) - 0.5f, 0.05f + uni(gen)));
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
        if (lobe != kPtLobeDiffuseTransmission) continue;
        ++transmitted;
        ASSERT_LT(wi.z, 0.0f);
        float evalPdf;
        const glm::vec3 value = ptEvalBsdf(s, wo, wi, evalPdf);
        ASSERT_NEAR(pdf, evalPdf, 1e-5f * std::max(1.0f, evalPdf));
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(weight[c] * pdf, value[c], 1e-5f * std::max(1.0f, value[c]));
    }
    EXPECT_GT(transmitted, n / 20);  // the lobe is chosen in proportion to its estimated albedo
}

// Mean sampling weight over directions below (transmitted) and above (reflected) the surface: the albedos.
void albedo(const PtSurface& s, float mu, int n, double& reflected, double& transmitted) {
    std::mt19937 gen(21);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
    reflected = transmitted = 0.0;
    for (int i = 0; i < n; ++i) {
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
        if (lobe == kPtLobeNone) continue;
        (wi.z < 0.0f ? transmitted : reflected) += weight.y;
    }
    reflected /= n;
    transmitted /= n;
}

// The transmitted albedo of a white factor-1 surface written from the formula: the integral of
// W(mu, |cos wi|) |cos wi| / pi over the lower hemisphere (W: plastic_weight.hpp; azimuth-free, so a midpoint
// rule in cos theta).
double transmittedByQuadrature(float mu, float roughness) {
    const int nz = 2000;
    double sum = 0.0;
    for (int a = 0; a < nz; ++a) {
        const double z = (a + 0.5) / nz;
        sum += plasticDiffuseWeight({roughness, 1.5}, mu, z) * z / kPi;
    }
    return sum * 2.0 * kPi / double(nz);
}

TEST(PtDiffuseTransmission, WhiteFurnace) {
    for (const float roughness : {0.2f, 0.5f, 1.0f}) {
        for (const float mu : {0.2f, 0.5f, 0.9f}) {
            PtSurface white = surface(glm::vec3(1.0f), 0.0f, roughness);
            double r0, t0;
            albedo(white, mu, 200000, r0, t0);
            white.diffuseTransmission = 1.0f;
            double r1, t1;
            albedo(white, mu, 200000, r1, t1);
            const double hand = transmittedByQuadrature(mu, roughness);
            std::printf("roughness %.1f mu %.1f: factor 0 albedo %.4f; factor 1 reflected %.4f + transmitted %.4f"
                        " = %.4f (transmitted by quadrature %.4f)\n",
                        roughness, mu, r0 + t0, r1, t1, r1 + t1, hand);
            EXPECT_EQ(t0, 0.0);
            EXPECT_NEAR(r1 + t1, r0, 0.01 * r0) << roughness << " " << mu;
            EXPECT_NEAR(t1, hand, 0.01 * hand) << roughness << " " << mu;
        }
    }
}

}  // namespace
}  // namespace idk::test
