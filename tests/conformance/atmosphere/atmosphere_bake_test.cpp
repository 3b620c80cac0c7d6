// atmosphere_bake_test.cpp: the GPU sky bake (atmosphere/bake.comp.glsl) against CPU numerical integration of the
// same single-scattering model (render/atmosphere.hpp atmosphereRadiance, double precision), for the sun high,
// low, at sunset (1 degree) and just below the horizon (-3 degrees), on a 32x16 map:
//  * same quadrature (32 x 8 midpoint steps): every texel within kSameTolerance relative (+ 1e-6 absolute): the kernel
//    computes what the C++ twin computes, up to float rounding;
//  * fine integration (256 x 64 steps) as the reference: the shipped quadrature's error, mean and worst relative
//    luminance error per texel stated, below 2% mean and 4% worst (seen: mean 0.2% at 60 degrees .. 1.2% at
//    sunset, worst 2.1%, at low sun where the sun rays cross the densest air).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/atmosphere.hpp"
#include "render/environment.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kWidth = 32, kHeight = 16;
// Float against double on the same quadrature: the ground-hit rays below the horizon (short paths whose length
// comes from a ray-sphere test at planet scale) show the largest relative differences.
constexpr double kSameTolerance = 5e-3;

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

class AtmosphereBakeTest : public GpuTest {};

TEST_F(AtmosphereBakeTest, GpuBakeMatchesCpuIntegrationAtSeveralSunAngles) {
    for (float elevation : {60.0f, 20.0f, 5.0f, 1.0f, -3.0f}) {
        const gpu::GpuAtmosphere params =
            render::earthAtmosphere(render::sunDirection(elevation, 35.0f), 20.0f, kWidth, kHeight);
        const core::ImageRgba32f gpuSky = render::bakeAtmosphere(ctx(), shaders(), params);
        ASSERT_EQ(gpuSky.width, kWidth);
        double worstSame = 0.0, sumFine = 0.0, worstFine = 0.0, maxLum = 0.0;
        uint32_t texels = 0;
        for (uint32_t y = 0; y < kHeight; ++y) {
            for (uint32_t x = 0; x < kWidth; ++x) {
                glm::vec2 uv((x + 0.5f) / kWidth, (y + 0.5f) / kHeight);
                glm::dvec3 d(render::equirectDirection(uv));
                const float* g = &gpuSky.pixels[(size_t(y) * kWidth + x) * 4];
                glm::dvec3 gpu(g[0], g[1], g[2]);
                glm::dvec3 same = render::atmosphereRadiance(params, d, params.viewSamples, params.lightSamples);
                glm::dvec3 fine = render::atmosphereRadiance(params, d, 256, 64);
                for (int c = 0; c < 3; ++c) {
                    double err = std::abs(gpu[c] - same[c]) / (std::abs(same[c]) + 1e-3);
                    worstSame = std::max(worstSame, err);
                    EXPECT_LE(std::abs(gpu[c] - same[c]), kSameTolerance * std::abs(same[c]) + 1e-6)
                        << "elevation " << elevation << " texel " << x << "," << y << " channel " << c;
                }
                double lf = luminance(fine);
                maxLum = std::max(maxLum, lf);
                double rel = std::abs(luminance(gpu) - lf) / std::max(lf, 1e-6);
                sumFine += rel;
                worstFine = std::max(worstFine, rel);
                ++texels;
            }
        }
        const double meanFine = sumFine / texels;
        EXPECT_GT(maxLum, 1e-3) << "the sky is lit at elevation " << elevation;
        EXPECT_LT(meanFine, 0.02) << "elevation " << elevation;
        EXPECT_LT(worstFine, 0.04) << "elevation " << elevation;
        std::printf("sun %5.1f deg: GPU vs same-quadrature CPU worst %.2e; vs fine integration mean %.4f worst "
                    "%.4f (relative luminance)\n",
                    elevation, worstSame, meanFine, worstFine);
    }
}

TEST_F(AtmosphereBakeTest, SunsetIsRedderThanNoonAndTheSkyBelowTheHorizonIsDim) {
    auto colour = [&](float elevation, glm::dvec3 d) {
        return render::atmosphereRadiance(render::earthAtmosphere(render::sunDirection(elevation, 0.0f), 20.0f, 1, 1),
                                          glm::normalize(d), 32, 8);
    };
    glm::dvec3 towardsSun(0.0, 0.02, -1.0);
    glm::dvec3 noon = colour(60.0f, towardsSun), sunset = colour(1.0f, towardsSun);
    EXPECT_GT(sunset.r / sunset.b, 2.0 * noon.r / noon.b) << "long paths near the horizon scatter the blue out";
    EXPECT_GT(colour(60.0f, {0, 1, 0}).b, colour(60.0f, {0, 1, 0}).r) << "a high sun gives a blue zenith";
    EXPECT_LT(luminance(colour(-3.0f, {0, 1, 0})), 0.05 * luminance(colour(20.0f, {0, 1, 0})));
}

}  // namespace
}  // namespace idk::test
