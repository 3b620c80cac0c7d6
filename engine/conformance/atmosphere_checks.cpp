// atmosphere_checks.cpp: "atmosphere/bake": the GPU sky bake (atmosphere/bake.comp.glsl through
// render::bakeAtmosphere) against CPU numerical integration of the same single-scattering model
// (render::atmosphereRadiance, double precision), for the sun high, low, at sunset (1 degree) and just below the
// horizon (-3 degrees), on a 32x16 map:
//  * same quadrature (32 x 8 midpoint steps): every texel within kSameTolerance relative (+ 1e-6 absolute): the
//    kernel computes what the C++ twin computes, up to float rounding;
//  * fine integration (256 x 64 steps) as the reference: the shipped quadrature's mean relative luminance error
//    per texel below 2% and its worst below 4% (seen on lavapipe: mean 0.2% at 60 degrees .. 1.2% at sunset,
//    worst 2.1%, at low sun where the sun rays cross the densest air).
// Moved from tests/conformance/atmosphere/atmosphere_bake_test.cpp (which keeps the CPU-only colour tests).
#include <algorithm>
#include <cmath>

#include "conformance/conformance.hpp"
#include "render/atmosphere.hpp"
#include "render/environment.hpp"

namespace idk::conformance {
namespace {

constexpr uint32_t kWidth = 32, kHeight = 16;
// Float against double on the same quadrature: the ground-hit rays below the horizon (short paths whose length
// comes from a ray-sphere test at planet scale) show the largest relative differences.
constexpr double kSameTolerance = 5e-3;

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

void bake(CheckEnv& env, Verdict& v) {
    for (float elevation : {60.0f, 20.0f, 5.0f, 1.0f, -3.0f}) {
        const std::string at = "sun at " + std::to_string(int(elevation)) + " degrees";
        const gpu::GpuAtmosphere params =
            render::earthAtmosphere(render::sunDirection(elevation, 35.0f), 20.0f, kWidth, kHeight);
        const core::ImageRgba32f sky = render::bakeAtmosphere(env.ctx, env.shaders, params);
        if (!v.expect(sky.width == kWidth && sky.height == kHeight, at + ": the map is not 32x16")) continue;
        double sumFine = 0.0, worstFine = 0.0, maxLum = 0.0;
        for (uint32_t y = 0; y < kHeight; ++y) {
            for (uint32_t x = 0; x < kWidth; ++x) {
                const glm::vec2 uv((x + 0.5f) / kWidth, (y + 0.5f) / kHeight);
                const glm::dvec3 d(render::equirectDirection(uv));
                const float* g = &sky.pixels[(size_t(y) * kWidth + x) * 4];
                const glm::dvec3 gpu(g[0], g[1], g[2]);
                const glm::dvec3 same = render::atmosphereRadiance(params, d, params.viewSamples, params.lightSamples);
                const glm::dvec3 fine = render::atmosphereRadiance(params, d, 256, 64);
                for (int c = 0; c < 3; ++c) {
                    v.recordError(std::abs(gpu[c] - same[c]) / (std::abs(same[c]) + 1e-3));
                    v.expect(std::abs(gpu[c] - same[c]) <= kSameTolerance * std::abs(same[c]) + 1e-6,
                             at + ", texel " + std::to_string(x) + "," + std::to_string(y) + " channel " +
                                 std::to_string(c) + ": GPU " + std::to_string(gpu[c]) + ", CPU " + std::to_string(same[c]));
                }
                const double lf = luminance(fine);
                maxLum = std::max(maxLum, lf);
                const double rel = std::abs(luminance(gpu) - lf) / std::max(lf, 1e-6);
                sumFine += rel;
                worstFine = std::max(worstFine, rel);
            }
        }
        const double meanFine = sumFine / (kWidth * kHeight);
        v.expect(maxLum > 1e-3, at + ": the sky is not lit");
        v.expect(meanFine < 0.02, at + ": mean error vs fine integration " + std::to_string(meanFine) + " (limit 0.02)");
        v.expect(worstFine < 0.04, at + ": worst error vs fine integration " + std::to_string(worstFine) + " (limit 0.04)");
    }
}

}  // namespace

std::vector<Check> atmosphereChecks() {
    return {{"atmosphere/bake", "",
             "5e-3 relative (+1e-6) vs the same quadrature; vs fine integration mean < 2%, worst < 4% luminance", bake}};
}

}  // namespace idk::conformance
