// coat_normal_test.cpp: KHR_materials_clearcoat's clearcoatNormalTexture in the shared BSDF (ptCoatNormalSetup of
// shared/pt_bsdf_frame.h, the coat lobe of pt_bsdf.h): a coat normal equal to the shading normal evaluates as no
// coat normal; a tilted coat normal moves the coat's highlight to the mirror direction about the coat normal, where
// the BSDF equals the coat formula computed here in double in the coat normal's frame
// (clearcoat F(v.h) D(n_c.h) G2(n_c.v, n_c.l) / (4 n_c.v), plus the base beneath weighted 1 - clearcoat F(n_c.v));
// sampling agrees with evaluation (pdf and weight) and a smooth coat mirrors about the coat normal.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shared/pt_sampling.h"
#include "support/pt_surface.hpp"

namespace idk::test {
namespace {

using namespace idk::gpu;
using glm::dvec3;

constexpr double kPi = 3.14159265358979;

PtSurface coated(float coatRoughness, glm::vec3 coatNormal) {
    // IOR 1: a Lambert base without its own specular.
    PtSurface s = plainPtSurface(glm::vec3(0.7f, 0.2f, 0.1f), 0.0f, 0.6f, 1.0f);
    s.clearcoat = 0.8f;
    s.clearcoatRoughness = coatRoughness;
    s.clearcoatNormal = coatNormal;
    return s;
}

double ggxD(double c, double alpha) {
    const double a2 = alpha * alpha, d = c * c * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}
double smithLambda(double c, double alpha) {
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * (1.0 - c * c) / (c * c)) - 1.0);
}
double schlick(double f0, double c) { return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0); }

TEST(PtCoatNormal, SameAsShadingNormalIsNoCoatNormal) {
    const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, -0.2f, 0.8f));
    const glm::vec3 wi = glm::normalize(glm::vec3(-0.4f, 0.3f, 0.7f));
    for (float r : {0.0f, 0.3f}) {
        float p0, p1;
        const glm::vec3 a = ptEvalBsdf(coated(r, glm::vec3(0.0f)), wo, wi, p0);
        const glm::vec3 b = ptEvalBsdf(coated(r, glm::vec3(0.0f, 0.0f, 1.0f)), wo, wi, p1);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-6f * std::max(1.0f, a[c]));
        EXPECT_NEAR(p0, p1, 1e-6f * std::max(1.0f, p0));
    }
}

TEST(PtCoatNormal, TiltedCoatMovesTheHighlight) {
    const double tilt = 0.35;  // radians, about the y axis
    const dvec3 nc(std::sin(tilt), 0.0, std::cos(tilt));
    const dvec3 wo = glm::normalize(dvec3(-0.2, 0.1, 1.0));
    const dvec3 mirrorCoat = 2.0 * glm::dot(wo, nc) * nc - wo;  // the coat's highlight
    const dvec3 mirrorBase(-wo.x, -wo.y, wo.z);                 // where it would be without the coat normal
    const float coatRoughness = 0.2f;
    const double alpha = double(coatRoughness) * coatRoughness;
    const PtSurface s = coated(coatRoughness, glm::vec3(nc));
    float pdf;
    const glm::vec3 atCoat = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(mirrorCoat), pdf);
    const glm::vec3 atBase = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(mirrorBase), pdf);
    EXPECT_GT(atCoat.x, 5.0f * atBase.x);  // the highlight moved
    // By hand at the coat's mirror direction: h = nc.
    const double cO = glm::dot(wo, nc), cI = glm::dot(mirrorCoat, nc);
    const double coat = 0.8 * schlick(0.04, cO) * ggxD(1.0, alpha) /
                        (1.0 + smithLambda(cO, alpha) + smithLambda(cI, alpha)) / (4.0 * cO);
    const double layer = 1.0 - 0.8 * schlick(0.04, cO);
    const dvec3 expected = dvec3(0.7, 0.2, 0.1) / kPi * mirrorCoat.z * layer + coat;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(atCoat[c], expected[c], 2e-4 * std::max(1.0, expected[c])) << c;
    // A smooth coat mirrors about its own normal, with weight clearcoat F(n_c.v).
    glm::vec3 wi, weight;
    float p;
    uint lobe;
    ptSampleBsdf(coated(0.0f, glm::vec3(nc)), glm::vec3(wo), glm::vec3(0.0f, 0.5f, 0.5f), wi, weight, p, lobe);
    ASSERT_EQ(lobe, kPtLobeClearcoat | kPtLobeDeltaFlag);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(wi[c], mirrorCoat[c], 1e-5);
    EXPECT_NEAR(weight.x * p, 0.8 * schlick(0.04, cO), 1e-5);
}

TEST(PtCoatNormal, SampledPdfAndWeightMatchEvaluation) {
    std::mt19937 gen(5);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const PtSurface s = coated(0.25f, glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f)));
    int coatSamples = 0;
    for (int i = 0; i < 20000; ++i) {
        const float c = 0.1f + 0.9f * uni(gen), phi = 6.2831853f * uni(gen);
        const glm::vec3 wo(std::sqrt(1.0f - c * c) * std::cos(phi), std::sqrt(1.0f - c * c) * std::sin(phi), c);
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
        if (lobe == kPtLobeNone || (lobe & kPtLobeDeltaFlag) != 0u) continue;
        float evalPdf;
        const glm::vec3 f = ptEvalBsdf(s, wo, wi, evalPdf);
        ASSERT_NEAR(evalPdf, pdf, 1e-4f * std::max(1.0f, pdf)) << i;
        for (int k = 0; k < 3; ++k) ASSERT_NEAR(weight[k], f[k] / evalPdf, 1e-3f * std::max(1.0f, weight[k])) << i;
        coatSamples += lobe == kPtLobeClearcoat;
    }
    EXPECT_GT(coatSamples, 500);
}

}  // namespace
}  // namespace idk::test
