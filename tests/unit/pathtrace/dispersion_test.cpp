// dispersion_test.cpp: KHR_materials_dispersion's maths (shared/pt_dispersion.h) against values computed here in
// double from the specification: the IOR at the Fraunhofer lines gives back the Abbe number 20 / dispersion and
// the IOR at 587.6 nm; a smooth dispersive glass refracts each channel by Snell's law at that channel's IOR (the
// BSDF's sampled direction against the closed form), red bending least; one channel carried at weight 3 is the
// RGB estimate on average; the channel pick is uniform.
#include <gtest/gtest.h>

#include <cmath>

#include "shared/pt_sampling.h"

namespace idk::test {
namespace {

using namespace idk::gpu;

double cauchyIor(double ior, double dispersion, double lambda) {  // the specification's formula, in double
    return std::max(ior + (ior - 1.0) * dispersion / 20.0 * (523655.0 / (lambda * lambda) - 1.5168), 1.0);
}

TEST(PtDispersion, FraunhoferLinesGiveTheAbbeNumber) {
    for (const float ior : {1.33f, 1.5f, 1.75f}) {
        for (const float dispersion : {0.25f, 1.0f, 3.0f}) {
            const double nC = ptDispersionIor(ior, dispersion, ptChannelWavelength(0u));
            const double nd = ptDispersionIor(ior, dispersion, ptChannelWavelength(1u));
            const double nF = ptDispersionIor(ior, dispersion, ptChannelWavelength(2u));
            EXPECT_NEAR(nd, ior, 1e-4 * dispersion);  // the IOR extension's value is the d line's
            EXPECT_NEAR((nd - 1.0) / (nF - nC), 20.0 / dispersion, 2e-3 * 20.0 / dispersion);
            EXPECT_NEAR(nC, cauchyIor(ior, dispersion, 656.3), 1e-6);
            EXPECT_NEAR(nF, cauchyIor(ior, dispersion, 486.1), 1e-6);
            EXPECT_LT(nC, nd);
            EXPECT_LT(nd, nF);
        }
    }
    EXPECT_EQ(ptDispersionIor(1.5f, 0.0f, 400.0f), 1.5f);  // dispersion 0: one IOR
}

TEST(PtDispersion, SmoothGlassRefractsEachChannelBySnell) {
    PtSurface s{};
    s.baseColor = glm::vec3(1.0f);
    s.alpha = 1.0f;
    s.roughness = 0.0f;  // delta refraction
    s.transmission = 1.0f;
    s.thickness = 1.0f;
    s.ior = 1.5f;
    s.dispersion = 2.0f;  // Abbe number 10: a strongly dispersive glass
    s.attenuationColor = glm::vec3(1.0f);
    s.shadingNormal = s.geometricNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    s.specular = 1.0f;
    s.specularColor = glm::vec3(1.0f);
    ASSERT_TRUE(ptIsDispersive(s));
    const double thetaI = 50.0 * 3.14159265358979 / 180.0;
    const glm::vec3 wo(float(std::sin(thetaI)), 0.0f, float(std::cos(thetaI)));
    double thetaT[3];
    for (uint c = 0; c < 3; ++c) {
        const PtSurface d = ptDispersedSurface(s, c);
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        ptSampleBsdf(d, wo, glm::vec3(0.9999f, 0.5f, 0.5f), wi, weight, pdf, lobe);  // u.x at the end: transmission
        ASSERT_EQ(lobe, kPtLobeTransmission | kPtLobeDeltaFlag) << c;
        const double n = cauchyIor(1.5, 2.0, ptChannelWavelength(c));
        const double sinT = std::sin(thetaI) / n;  // Snell, from air into the glass
        const glm::dvec3 expected(-sinT, 0.0, -std::sqrt(1.0 - sinT * sinT));
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(wi[k], expected[k], 2e-6) << "channel " << c;
        thetaT[c] = std::asin(std::sqrt(double(wi.x) * wi.x + double(wi.y) * wi.y));
    }
    std::printf("50 degrees incidence, dispersion 2: refraction angles R %.4f G %.4f B %.4f degrees\n",
                thetaT[0] * 57.2957795, thetaT[1] * 57.2957795, thetaT[2] * 57.2957795);
    EXPECT_GT(thetaT[0], thetaT[1]);  // red bends least: its refracted ray stays closest to the incident direction
    EXPECT_GT(thetaT[1], thetaT[2]);
    EXPECT_GT(thetaT[0] - thetaT[2], 0.01);  // about 1.2 degrees apart
}

TEST(PtDispersion, OneChannelAtWeightThreeIsTheRgbEstimateOnAverage) {
    glm::vec3 mean(0.0f);
    int picks[3] = {0, 0, 0};
    const int n = 3000;
    for (int i = 0; i < n; ++i) {
        const uint c = ptPickChannel((float(i) + 0.5f) / float(n));
        ++picks[c];
        mean += ptChannelWeight(c) / float(n);
    }
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(picks[c], n / 3);
        EXPECT_NEAR(mean[c], 1.0f, 1e-5f);
    }
    EXPECT_EQ(ptPickChannel(0.0f), 0u);
    EXPECT_EQ(ptPickChannel(0.99999994f), 2u);
}

TEST(PtDispersion, OnlyVolumesWithTransmissionDisperse) {
    PtSurface s{};
    s.dispersion = 1.0f;
    s.transmission = 1.0f;
    s.thickness = 0.0f;  // thin-walled: no refraction, nothing to disperse
    EXPECT_FALSE(ptIsDispersive(s));
    s.thickness = 1.0f;
    EXPECT_TRUE(ptIsDispersive(s));
    s.transmission = 0.0f;
    EXPECT_FALSE(ptIsDispersive(s));
    s.transmission = 1.0f;
    s.dispersion = 0.0f;
    EXPECT_FALSE(ptIsDispersive(s));
}

}  // namespace
}  // namespace idk::test
