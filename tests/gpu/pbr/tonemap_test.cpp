// tonemap_test.cpp: the tonemap pass against the C++ AgX (support/pbr_oracle.cpp): the same frame rendered as
// linear HDR (EXR path, no tonemap) and as display bytes (PNG path); every display byte must equal
// round(255 * srgb(agx(exposure * hdr))) within 1 code (rounding of the GPU's float math and UNORM conversion).
// Also checks a few AgX anchor points: black stays black, middle grey maps near display grey, white clips below 1.
#include <gtest/gtest.h>

#include <cmath>

#include "app/default_scene.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/pbr_oracle.hpp"

namespace idk::test {
namespace {

class TonemapTest : public GpuTest, public ::testing::WithParamInterface<float> {};

TEST_P(TonemapTest, DisplayBytesAreAgxOfTheHdrFrame) {
    const float exposure = GetParam();
    scene::Scene scene = app::loadDefaultScene();
    render::Renderer renderer(ctx(), shaders());
    renderer.settings().exposure = exposure;
    renderer.setScene(scene);
    scene::CameraView camera = scene::defaultCamera(scene);
    renderer.settings().output = render::OutputKind::Hdr;
    render::FrameResult hdr = renderer.renderOffscreen(camera, 64, 64);
    renderer.settings().output = render::OutputKind::Display;
    render::FrameResult display = renderer.renderOffscreen(camera, 64, 64);
    ASSERT_EQ(display.display.size(), hdr.image.pixels.size());
    int worst = 0;
    for (size_t p = 0; p < hdr.image.pixels.size() / 4; ++p) {
        glm::dvec3 radiance(hdr.image.pixels[p * 4], hdr.image.pixels[p * 4 + 1], hdr.image.pixels[p * 4 + 2]);
        glm::dvec3 shown = agx(radiance * double(exposure));
        for (int c = 0; c < 3; ++c) {
            int want = int(std::lround(srgbEncode(shown[c]) * 255.0));
            worst = std::max(worst, std::abs(int(display.display[p * 4 + c]) - want));
        }
        EXPECT_EQ(display.display[p * 4 + 3], 255);
    }
    EXPECT_LE(worst, 1) << "largest difference in 8-bit codes";
}

INSTANTIATE_TEST_SUITE_P(Exposures, TonemapTest, ::testing::Values(1.0f, 4.0f));

TEST(AgxOracle, AnchorPoints) {
    EXPECT_LT(agx(glm::dvec3(0.0)).x, 1e-4);
    double grey = srgbEncode(agx(glm::dvec3(0.18)).x);
    EXPECT_GT(grey, 0.35);  // AgX base places scene middle grey a bit below display middle grey
    EXPECT_LT(grey, 0.55);
    EXPECT_LT(agx(glm::dvec3(1.0)).x, 1.0);
    EXPECT_GT(agx(glm::dvec3(16.0)).x, 0.9);                    // the shoulder approaches display white
    EXPECT_LT(agx(glm::dvec3(0.5)).x, agx(glm::dvec3(0.6)).x);  // monotonic
}

}  // namespace
}  // namespace idk::test
