// denoise_test.cpp: the path tracer's denoiser (engine/passes/denoise.cpp) on the Vulkan device: its quality on a
// synthetic scene with known clean image (noise falls, edges stay, fireflies clamped, no leak from dark albedo, the
// variance input never makes it worse) and its robustness (sky/black/huge/NaN inputs give finite output that still
// matches the CPU oracle). The plain GPU-vs-oracle comparisons are registered checks (engine/conformance/
// denoise_checks.cpp: `idk conformance`, and ctest through tests/conformance/registry/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "conformance/denoise_harness.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

using namespace idk::conformance;  // the harness, the oracle and the comparison are shared with the registry

// RMSE over RGB of the pixels whose edge distance is in [minEdge, maxEdge] and that are not sky.
double rmse(const SyntheticScene& s, const std::vector<glm::vec4>& image, int minEdge, int maxEdge) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t k = 0; k < image.size(); ++k) {
        if (std::isinf(s.noisy.depth[k]) || s.edgeDistance[k] < minEdge || s.edgeDistance[k] > maxEdge) continue;
        for (int c = 0; c < 3; ++c) sum += double(image[k][c] - s.clean[k][c]) * (image[k][c] - s.clean[k][c]);
        n += 3;
    }
    return std::sqrt(sum / double(n));
}

size_t countNonFinite(const std::vector<glm::vec4>& image) {
    size_t n = 0;
    for (const glm::vec4& p : image)
        for (int c = 0; c < 4; ++c) n += std::isfinite(p[c]) ? 0 : 1;
    return n;
}

class Denoise : public GpuTest {};

TEST_F(Denoise, ZeroIterationsIsTheIdentityOnGeometry) {
    SyntheticScene s = makeSyntheticScene(48, 48, 0.5f, 3);
    std::vector<glm::vec4> out = denoiseOnGpu(ctx(), shaders(), s.noisy, passes::DenoiseSettings{0, 4, 128, 1, 0});
    for (size_t k = 0; k < out.size(); ++k)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(out[k][c], s.noisy.color[k][c], 1e-6f + 1e-6f * s.noisy.color[k][c]) << "pixel " << k;
}

// Quality on the synthetic scene (96x96, 60% multiplicative noise, like a few samples per pixel): the RMSE against
// the clean image falls by at least 4x overall, and by at least 2.5x on the pixels right next to an albedo, normal
// or depth edge (a filter that blurred across edges would raise their error instead; measured on the last run:
// see the printed values).
TEST_F(Denoise, ReducesNoiseAndPreservesEdges) {
    SyntheticScene s = makeSyntheticScene(96, 96, 0.6f, 1234);
    std::vector<glm::vec4> out = denoiseOnGpu(ctx(), shaders(), s.noisy, passes::DenoiseSettings{});
    ASSERT_EQ(countNonFinite(out), 0u);
    double noisyAll = rmse(s, s.noisy.color, 0, 8), outAll = rmse(s, out, 0, 8);
    double noisyEdge = rmse(s, s.noisy.color, 1, 1), outEdge = rmse(s, out, 1, 1);
    std::printf("denoise RMSE: all %.4f -> %.4f (%.1fx), at edges %.4f -> %.4f (%.1fx)\n", noisyAll, outAll,
                noisyAll / outAll, noisyEdge, outEdge, noisyEdge / outEdge);
    EXPECT_GE(noisyAll / outAll, 4.0);
    EXPECT_GE(noisyEdge / outEdge, 2.5);
    // Sky passes through unchanged.
    for (size_t k = 0; k < out.size(); ++k) {
        if (!std::isinf(s.noisy.depth[k])) continue;
        ASSERT_EQ(out[k], s.noisy.color[k]) << "sky pixel " << k;
    }
}

