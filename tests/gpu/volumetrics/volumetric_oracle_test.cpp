// volumetric_oracle_test.cpp: volumetric lighting against a CPU ray march of the same medium and lights. Scene: a
// floor, a box and a point light above it (its cube shadow hides part of the medium), 128x128 HDR frames with no
// environment light. Per pixel the CPU predicts frame_off * T + L along the pixel's centre ray (T = exp(-sigma d)
// to the surface, L = sum over 512 midpoint steps of T(t) sigma I / r^2 HG(cos) V, V = the CPU ray test from the
// step to the light through the box) and the GPU frame with volumetrics on must match it: mean relative error
// below 3% and 95th percentile below 12% at half and at quarter resolution (errors stated; the largest are at the
// box's silhouette, where the upsample mixes depths, and at the edges of the shadow in the medium). The same
// prediction without V must be clearly worse: the medium's shadows are really there. The scene and the march are
// support/volumetric_oracle.hpp (shared with the benchmark's volumetrics rows).
#include <gtest/gtest.h>

#include <filesystem>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"
#include "support/volumetric_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = kShadowFrameSize;

core::ImageRgba32f renderFrame(vk::Context& ctx, vk::ShaderLibrary& shaders, const VolumetricCase& c, bool volumetrics,
                               uint32_t scale) {
    render::Renderer renderer(ctx, shaders, volumetricSettings(c, volumetrics, scale));
    renderer.setScene(c.scene);
    return renderer.renderOffscreen(c.camera, kSize, kSize).image;
}

class VolumetricOracleTest : public GpuTest {};

TEST_F(VolumetricOracleTest, InScatteringMatchesACpuRayMarchWithShadows) {
    const VolumetricCase c = volumetricCase();
    const core::ImageRgba32f off = renderFrame(ctx(), shaders(), c, false, 2);
    const VolumetricPrediction p = predictVolumetrics(c, off, kSize);
    for (uint32_t scale : {2u, 4u}) {
        const core::ImageRgba32f on = renderFrame(ctx(), shaders(), c, true, scale);
        std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "volumetric_oracle_test";
        std::filesystem::create_directories(dir);
        core::writeImage((dir / ("on_scale" + std::to_string(scale) + ".exr")).string(), on);
        const RelativeErrors e = relativeErrors(on, p.predicted), u = relativeErrors(on, p.unshadowed),
                             none = relativeErrors(on, p.withoutMedium);
        EXPECT_LT(e.mean, 0.02) << "scale " << scale;
        EXPECT_LT(e.p95, 0.05) << "scale " << scale;
        EXPECT_GT(none.mean, 0.2) << "the medium changes the frame a lot";
        EXPECT_GT(u.mean, 2.0 * e.mean) << "scale " << scale << ": ignoring the medium's shadows must be worse";
        std::printf("volumetrics 1/%u: mean relative error %.4f, p95 %.4f (without the medium's shadows: mean %.4f)\n",
                    scale, e.mean, e.p95, u.mean);
    }
}

}  // namespace
}  // namespace idk::test
