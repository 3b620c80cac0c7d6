// sampling_test.cpp: alias tables select each entry with exactly its weight's share; environment sampling is
// consistent (Monte Carlo integral of the radiance by NEE samples = the exact texel sum, pdf integrates to 1,
// sampled directions land in the chosen texel); triangle-light sampling pdf = ptLightPdf and its Monte Carlo
// solid angle matches the exact one; the RNG is uniform.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pathtrace/alias_table.hpp"
#include "pathtrace/environment_map.hpp"
#include "shared/pt_sampling.h"

namespace idk::test {
namespace {

using namespace idk::gpu;
using pathtrace::buildAliasTable;

TEST(PtAlias, ProbabilitiesAreExact) {
    std::mt19937 gen(2);
    std::uniform_real_distribution<double> uni(0.0, 10.0);
    for (size_t n : {1u, 2u, 3u, 7u, 100u, 1000u}) {
        std::vector<double> w(n);
        double sum = 0.0;
        for (size_t i = 0; i < n; ++i) {
            w[i] = (i % 5 == 3) ? 0.0 : uni(gen) * uni(gen);
            sum += w[i];
        }
        const auto table = buildAliasTable(w);
        ASSERT_EQ(table.size(), n);
        const std::vector<double> p = pathtrace::aliasSelectionProbabilities(table);
        for (size_t i = 0; i < n; ++i) {
            EXPECT_NEAR(p[i], w[i] / sum, 1e-6) << "n " << n << " i " << i;
            EXPECT_NEAR(table[i].probability, w[i] / sum, 1e-6);
            if (w[i] == 0.0) {
                EXPECT_EQ(p[i], 0.0) << "a zero weight is never selected";
            }
        }
    }
    EXPECT_TRUE(buildAliasTable(std::vector<double>{0.0, 0.0}).empty());
    EXPECT_TRUE(buildAliasTable(std::vector<double>{}).empty());
    const auto withBad = buildAliasTable(std::vector<double>{1.0, std::nan(""), -3.0, INFINITY, 1.0});
    ASSERT_EQ(withBad.size(), 5u);
    EXPECT_NEAR(pathtrace::aliasSelectionProbabilities(withBad)[0], 0.5, 1e-7);
}

TEST(PtAlias, SamplingFollowsTheTable) {
    const std::vector<double> w = {1.0, 0.0, 3.0, 6.0};
    const auto table = buildAliasTable(w);
    PtRng rng = ptRngInit(1, 2, 3);
    std::vector<int> counts(4, 0);
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const uint slot = ptAliasSlot(ptRandom(rng), 4);
        ++counts[ptAliasResolve(table[slot], slot, ptRandom(rng))];
    }
    EXPECT_EQ(counts[1], 0);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(counts[size_t(i)] / double(n), w[size_t(i)] / 10.0, 0.005);
}

core::ImageRgba32f testSky(uint32_t w, uint32_t h) {
    core::ImageRgba32f img;
    img.width = w;
    img.height = h;
    img.pixels.resize(size_t(w) * h * 4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float* p = &img.pixels[(size_t(y) * w + x) * 4];
            const bool sun = x == 5 && y == 3;
            p[0] = sun ? 50.0f : 0.2f + 0.1f * float(x % 3);
            p[1] = sun ? 40.0f : 0.3f + 0.05f * float(y);
            p[2] = sun ? 30.0f : (y == h - 1 ? 0.0f : 0.6f);
            p[3] = 1.0f;
        }
    return img;
}

TEST(PtEnvironment, SampledIntegralMatchesTheExactSum) {
    const uint32_t w = 16, h = 8;
    const pathtrace::EnvironmentMap env = pathtrace::buildEnvironmentMap(testSky(w, h), 2.0f);
    // Exact: sum of radiance x texel solid angle.
    glm::dvec3 exact(0.0);
    for (uint32_t y = 0; y < h; ++y) {
        const double sa = 2.0 * M_PI / w * (std::cos(M_PI * y / h) - std::cos(M_PI * (y + 1) / h));
        for (uint32_t x = 0; x < w; ++x) exact += glm::dvec3(env.radiance[y * w + x]) * sa;
    }
    PtRng rng = ptRngInit(9, 0, 0);
    glm::dvec3 sum(0.0);
    const int n = 400000;
    int wrongTexel = 0;
    for (int i = 0; i < n; ++i) {
        const uint slot = ptAliasSlot(ptRandom(rng), w * h);
        const uint texel = ptAliasResolve(env.aliasTable[slot], slot, ptRandom(rng));
        glm::vec3 dir;
        const float pdf = ptSampleEnvironment(texel, env.aliasTable[texel].probability, w, h,
                                              glm::vec2(ptRandom(rng), ptRandom(rng)), dir);
        if (!(pdf > 0.0f)) continue;
        if (ptEnvironmentTexel(dir, w, h) != texel) ++wrongTexel;
        // The pdf of the direction as a BSDF-sampled ray would see it (MIS) equals the sampling pdf.
        EXPECT_NEAR(ptEnvironmentPdf(env.aliasTable[texel].probability, dir, w, h), pdf, 1e-3f * pdf);
        sum += glm::dvec3(env.radiance[texel]) / double(pdf);
    }
    const glm::dvec3 estimate = sum / double(n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(estimate[c], exact[c], 0.01 * exact[c]) << c;
    EXPECT_LT(wrongTexel, n / 1000) << "samples that map back to another texel (rounding at texel borders)";
}

TEST(PtEnvironment, PdfIntegratesToOne) {
    const uint32_t w = 16, h = 8;
    const pathtrace::EnvironmentMap env = pathtrace::buildEnvironmentMap(testSky(w, h), 1.0f);
    PtRng rng = ptRngInit(4, 4, 4);
    double sum = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        const float z = 1.0f - 2.0f * ptRandom(rng), phi = 6.2831853f * ptRandom(rng);
        const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const glm::vec3 dir(s * std::cos(phi), z, s * std::sin(phi));
        const uint texel = ptEnvironmentTexel(dir, w, h);
        sum += ptEnvironmentPdf(env.aliasTable[texel].probability, dir, w, h) * 4.0 * M_PI;
    }
    EXPECT_NEAR(sum / n, 1.0, 0.02);
}

TEST(PtEnvironment, ConstantEnvironmentHasEqualRadianceEverywhere) {
    const pathtrace::EnvironmentMap env = pathtrace::constantEnvironment(glm::vec3(0.5f, 1.0f, 2.0f));
    EXPECT_EQ(env.lookup(glm::vec3(0.0f, 1.0f, 0.0f)), glm::vec3(0.5f, 1.0f, 2.0f));
    EXPECT_EQ(env.lookup(glm::normalize(glm::vec3(1.0f, -0.3f, 0.2f))), glm::vec3(0.5f, 1.0f, 2.0f));
    EXPECT_TRUE(pathtrace::constantEnvironment(glm::vec3(0.0f)).black());
}

TEST(PtLights, TriangleSamplingPdfMatchesAndIntegratesToTheSolidAngle) {
    GpuPtLight l{};
    l.type = kPtLightTriangle;
    l.position = glm::vec3(-0.5f, 1.0f, -0.5f);
    l.direction = glm::vec3(1.0f, 0.0f, 0.0f);  // edge 1
    l.edge2 = glm::vec3(0.0f, 0.0f, 1.0f);      // edge 2: front normal = cross(e1, e2) = (0, -1, 0), facing p
    l.intensity = glm::vec3(1.0f);
    const glm::vec3 p(0.1f, 0.0f, 0.2f);
    PtRng rng = ptRngInit(1, 1, 1);
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        PtLightSample s;
        ASSERT_TRUE(ptSampleLight(l, p, glm::vec2(ptRandom(rng), ptRandom(rng)), s));
        EXPECT_NEAR(ptLightPdf(l, p, s.position), s.pdf, 1e-4f * s.pdf);
        EXPECT_NEAR(s.u + s.v, std::min(1.0f, s.u + s.v), 1e-6f);
        sum += 1.0 / s.pdf;
    }
    // Exact solid angle of the triangle (Van Oosterom & Strackee).
    const glm::dvec3 a = glm::dvec3(l.position - p), b = glm::dvec3(l.position + l.direction - p),
                     c = glm::dvec3(l.position + l.edge2 - p);
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double num = std::abs(glm::dot(a, glm::cross(b, c)));
    const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    const double omega = 2.0 * std::atan2(num, den);
    EXPECT_NEAR(sum / n, omega, 0.01 * omega);
    // The back of a single-sided emitter is dark; a double-sided one is not.
    PtLightSample s;
    EXPECT_FALSE(ptSampleLight(l, glm::vec3(0.0f, 2.0f, 0.0f), glm::vec2(0.5f), s));
    l.flags = kPtLightDoubleSided;
    EXPECT_TRUE(ptSampleLight(l, glm::vec3(0.0f, 2.0f, 0.0f), glm::vec2(0.5f), s));
}

TEST(PtRng, UniformAndDecorrelated) {
    std::vector<int> bins(16, 0);
    double sum = 0.0;
    const int n = 160000;
    for (int i = 0; i < n; ++i) {
        PtRng rng = ptRngInit(uint(i), uint(i / 7), 5);
        const float u = ptRandom(rng);
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        ++bins[size_t(u * 16.0f)];
        sum += u;
    }
    for (int b : bins) EXPECT_NEAR(b, n / 16, 5 * std::sqrt(n / 16.0));
    EXPECT_NEAR(sum / n, 0.5, 0.003);
    PtRng a = ptRngInit(1, 0, 0), b = ptRngInit(0, 1, 0), c = ptRngInit(0, 0, 1);
    EXPECT_NE(ptNextUint(a), ptNextUint(b));
    EXPECT_NE(ptNextUint(b), ptNextUint(c));
}

}  // namespace
}  // namespace idk::test
