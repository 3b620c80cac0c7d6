// energy_test.cpp: the GGX energy compensation (shared/pt_energy.h) and its tables (shared/pt_albedo_tables.h):
// the committed tables equal what the CPU integrator (pathtrace/albedo_integrator.cpp) computes now; the
// integrator agrees with an independent hemisphere quadrature of D G2 / (4 cos); and the white furnace: the mean
// BSDF sampling weight (= directional albedo) of a white metal and of a white rough dielectric interface (energy:
// refracted weights times eta^2) is 1 within 1% for every roughness 0..1 and view angle.
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

PtSurface whiteSurface(float metallic, float roughness, float transmission, float ior, float thickness) {
    PtSurface s = plainPtSurface(glm::vec3(1.0f), metallic, roughness, ior);
    s.transmission = transmission;
    s.thickness = thickness;
    return s;
}

TEST(PtAlbedoTables, CommittedTablesMatchTheIntegrator) {
    // Every 37th entry of each table (the whole set takes seconds; the stride walks all rows and columns).
    const int strata = pathtrace::kAlbedoTableStrata;
    int checked = 0;
    for (uint32_t k = 0; k < kPtAlbedoMu * kPtAlbedoRough; k += 37) {
        const float mu = ptAlbedoNodeMu(k % kPtAlbedoMu, kPtAlbedoMu);
        const float r = ptAlbedoNodeRough(k / kPtAlbedoMu, kPtAlbedoRough);
        EXPECT_EQ(kPtAlbedoMetal[k], float(pathtrace::ggxReflectionAlbedo(mu, r, strata))) << k;
        EXPECT_EQ(kPtAlbedoSheen[k], float(pathtrace::sheenAlbedo(mu, r, strata))) << k;
        ++checked;
    }
    const uint32_t dielCount = 2 * kPtAlbedoDielIor * kPtAlbedoDielRough * kPtAlbedoDielMu;
    for (uint32_t k = 0; k < dielCount; k += 37) {
        const uint32_t i = k % kPtAlbedoDielMu, j = (k / kPtAlbedoDielMu) % kPtAlbedoDielRough;
        const uint32_t n = (k / (kPtAlbedoDielMu * kPtAlbedoDielRough)) % kPtAlbedoDielIor;
        const uint32_t side = k / (kPtAlbedoDielMu * kPtAlbedoDielRough * kPtAlbedoDielIor);
        const float ior = ptAlbedoNodeIor(n, kPtAlbedoDielIor);
        const float eta = side == 0 ? ior : 1.0f / ior;
        EXPECT_EQ(kPtAlbedoDielectric[k],
                  float(pathtrace::ggxDielectricAlbedo(ptAlbedoNodeMu(i, kPtAlbedoDielMu),
                                                       ptAlbedoNodeRough(j, kPtAlbedoDielRough), eta, strata)))
            << k;
        ++checked;
    }
    for (uint32_t k = 0; k < kPtAlbedoAnisoMu * kPtAlbedoAnisoAz * kPtAlbedoAnisoRough * kPtAlbedoAnisoStrength; k += 37) {
        const uint32_t i = k % kPtAlbedoAnisoMu, j = (k / kPtAlbedoAnisoMu) % kPtAlbedoAnisoAz;
        const uint32_t n = (k / (kPtAlbedoAnisoMu * kPtAlbedoAnisoAz)) % kPtAlbedoAnisoRough;
        const uint32_t l = k / (kPtAlbedoAnisoMu * kPtAlbedoAnisoAz * kPtAlbedoAnisoRough);
        EXPECT_EQ(kPtAlbedoAnisoMetal[k],
                  float(pathtrace::ggxAnisoReflectionAlbedo(
                      ptAlbedoNodeMu(i, kPtAlbedoAnisoMu), ptAlbedoNodeRough(j, kPtAlbedoAnisoAz),
                      ptAlbedoNodeRough(n, kPtAlbedoAnisoRough), ptAlbedoNodeRough(l, kPtAlbedoAnisoStrength), strata)))
            << k;
        ++checked;
    }
    EXPECT_GE(checked, 2000);
    const uint32_t specCount = kPtAlbedoSpecIor * kPtAlbedoSpecRough * kPtAlbedoDielMu;
    for (uint32_t k = 0; k < specCount; k += 37) {
        const uint32_t i = k % kPtAlbedoDielMu, j = (k / kPtAlbedoDielMu) % kPtAlbedoSpecRough;
        const uint32_t n = k / (kPtAlbedoDielMu * kPtAlbedoSpecRough);
        EXPECT_EQ(kPtAlbedoSpecular[k],
                  float(pathtrace::ggxDielectricReflectionAlbedo(ptAlbedoNodeMu(i, kPtAlbedoDielMu),
                                                                 ptAlbedoNodeRough(j, kPtAlbedoSpecRough),
                                                                 ptAlbedoNodeIor(n, kPtAlbedoSpecIor), strata)))
            << k;
        ++checked;
    }
    EXPECT_GE(checked, 2400);
}

