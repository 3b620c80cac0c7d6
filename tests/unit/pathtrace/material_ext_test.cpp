// material_ext_test.cpp: the material extensions of the shared BSDF (shared/pt_bsdf_frame.h) against values
// computed here by hand, in double, from the extension specifications' formulas at chosen angles:
// KHR_materials_specular (a rough dielectric: GGX reflection with the scaled Fresnel + Lambert beneath + the
// multiple-scattering term), KHR_materials_clearcoat (a coat over Lambert), KHR_materials_sheen (the Charlie
// lobe over Lambert, albedo-scaled); and that sampling each lobe agrees with evaluation (pdf and weight).
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

PtSurface surface(glm::vec3 base, float metallic, float roughness, float ior) {
    return plainPtSurface(base, metallic, roughness, ior);
}

dvec3 dir(double cosTheta, double phi) {
    const double s = std::sqrt(1.0 - cosTheta * cosTheta);
    return dvec3(s * std::cos(phi), s * std::sin(phi), cosTheta);
}

double ggxD(double c, double alpha) {
    const double a2 = alpha * alpha, d = c * c * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}
double smithLambda(double c, double alpha) {
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * (1.0 - c * c) / (c * c)) - 1.0);
}
double fresnelExact(double c, double eta) {  // unpolarised, from outside
    const double cosT = std::sqrt(1.0 - (1.0 - c * c) / (eta * eta));
    const double rs = (c - eta * cosT) / (c + eta * cosT), rp = (eta * c - cosT) / (eta * c + cosT);
    return 0.5 * (rs * rs + rp * rp);
}
double schlick(double f0, double c) { return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0); }

void expectNear(glm::vec3 got, dvec3 expected, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], expected[c], 2e-4 * std::max(1.0, std::abs(expected[c]))) << what << " channel " << c;
}

TEST(PtMaterialExt, SpecularByHand) {
    PtSurface s = surface(glm::vec3(0.5f, 0.4f, 0.3f), 0.0f, 0.5f, 1.5f);
    s.specular = 0.6f;
    s.specularColor = glm::vec3(1.0f, 0.5f, 3.0f);  // above 1 is legal: f0 is clamped after scaling
    const dvec3 wo = dir(0.8, 0.0), wi = dir(0.6, 2.5);
    float pdf;
    const glm::vec3 got = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf);

    const double alpha = 0.25, f0 = 0.04;
    const dvec3 h = glm::normalize(wo + wi);
    const double w = (fresnelExact(glm::dot(wo, h), 1.5) - f0) / (1.0 - f0);
    const dvec3 f0s = glm::min(f0 * dvec3(1.0, 0.5, 3.0), dvec3(1.0));
    const dvec3 F = 0.6 * (f0s + (1.0 - f0s) * w);
    const double G2 = 1.0 / (1.0 + smithLambda(wo.z, alpha) + smithLambda(wi.z, alpha));
    const dvec3 spec = F * ggxD(h.z, alpha) * G2 / (4.0 * wo.z);
    // The Lambert base beneath, albedo-scaled by the reflection lobe's albedo (its strongest channel: blue).
    const double weight = plasticDiffuseWeight({0.5f, 1.5, 0.6, std::min(f0 * 3.0, 1.0)}, wo.z, wi.z);
    const dvec3 diffuse = dvec3(0.5, 0.4, 0.3) * weight / kPi * wi.z;
    // Multiple scattering (Kulla-Conty) with the tabulated E (checked against the integrator in energy_test).
    const double eo = ptAlbedoMetal(float(wo.z), 0.5f), ei = ptAlbedoMetal(float(wi.z), 0.5f);
    const double eavg = ptAlbedoMetalAvg(0.5f);
    const double favgExact = 0.5 / (4.08567 + 1.00071 * 1.5);  // Kulla-Conty's fit of the average exact Fresnel
    const dvec3 favg = 0.6 * (f0s + (1.0 - f0s) * (favgExact - f0) / (1.0 - f0));
    const dvec3 fms = favg * favg * eavg / (1.0 - favg * (1.0 - eavg));
    const dvec3 ms = fms * (1.0 - eo) * (1.0 - ei) / (kPi * (1.0 - eavg)) * wi.z;
    expectNear(got, spec + diffuse + ms, "specular");
    // Without the extension's weight the surface reflects more and passes less to the diffuse.
    s.specular = 1.0f;
    s.specularColor = glm::vec3(1.0f);
    float pdf1;
    const glm::vec3 full = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf1);
    EXPECT_GT(ptMaxComponent(full - got), 0.0f);
    // specular = 0: pure Lambert, the case (no white grazing sheen on a surface authored as Lambert).
    s.specular = 0.0f;
    const glm::vec3 lambert = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(dir(0.05, 2.5)), pdf1);
    expectNear(lambert, dvec3(0.5, 0.4, 0.3) / kPi * 0.05, "specular 0");
}

