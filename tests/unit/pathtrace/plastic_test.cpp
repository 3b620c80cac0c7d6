// plastic_test.cpp: the opaque dielectric with a Lambert base ("plastic": metallic 0, transmission 0) in the
// shared BSDF (shared/pt_bsdf.h, the albedo-scaled diffuse weight of pt_bsdf_frame.h): the white furnace (base
// colour 1: the directional albedo, integrated here by sampling or quadrature, is 1 within 1% for roughness 0..1,
// view cosines down to 0.1 and IOR 1.33 / 1.5 / 2), KHR_materials_specular keeps it at most 1 and gives back
// exactly the energy its specular lobe no longer takes, and the BSDF is reciprocal: f(wo, wi) = f(wi, wo).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "shared/pt_sampling.h"
#include "support/pt_surface.hpp"

namespace idk::test {
namespace {

using namespace idk::gpu;

PtSurface plastic(float roughness, float ior) {
    return plainPtSurface(glm::vec3(1.0f), 0.0f, roughness, ior);
}

glm::vec3 view(float mu) { return glm::vec3(std::sqrt(1.0f - mu * mu), 0.0f, mu); }

// Mean sampling weight (green) over a stratified grid of the direction uniforms, the lobe uniform jittered.
double sampledAlbedo(const PtSurface& s, float mu, std::mt19937& gen) {
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const int n = 160;
    double sum = 0.0;
    for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
            glm::vec3 wi, weight;
            float pdf;
            uint lobe;
            const glm::vec3 u(uni(gen), (float(a) + uni(gen)) / float(n), (float(b) + uni(gen)) / float(n));
            ptSampleBsdf(s, view(mu), u, wi, weight, pdf, lobe);
            if (lobe != kPtLobeNone) sum += weight.y;
        }
    }
    return sum / (double(n) * n);
}

// The same by midpoint quadrature of f cos over the upper hemisphere (rough lobes: roughness >= 0.5), the
// delta-free BSDF evaluated; the grid is finer in cos theta, where the lobes and the Fresnel term vary.
double quadratureAlbedo(const PtSurface& s, float mu) {
    const int nz = 400, nphi = 160;
    double sum = 0.0;
    for (int a = 0; a < nz; ++a) {
        const float z = (float(a) + 0.5f) / float(nz);
        const float sr = std::sqrt(std::max(0.0f, 1.0f - z * z));
        for (int b = 0; b < nphi; ++b) {
            const float phi = 3.14159265f * (float(b) + 0.5f) / float(nphi);  // symmetric about wo's plane
            float pdf;
            sum += ptEvalBsdf(s, view(mu), glm::vec3(sr * std::cos(phi), sr * std::sin(phi), z), pdf).y;
        }
    }
    return sum * 2.0 * 3.14159265358979 / (double(nz) * nphi);
}

double albedo(const PtSurface& s, float mu, std::mt19937& gen) {
    return s.roughness >= 0.5f ? quadratureAlbedo(s, mu) : sampledAlbedo(s, mu, gen);
}

TEST(PtPlastic, WhiteFurnace) {
    std::mt19937 gen(3);
    double worst = 0.0;
    for (float ior : {1.33f, 1.5f, 2.0f}) {
        for (int k = 0; k <= 10; ++k) {
            const float r = 0.1f * float(k);
            for (float mu : {0.95f, 0.7f, 0.4f, 0.2f, 0.1f}) {
                const double e = albedo(plastic(r, ior), mu, gen);
                EXPECT_NEAR(e, 1.0, 0.01) << "white plastic, ior " << ior << " roughness " << r << " mu " << mu;
                worst = std::max(worst, std::abs(e - 1.0));
                if (ior == 1.5f && (k == 2 || k == 5 || k == 10) && (mu == 0.2f || mu == 0.7f))
                    std::printf("white plastic ior 1.5 roughness %.1f mu %.1f: albedo %.4f\n", r, mu, e);
            }
        }
    }
    std::printf("white plastic furnace worst |albedo - 1|: %.4f\n", worst);
}

// KHR_materials_specular: a weaker or coloured specular lobe leaves its energy to the diffuse base, which the
// albedo scaling gives back: still 1 (white specular colour) or at most 1 (coloured: the weight follows the
// strongest channel, the others lose what their weaker lobe does not take).
TEST(PtPlastic, SpecularExtensionKeepsTheFurnace) {
    std::mt19937 gen(9);
    for (float r : {0.3f, 0.7f}) {
        for (float mu : {0.8f, 0.3f}) {
            PtSurface s = plastic(r, 1.5f);
            s.specular = 0.4f;
            EXPECT_NEAR(albedo(s, mu, gen), 1.0, 0.01) << "specular 0.4, roughness " << r << " mu " << mu;
            s.specular = 1.0f;
            s.specularColor = glm::vec3(2.0f);
            EXPECT_NEAR(albedo(s, mu, gen), 1.0, 0.01) << "specularColor 2, roughness " << r << " mu " << mu;
            s.specularColor = glm::vec3(1.0f, 0.5f, 0.0f);  // green: below the strongest (red) channel
            const double green = albedo(s, mu, gen);
            EXPECT_LE(green, 1.005) << "coloured specular, roughness " << r << " mu " << mu;
            EXPECT_GT(green, 0.9) << "coloured specular, roughness " << r << " mu " << mu;
        }
    }
}

// f(wo, wi) = f(wi, wo) (ptEvalBsdf returns f |cos wi|) for random pairs on random plastics, coloured and
// white, with KHR_materials_specular, a metallic mix and diffuse transmission (reflected side).
TEST(PtPlastic, Reciprocity) {
    std::mt19937 gen(13);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    auto dir = [&]() {
        const float z = 0.05f + 0.95f * uni(gen), phi = 6.2831853f * uni(gen);
        const float sr = std::sqrt(1.0f - z * z);
        return glm::vec3(sr * std::cos(phi), sr * std::sin(phi), z);
    };
    int checked = 0;
    for (int i = 0; i < 4000; ++i) {
        PtSurface s = plastic(0.05f + 0.95f * uni(gen), 1.0f + 1.5f * uni(gen));
        s.baseColor = glm::vec3(uni(gen), uni(gen), uni(gen));
        if (i % 4 == 1) s.specular = uni(gen);
        if (i % 4 == 2) s.specularColor = glm::vec3(2.0f * uni(gen), uni(gen), uni(gen));
        if (i % 8 == 3) s.metallic = uni(gen);
        if (i % 8 == 7) s.diffuseTransmission = uni(gen);
        const glm::vec3 wo = dir(), wi = dir();
        float pdf;
        const glm::vec3 a = ptEvalBsdf(s, wo, wi, pdf) / wi.z;
        const glm::vec3 b = ptEvalBsdf(s, wi, wo, pdf) / wo.z;
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(a[c], b[c], 2e-4f * std::max(1.0f, std::abs(a[c]))) << "pair " << i << " channel " << c;
        checked += a.y > 0.0f;
    }
    EXPECT_GT(checked, 3000);
}

}  // namespace
}  // namespace idk::test
