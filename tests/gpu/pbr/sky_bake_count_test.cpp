// sky_bake_count_test.cpp: `--sky atmosphere` bakes the sky when the sun moves, not every frame
// (frame/environment_feature.cpp, EnvironmentFeature::skyBakes): MetalRoughSpheresNoTextures at 32x32 (the sky fills
// the background), counted exactly:
//  * `--sky hdr` bakes nothing;
//  * three frames with a still sun: one bake; an unrelated setting (exposure) changed: still one;
//  * the sun moved (elevation, then azimuth): one more bake each, however many frames follow, and the background
//    changes with it (the new sky is the one shown).
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 32;

double meanAbsDifference(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
    return sum / double(a.pixels.size());
}

class SkyBakeCountTest : public GpuTest {};

TEST_F(SkyBakeCountTest, TheSkyBakesOncePerSunMove) {
    const scene::Scene scene = scene::loadGltf(
        std::string(IDK_SHARED_DIR) + "/scenes/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb");
    const scene::CameraView camera = scene::defaultCamera(scene);
    {
        render::Renderer hdr(ctx(), shaders(), render::RenderSettings{});
        hdr.setScene(scene);
        hdr.renderOffscreen(camera, kSize, kSize);
        EXPECT_EQ(hdr.environment().skyBakes(), 0u) << "--sky hdr baked a sky";
    }
    render::RenderSettings settings;
    settings.atmosphere.enabled = true;
    settings.atmosphere.sunElevation = 30.0f;
    settings.atmosphere.width = 64;
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    core::ImageRgba32f before;
    for (int i = 0; i < 3; ++i) before = renderer.renderOffscreen(camera, kSize, kSize).image;
    EXPECT_EQ(renderer.environment().skyBakes(), 1u) << "three frames under a still sun";
    renderer.settings().exposure *= 2.0f;
    renderer.renderOffscreen(camera, kSize, kSize);
    renderer.settings().exposure /= 2.0f;
    EXPECT_EQ(renderer.environment().skyBakes(), 1u) << "an exposure change rebaked the sky";

    renderer.settings().atmosphere.sunElevation = 4.0f;  // towards sunset: a redder, darker sky
    core::ImageRgba32f after;
    for (int i = 0; i < 3; ++i) after = renderer.renderOffscreen(camera, kSize, kSize).image;
    EXPECT_EQ(renderer.environment().skyBakes(), 2u) << "the sun moved once";
    const double change = meanAbsDifference(before, after);
    std::printf("sun 30 -> 4 degrees: mean |difference| of the frames %.4f\n", change);
    EXPECT_GT(change, 1e-3) << "the new sky is not the one shown";

    renderer.settings().atmosphere.sunAzimuth = 90.0f;
    renderer.renderOffscreen(camera, kSize, kSize);
    renderer.renderOffscreen(camera, kSize, kSize);
    EXPECT_EQ(renderer.environment().skyBakes(), 3u) << "the sun moved a second time";
}

}  // namespace
}  // namespace idk::test