TEST(PtMaterialExt, ClearcoatByHand) {
    PtSurface s = surface(glm::vec3(0.7f, 0.2f, 0.1f), 0.0f, 0.6f, 1.0f);  // IOR 1: Lambert base, no base spec
    s.clearcoat = 0.8f;
    s.clearcoatRoughness = 0.3f;
    const dvec3 wo = dir(0.7, 0.0), wi = dir(0.5, 3.0);
    float pdf;
    const glm::vec3 got = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf);
    const double alpha = 0.09;
    const dvec3 h = glm::normalize(wo + wi);
    const double coat = 0.8 * schlick(0.04, glm::dot(wo, h)) * ggxD(h.z, alpha) /
                        (1.0 + smithLambda(wo.z, alpha) + smithLambda(wi.z, alpha)) / (4.0 * wo.z);
    const double layer = 1.0 - 0.8 * schlick(0.04, wo.z);
    const dvec3 base = dvec3(0.7, 0.2, 0.1) / kPi * wi.z * layer;
    expectNear(got, base + coat, "clearcoat");
    // A smooth coat is a delta lobe: evaluation leaves it out, sampling picks it with its Fresnel weight.
    s.clearcoatRoughness = 0.0f;
    expectNear(ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf), base, "smooth clearcoat");
    glm::vec3 sampled, weight;
    float p;
    uint lobe;
    ptSampleBsdf(s, glm::vec3(wo), glm::vec3(0.0f, 0.5f, 0.5f), sampled, weight, p, lobe);
    EXPECT_EQ(lobe, kPtLobeClearcoat | kPtLobeDeltaFlag);
    EXPECT_NEAR(sampled.z, wo.z, 1e-5);
    EXPECT_NEAR(weight.x * p, 0.8 * schlick(0.04, wo.z), 1e-5);
}

double sheenL(double x, double alpha) {
    const double t = (1.0 - alpha) * (1.0 - alpha);
    auto lerp = [&](double a, double b) { return a + (b - a) * t; };
    return lerp(21.5473, 25.3245) / (1.0 + lerp(3.82987, 3.32435) * std::pow(x, lerp(0.19823, 0.16801))) +
           lerp(-1.97760, -1.27393) * x + lerp(-4.32054, -4.85967);
}
double sheenLambda(double c, double alpha) {
    return c < 0.5 ? std::exp(sheenL(c, alpha)) : std::exp(2.0 * sheenL(0.5, alpha) - sheenL(1.0 - c, alpha));
}

TEST(PtMaterialExt, SheenByHand) {
    PtSurface s = surface(glm::vec3(0.3f, 0.6f, 0.9f), 0.0f, 0.5f, 1.0f);
    s.sheenColor = glm::vec3(1.0f, 0.5f, 0.0f);
    s.sheenRoughness = 0.6f;
    for (double cosI : {0.9, 0.4, 0.1}) {
        const dvec3 wo = dir(0.3, 0.0), wi = dir(cosI, 2.0);
        float pdf;
        const glm::vec3 got = ptEvalBsdf(s, glm::vec3(wo), glm::vec3(wi), pdf);
        const double alpha = 0.36;
        const dvec3 h = glm::normalize(wo + wi);
        const double sinH = std::sqrt(1.0 - h.z * h.z);
        const double D = (2.0 + 1.0 / alpha) * std::pow(sinH, 1.0 / alpha) / (2.0 * kPi);
        const double V = 1.0 / ((1.0 + sheenLambda(wo.z, alpha) + sheenLambda(wi.z, alpha)) * 4.0 * wo.z * wi.z);
        const dvec3 sheen = dvec3(1.0, 0.5, 0.0) * D * V * wi.z;
        const double scale = 1.0 - 1.0 * ptAlbedoSheen(float(wo.z), 0.6f);
        const dvec3 base = dvec3(0.3, 0.6, 0.9) / kPi * wi.z * scale;
        expectNear(got, sheen + base, "sheen");
    }
    // The sheen albedo the table holds stays below 1 and grows toward grazing for a rough sheen.
    EXPECT_GT(ptAlbedoSheen(0.1f, 1.0f), ptAlbedoSheen(0.9f, 1.0f));
    EXPECT_LT(ptAlbedoSheen(0.1f, 1.0f), 1.0f);
}

// Every lobe's samples carry pdf = the evaluated pdf and weight = f cos / pdf (one-sample MIS over the lobes).
TEST(PtMaterialExt, SampledPdfAndWeightMatchEvaluation) {
    std::mt19937 gen(31);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    PtSurface layered = surface(glm::vec3(0.6f, 0.5f, 0.4f), 0.3f, 0.7f, 1.5f);
    layered.clearcoat = 0.7f;
    layered.clearcoatRoughness = 0.2f;
    layered.sheenColor = glm::vec3(0.8f, 0.6f, 0.7f);
    layered.sheenRoughness = 0.4f;
    layered.specular = 0.7f;
    layered.specularColor = glm::vec3(0.9f, 1.2f, 0.5f);
    int perLobe[8] = {};
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 wo = glm::vec3(dir(0.05 + 0.95 * uni(gen), 6.2831853 * uni(gen)));
        glm::vec3 wi, weight;
        float pdf;
        uint lobe;
        ptSampleBsdf(layered, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
        if (lobe == kPtLobeNone || (lobe & kPtLobeDeltaFlag) != 0u) continue;
        float evalPdf;
        const glm::vec3 f = ptEvalBsdf(layered, wo, wi, evalPdf);
        ASSERT_NEAR(evalPdf, pdf, 1e-4f * std::max(1.0f, pdf)) << i;
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(weight[c], f[c] / evalPdf, 1e-3f * std::max(1.0f, weight[c])) << i;
        ++perLobe[lobe & 7u];
    }
    for (uint lobe : {kPtLobeDiffuse, kPtLobeSpecular, kPtLobeMultiScatter, kPtLobeSheen, kPtLobeClearcoat})
        EXPECT_GT(perLobe[lobe], 100) << "lobe " << lobe;
}

}  // namespace
}  // namespace idk::test