// Isolated 1000x samples (what a low-spp path tracer produces near small bright lights): with the firefly clamp the
// 5x5 area around each stays within 3x of the clean image; without it the spike survives the edge-stopping filter
// (more than 10x), which is why the clamp exists.
TEST_F(Denoise, FirefliesAreClampedToTheNeighbourhood) {
    SyntheticScene s = makeSyntheticScene(64, 64, 0.3f, 21);
    const glm::ivec2 spikes[] = {{12, 20}, {40, 30}, {20, 50}};
    for (glm::ivec2 p : spikes) s.noisy.color[size_t(p.y) * 64 + p.x] *= glm::vec4(1000.0f, 1000.0f, 1000.0f, 1.0f);
    passes::DenoiseSettings off;
    off.fireflyClamp = 0.0f;
    std::vector<glm::vec4> clamped = denoiseOnGpu(ctx(), shaders(), s.noisy, passes::DenoiseSettings{});
    std::vector<glm::vec4> unclamped = denoiseOnGpu(ctx(), shaders(), s.noisy, off);
    auto lum = [](glm::vec4 c) { return gpu::denoiseLuminance(glm::vec3(c)); };
    for (glm::ivec2 p : spikes) {
        size_t k = size_t(p.y) * 64 + p.x;
        EXPECT_GT(lum(unclamped[k]), 10.0f * lum(s.clean[k])) << p.x << "," << p.y;
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                size_t q = size_t(p.y + dy) * 64 + (p.x + dx);
                EXPECT_LT(lum(clamped[q]), 3.0f * lum(s.clean[q])) << p.x + dx << "," << p.y + dy;
            }
    }
}

// Radiance that does not scale with albedo (a specular highlight or emission on a black surface: radiance 0.4 on
// albedo 0.001 demodulates to 400) next to a bright diffuse surface on the same plane: the bright side must not
// pick up the amplified illumination (TransmissionTest's black label backgrounds blew up to 400 before the
// albedo-ratio weight), and the black side keeps roughly its own radiance.
TEST_F(Denoise, DarkAlbedoWithSpecularRadianceDoesNotLeak) {
    SyntheticScene s = makeSyntheticScene(64, 64, 0.0f, 1);
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            size_t k = y * 64 + x;
            s.noisy.normal[k] = glm::vec4(0, 0, 1, 0);
            s.noisy.depth[k] = 2.0f;
            bool black = (x / 4 + y / 4) % 2 == 0;  // 4x4 checker of black "label" and white "text"
            s.noisy.albedo[k] = black ? glm::vec4(0.001f, 0.001f, 0.001f, 1) : glm::vec4(1, 1, 1, 1);
            s.noisy.color[k] = black ? glm::vec4(0.4f, 0.4f, 0.4f, 1) : glm::vec4(0.8f, 0.8f, 0.8f, 1);
        }
    std::vector<glm::vec4> out = denoiseOnGpu(ctx(), shaders(), s.noisy, passes::DenoiseSettings{});
    for (size_t k = 0; k < out.size(); ++k)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(out[k][c], s.noisy.color[k][c], 0.1f) << "pixel " << k;
}

// Zero-luminance tiles, black geometry, every kind of sky guide (depth 0, inf, NaN, normal 0) and non-finite or
// negative radiance: the output is finite everywhere; sky keeps its (sanitized) radiance.
TEST_F(Denoise, DegenerateInputsStayFinite) {
    SyntheticScene s = makeSyntheticScene(64, 64, 0.6f, 5);
    DenoiseImages& in = s.noisy;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            size_t k = y * 64 + x;
            if (x >= 8 && x < 24 && y >= 16 && y < 32) in.color[k] = glm::vec4(0, 0, 0, 1);          // black tile
            if (x >= 8 && x < 24 && y >= 36 && y < 52) in.albedo[k] = glm::vec4(0, 0, 0, 1);         // black albedo
            if (x >= 40 && x < 44) in.depth[k] = 0.0f;                                                 // depth 0
            if (x >= 44 && x < 46) in.depth[k] = NAN;                                                  // depth NaN
            if (x >= 46 && x < 48 && y >= 20) in.normal[k] = glm::vec4(0.0f);                          // normal 0
            if (x == 30 && y == 30) in.color[k] = glm::vec4(NAN, INFINITY, -INFINITY, 1);              // bad radiance
            if (x == 31 && y == 40) in.color[k] = glm::vec4(-1.0f, 3e38f, 1.0f, 1);                    // huge
        }
    passes::DenoiseSettings settings;
    std::vector<glm::vec4> out = denoiseOnGpu(ctx(), shaders(), in, settings);
    EXPECT_EQ(countNonFinite(out), 0u);
    for (const glm::vec4& p : out)
        for (int c = 0; c < 3; ++c) ASSERT_GE(p[c], 0.0f);
    for (uint32_t y = 0; y < 64; ++y) {
        size_t k = y * 64 + 41;  // depth 0: passes through
        ASSERT_EQ(out[k], in.color[k]);
    }
    DenoiseDiff d = compareDenoised(out, DenoiseOracle(in).run(settings));
    EXPECT_LE(d.worst, 1.0f) << "the oracle sanitizes the same way";
}

