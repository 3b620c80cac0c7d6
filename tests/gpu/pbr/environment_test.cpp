// environment_test.cpp: the environment's CPU side (engine/render/environment.cpp): the equirectangular mapping
// round-trips, and the SH9 irradiance projection reproduces analytic irradiance for environments whose
// irradiance lies in the first bands: constant L -> E = pi L; L = 1 + d.y -> E(n) = pi + (2 pi / 3) n.y
// (Ramamoorthi & Hanrahan 2001). Tolerance 0.2% (a 256x128 quadrature). Also the mip chain's shape and mean.
#include <gtest/gtest.h>

#include <cmath>

#include "render/environment.hpp"

namespace idk::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

core::ImageRgba32f equirect(uint32_t w, uint32_t h, glm::vec3 (*radiance)(const glm::vec3&)) {
    core::ImageRgba32f img{w, h, std::vector<float>(size_t(w) * h * 4, 1.0f)};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            glm::vec3 d = render::equirectDirection(glm::vec2((x + 0.5f) / w, (y + 0.5f) / h));
            glm::vec3 l = radiance(d);
            float* p = &img.pixels[(size_t(y) * w + x) * 4];
            p[0] = l.r, p[1] = l.g, p[2] = l.b;
        }
    return img;
}

const glm::vec3 kNormals[] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0.48f, 0.6f, 0.64f}};

TEST(Environment, EquirectMappingRoundTrips) {
    EXPECT_NEAR(render::equirectDirection({0.5f, 0.5f}).z, -1.0f, 1e-6f);  // u = 0.5 looks down -Z
    EXPECT_NEAR(render::equirectDirection({0.5f, 0.0f}).y, 1.0f, 1e-6f);   // v = 0 is straight up
    for (glm::vec2 uv : {glm::vec2(0.1f, 0.2f), glm::vec2(0.7f, 0.9f), glm::vec2(0.33f, 0.5f)}) {
        glm::vec2 back = render::equirectUv(render::equirectDirection(uv));
        EXPECT_NEAR(back.x, uv.x, 1e-5f);
        EXPECT_NEAR(back.y, uv.y, 1e-5f);
    }
}

TEST(Environment, ShIrradianceOfAConstantEnvironmentIsPiL) {
    render::ShIrradiance sh =
        render::projectIrradianceSh(equirect(256, 128, [](const glm::vec3&) { return glm::vec3(0.5f, 1.0f, 2.0f); }));
    for (const glm::vec3& n : kNormals) {
        glm::vec3 e = render::evaluateIrradianceSh(sh, glm::normalize(n));
        EXPECT_NEAR(e.r, kPi * 0.5, 2e-3 * kPi * 0.5);
        EXPECT_NEAR(e.g, kPi * 1.0, 2e-3 * kPi);
        EXPECT_NEAR(e.b, kPi * 2.0, 2e-3 * kPi * 2.0);
    }
}

// The renderer's constant environment (`--environment none`) is a 1x1 image: one texel covers the whole sphere,
// so the projection must integrate over the texel's area, not take its centre direction (which put all the light
// on the horizon and gave a floor E = 0.589 pi L). Same 0.2% tolerance at every size down to one texel.
TEST(Environment, ShIrradianceOfACoarseConstantEnvironmentIsPiL) {
    for (glm::uvec2 size : {glm::uvec2(1, 1), glm::uvec2(2, 1), glm::uvec2(4, 2), glm::uvec2(3, 5)}) {
        render::ShIrradiance sh = render::projectIrradianceSh(
            equirect(size.x, size.y, [](const glm::vec3&) { return glm::vec3(0.5f); }));
        for (const glm::vec3& n : kNormals)
            EXPECT_NEAR(render::evaluateIrradianceSh(sh, glm::normalize(n)).r, kPi * 0.5, 2e-3 * kPi * 0.5)
                << size.x << "x" << size.y << " texels, n = (" << n.x << ", " << n.y << ", " << n.z << ")";
    }
}

TEST(Environment, ShIrradianceOfALinearGradientMatchesTheAnalyticIntegral) {
    render::ShIrradiance sh =
        render::projectIrradianceSh(equirect(256, 128, [](const glm::vec3& d) { return glm::vec3(1.0f + d.y); }));
    for (const glm::vec3& n : kNormals) {
        glm::vec3 u = glm::normalize(n);
        double want = kPi + 2.0 * kPi / 3.0 * u.y;
        EXPECT_NEAR(render::evaluateIrradianceSh(sh, u).r, want, 2e-3 * kPi);
    }
}

TEST(Environment, MipChainHalvesToOneTexelAndKeepsTheMean) {
    core::ImageRgba32f img = equirect(64, 16, [](const glm::vec3& d) { return glm::vec3(d.x * d.x + 0.25f); });
    double mean0 = 0.0;
    for (size_t p = 0; p < img.pixels.size(); p += 4) mean0 += img.pixels[p];
    mean0 /= double(img.pixels.size() / 4);
    std::vector<core::ImageRgba32f> mips = render::buildMipChain(img);
    ASSERT_EQ(mips.size(), 7u);  // 64x16 -> 32x8 -> 16x4 -> 8x2 -> 4x1 -> 2x1 -> 1x1
    EXPECT_EQ(mips[4].width, 4u);
    EXPECT_EQ(mips[4].height, 1u);
    EXPECT_EQ(mips.back().width, 1u);
    EXPECT_NEAR(mips.back().pixels[0], mean0, 1e-5);
}

}  // namespace
}  // namespace idk::test
