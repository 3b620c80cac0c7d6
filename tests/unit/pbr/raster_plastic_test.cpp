// raster_plastic_test.cpp: the rasterizer's direct-light BRDF (tests/support/pbr_oracle.cpp, the twin of
// include/pbr.glsl's brdfCosine with material_layers.glsl's albedo-scaled diffuse weight) on a white plastic
// (base colour 1, metallic 0): its directional albedo, integrated here with two stratified strategies (cosine and
// the GGX visible normals) combined by the balance heuristic, is 1 within 1% for roughness 0..1 and view cosines
// down to 0.1 (the per-half-vector 1 - F weight it replaced reached 1.27 at roughness 0.2, cosine 0.2); the lobe's
// diffuse part is reciprocal and is the path tracers' weight (shared/pt_bsdf_frame.h ptDiffuseWeight).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shared/pt_sampling.h"
#include "support/pbr_oracle.hpp"
#include "support/plastic_weight.hpp"
#include "support/pt_surface.hpp"

namespace idk::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinRoughness = 0.045;  // pbr.glsl's clamp

glm::dvec3 view(double mu) { return glm::dvec3(std::sqrt(1.0 - mu * mu), 0.0, mu); }

// Directional albedo of the white plastic's brdfCosine at view cosine mu (green channel).
double rasterAlbedo(double roughness, double mu) {
    const glm::dvec3 n(0.0, 0.0, 1.0), v = view(mu), white(1.0);
    const double r = std::clamp(roughness, kMinRoughness, 1.0);
    const float alpha = float(r * r);
    const glm::vec3 vf(v);
    auto pdfCos = [](const glm::dvec3& l) { return std::max(l.z, 0.0) / kPi; };
    auto pdfSpec = [&](const glm::dvec3& l) {
        const glm::dvec3 h = glm::normalize(l + v);
        const double vh = glm::dot(v, h);
        return vh > 0.0 ? double(gpu::ptGgxVndfPdf(vf, glm::vec3(h), alpha)) / (4.0 * vh) : 0.0;
    };
    const int n1 = 200;
    double sum = 0.0;
    for (int strategy = 0; strategy < 2; ++strategy) {
        for (int a = 0; a < n1; ++a) {
            for (int b = 0; b < n1; ++b) {
                const double u1 = (a + 0.5) / n1, u2 = (b + 0.5) / n1;
                glm::dvec3 l;
                if (strategy == 0) {
                    const double s = std::sqrt(u1), phi = 2.0 * kPi * u2;
                    l = glm::dvec3(s * std::cos(phi), s * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1)));
                } else {
                    const glm::dvec3 h(gpu::ptSampleGgxVndf(vf, alpha, float(u1), float(u2)));
                    l = glm::normalize(2.0 * glm::dot(v, h) * h - v);
                }
                if (l.z <= 0.0) continue;
                const double p = pdfCos(l) + pdfSpec(l);
                if (p > 0.0) sum += brdfCosine(white, 0.0, roughness, n, v, l).y / p;
            }
        }
    }
    return sum / (double(n1) * n1);
}

TEST(PbrPlastic, WhiteFurnace) {
    double worst = 0.0;
    for (int k = 0; k <= 10; ++k) {
        const double r = 0.1 * k;
        for (double mu : {0.95, 0.7, 0.4, 0.2, 0.1}) {
            const double e = rasterAlbedo(r, mu);
            EXPECT_NEAR(e, 1.0, 0.01) << "white plastic, roughness " << r << " mu " << mu;
            worst = std::max(worst, std::abs(e - 1.0));
        }
    }
    std::printf("raster white plastic: worst |albedo - 1| %.4f\n", worst);
}

// The diffuse part of brdfCosine (the white base minus the black one) is reciprocal and equals the path tracers'
// Lambert lobe of the same plastic (IOR 1.5, its sanitised roughness): diffScale (1 - Es(mu_i)) / pi from
// ptBsdfSetup, to float precision.
TEST(PbrPlastic, DiffuseLobeIsThePathTracers) {
    const glm::dvec3 n(0.0, 0.0, 1.0);
    double worstRecip = 0.0, worstPt = 0.0;
    for (double r : {0.1, 0.3, 0.6, 1.0}) {
        for (double muO : {0.9, 0.5, 0.15}) {
            for (double muI : {0.8, 0.35, 0.12}) {
                const glm::dvec3 v = view(muO);
                const glm::dvec3 l(-std::sqrt(1.0 - muI * muI) * 0.6, std::sqrt(1.0 - muI * muI) * 0.8, muI);
                auto diffuse = [&](const glm::dvec3& a, const glm::dvec3& b) {
                    return (brdfCosine(glm::dvec3(1.0), 0.0, r, n, a, b).y - brdfCosine(glm::dvec3(0.0), 0.0, r, n, a, b).y) /
                           b.z;
                };
                const double f = diffuse(v, l), fr = diffuse(l, v);
                worstRecip = std::max(worstRecip, std::abs(f - fr) / f);
                const gpu::PtSurface s = plainPtSurface(glm::vec3(1.0f), 0.0f, float(r));
                gpu::PtBsdfFrame fr0;
                ASSERT_TRUE(gpu::ptBsdfSetup(s, glm::vec3(v), fr0));
                const double pt = double(gpu::ptDiffuseWeight(fr0, float(muI))) / kPi;
                worstPt = std::max(worstPt, std::abs(f - pt) / pt);
                EXPECT_NEAR(f, pt, 1e-5 * pt) << "roughness " << r << " mu_o " << muO << " mu_i " << muI;
            }
        }
    }
    EXPECT_LT(worstRecip, 1e-9);
    std::printf("raster diffuse lobe: reciprocity %.2e, vs path tracer %.2e (relative)\n", worstRecip, worstPt);
}

}  // namespace
}  // namespace idk::test