// E(mu, r) by brute force: midpoint rule over (cos theta_i, phi) of D G2 / (4 cos_o), in double.
double bruteForceMetalAlbedo(double mu, double roughness) {
    const double pi = 3.14159265358979;
    const double alpha = std::max(roughness * roughness, 1e-3), a2 = alpha * alpha;
    const double so = std::sqrt(1.0 - mu * mu);
    auto lambda = [&](double c) { return 0.5 * (std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c)) - 1.0); };
    const int nt = 2000, np = 400;
    double sum = 0.0;
    for (int a = 0; a < nt; ++a) {
        const double c = (a + 0.5) / nt, s = std::sqrt(1.0 - c * c);
        for (int b = 0; b < np; ++b) {
            const double phi = pi * (b + 0.5) / np;
            double hx = s * std::cos(phi) + so, hy = s * std::sin(phi), hz = c + mu;
            const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
            hz /= len;
            const double d = hz * hz * (a2 - 1.0) + 1.0;
            const double D = a2 / (pi * d * d);
            sum += D / (1.0 + lambda(mu) + lambda(c)) / (4.0 * mu);
        }
    }
    return sum * 2.0 * pi / (double(nt) * np);
}

TEST(PtAlbedoTables, IntegratorMatchesBruteForceQuadrature) {
    for (float r : {0.3f, 0.6f, 1.0f}) {
        for (float mu : {0.2f, 0.5f, 0.9f}) {
            const double expected = bruteForceMetalAlbedo(mu, r);
            const double got = pathtrace::ggxReflectionAlbedo(mu, r, 64);
            EXPECT_NEAR(got, expected, 3e-3) << "r " << r << " mu " << mu;
            EXPECT_LT(expected, 1.0);
        }
    }
    // Single scattering loses real energy on a rough metal: the reason for the compensation.
    EXPECT_LT(pathtrace::ggxReflectionAlbedo(0.5f, 1.0f, 64), 0.8);
}

// Mean of the sampling weights (energy: refracted weights times eta^2 undo the radiance scaling) = albedo.
double meanEnergyWeight(const PtSurface& s, float mu, std::mt19937& gen, int n) {
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
    double sum = 0.0;
    const float ior = s.ior;
    for (int i = 0; i < n; ++i) {
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
        if (lobe == kPtLobeNone) continue;
        double w = weight.y;
        if (s.thickness > 0.0f && wi.z < 0.0f) w *= double(ior) * ior;  // entered the denser side from outside
        sum += w;
    }
    return sum / n;
}

// The same albedo by deterministic quadrature of f cos over the sphere (midpoint grid in cos theta and phi), for
// lobes wide enough for the grid (roughness >= 0.5); refracted light counted as energy (times ior^2).
double quadratureEnergy(const PtSurface& s, float mu) {
    const int nz = 600, nphi = 200;
    const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
    double sum = 0.0;
    for (int a = 0; a < nz; ++a) {
        const float z = -1.0f + 2.0f * (float(a) + 0.5f) / float(nz);
        const float sr = std::sqrt(std::max(0.0f, 1.0f - z * z));
        for (int b = 0; b < nphi; ++b) {
            const float phi = 6.2831853f * (float(b) + 0.5f) / float(nphi);
            float pdf;
            const glm::vec3 f = ptEvalBsdf(s, wo, glm::vec3(sr * std::cos(phi), sr * std::sin(phi), z), pdf);
            sum += z < 0.0f && s.thickness > 0.0f ? f.y * double(s.ior) * s.ior : f.y;
        }
    }
    return sum * 4.0 * 3.14159265358979 / (double(nz) * nphi);
}