// Radiance around 1e6 (and 1e9 after demodulating by a zero albedo): no overflow, the constant part is kept.
TEST_F(Denoise, LargeValuesDoNotOverflow) {
    SyntheticScene s = makeSyntheticScene(48, 48, 0.3f, 9);
    DenoiseImages& in = s.noisy;
    for (size_t k = 0; k < in.color.size(); ++k) {
        in.color[k] = glm::vec4(glm::vec3(in.color[k]) * 1e6f, 1.0f);
        if (k % 48 < 24) in.albedo[k] = glm::vec4(0, 0, 0, 1);
    }
    std::vector<glm::vec4> out = denoiseOnGpu(ctx(), shaders(), in, passes::DenoiseSettings{});
    EXPECT_EQ(countNonFinite(out), 0u);
    DenoiseDiff d = compareDenoised(out, DenoiseOracle(in).run(passes::DenoiseSettings{}));
    EXPECT_LE(d.worst, 1.0f);

    DenoiseImages flat = in;  // a constant 1e6 image is a fixed point of the filter
    for (glm::vec4& c : flat.color) c = glm::vec4(1e6f, 1e6f, 1e6f, 1.0f);
    for (glm::vec4& a : flat.albedo) a = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    std::vector<glm::vec4> flatOut = denoiseOnGpu(ctx(), shaders(), flat, passes::DenoiseSettings{});
    for (const glm::vec4& p : flatOut)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(p[c], 1e6f, 1e6f * 1e-5f);
}

}  // namespace
}  // namespace idk::test

namespace idk::test {
namespace {

// Never worse than the input: with the per-pixel variance, at every noise level from heavy (0.6) to almost none
// (0.001: a high sample count), the denoised RMSE against the clean image is at most the noisy one's. Without the
// variance, the neighbourhood's spread (the irradiance and albedo detail) passes for noise at low levels and the
// filter blurs real detail: worse than the input (the case this input fixes).
TEST_F(Denoise, WithVarianceNeverWorseThanTheInput) {
    passes::DenoiseSettings settings;
    for (float noise : {0.6f, 0.2f, 0.05f, 0.01f, 0.001f}) {
        SyntheticScene s = makeSyntheticScene(72, 56, noise, 3);
        const double raw = rmse(s, s.noisy.color, 0, 8);
        const double spatialOnly = rmse(s, denoiseOnGpu(ctx(), shaders(), s.noisy, settings), 0, 8);
        addVariance(s, noise, false);
        const double withVariance = rmse(s, denoiseOnGpu(ctx(), shaders(), s.noisy, settings), 0, 8);
        std::printf("noise %.3f: RMSE raw %.6f, denoised (spatial variance) %.6f, denoised (pixel variance) %.6f\n",
                    noise, raw, spatialOnly, withVariance);
        EXPECT_LE(withVariance, raw) << "noise " << noise;
        if (noise == 0.001f) {
            EXPECT_GT(spatialOnly, raw) << "the spatial estimate over-blurs at low noise";
        }
    }
}

}  // namespace
}  // namespace idk::test