// Sampling (smooth lobes: the weights barely vary) or quadrature (rough lobes).
double energyAlbedo(const PtSurface& s, float mu, std::mt19937& gen) {
    return s.roughness >= 0.5f ? quadratureEnergy(s, mu) : meanEnergyWeight(s, mu, gen, 40000);
}

TEST(PtEnergy, WhiteFurnaceRoughMetalAndDielectric) {
    std::mt19937 gen(17);
    double worstMetal = 0.0, worstGlass = 0.0, worstSheet = 0.0, uncompensated = 1.0;
    for (int k = 0; k <= 10; ++k) {
        const float r = 0.1f * float(k);
        for (float mu : {0.95f, 0.7f, 0.4f, 0.15f}) {
            const double metal = energyAlbedo(whiteSurface(1.0f, r, 0.0f, 1.5f, 0.0f), mu, gen);
            EXPECT_NEAR(metal, 1.0, 0.01) << "white metal, roughness " << r << " mu " << mu;
            worstMetal = std::max(worstMetal, std::abs(metal - 1.0));
            const double glass = energyAlbedo(whiteSurface(0.0f, r, 1.0f, 1.5f, 1.0f), mu, gen);
            EXPECT_NEAR(glass, 1.0, 0.01) << "rough glass (from outside), roughness " << r << " mu " << mu;
            worstGlass = std::max(worstGlass, std::abs(glass - 1.0));
            const double sheet = energyAlbedo(whiteSurface(0.0f, r, 1.0f, 1.5f, 0.0f), mu, gen);
            EXPECT_NEAR(sheet, 1.0, 0.01) << "thin-walled dielectric, roughness " << r << " mu " << mu;
            worstSheet = std::max(worstSheet, std::abs(sheet - 1.0));
            uncompensated = std::min(uncompensated, pathtrace::ggxReflectionAlbedo(mu, r, 32));
        }
    }
    std::printf("white furnace worst |albedo - 1|: metal %.4f, glass %.4f, thin %.4f (single scattering alone: "
                "down to %.3f)\n", worstMetal, worstGlass, worstSheet, uncompensated);
}

// Light leaving the inside of a volume (eta = 1 / ior, total internal reflection): here sampling picks the
// transmission lobe rarely (the selection estimate sees total internal reflection at the macro normal) and its
// weights vary a lot, so the albedo is integrated deterministically instead: f cos over the sphere on a midpoint
// grid, the refracted half counted as energy (times eta^2 = 1 / ior^2: the BSDF carries radiance's 1 / eta^2).
TEST(PtEnergy, WhiteFurnaceRoughDielectricFromInside) {
    const int nz = 1200, nphi = 300;
    for (float r : {0.4f, 0.7f, 1.0f}) {
        for (float mu : {0.9f, 0.5f, 0.2f}) {
            PtSurface s = whiteSurface(0.0f, r, 1.0f, 1.5f, 1.0f);
            s.geometricNormal = glm::vec3(0.0f, 0.0f, -1.0f);  // wo is inside: on the back of the front face
            s.shadingNormal = s.geometricNormal;
            const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
            double sum = 0.0;
            for (int a = 0; a < nz; ++a) {
                const float z = -1.0f + 2.0f * (float(a) + 0.5f) / float(nz);
                const float sr = std::sqrt(std::max(0.0f, 1.0f - z * z));
                for (int b = 0; b < nphi; ++b) {
                    const float phi = 6.2831853f * (float(b) + 0.5f) / float(nphi);
                    float pdf;
                    const glm::vec3 f =
                        ptEvalBsdf(s, wo, glm::vec3(sr * std::cos(phi), sr * std::sin(phi), z), pdf);
                    sum += z < 0.0f ? f.y / (1.5 * 1.5) : f.y;
                }
            }
            const double albedo = sum * 4.0 * 3.14159265358979 / (double(nz) * nphi);
            EXPECT_NEAR(albedo, 1.0, 0.01) << "roughness " << r << " mu " << mu;
        }
    }
}

}  // namespace
}  // namespace idk::test
