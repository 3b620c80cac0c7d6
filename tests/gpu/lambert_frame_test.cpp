// lambert_frame_test.cpp: whole frames of the Lambert rasterizer (through the render graph) against the CPU
// ray-cast oracle, at 64x64 on the Cornell box and on a real glTF asset. Metric: a pixel is bad when a channel
// differs by more than 2% (relative above 1); silhouette pixels may differ because the raster samples the pixel
// centre with its own edge rules, so up to 3% bad pixels are allowed, and the mean error must stay below 0.005.
// A diff image (actual | expected | 10x difference) is written to the build tree on failure.
#include <gtest/gtest.h>

#include "app/default_scene.hpp"
#include "render/renderer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "support/lambert_oracle.hpp"

namespace idk::test {
namespace {

// The foundation's pass stays available behind RenderSettings::shading (the default is the deferred PBR frame).
render::RenderSettings lambertSettings() {
    render::RenderSettings s;
    s.shading = render::Shading::Lambert;
    return s;
}

class LambertFrameTest : public GpuTest {
protected:
    void checkAgainstOracle(const scene::Scene& scene, const std::string& name, uint32_t size = 64) {
        render::Renderer renderer(ctx(), shaders(), lambertSettings());
        renderer.setScene(scene);
        scene::CameraView camera = scene::defaultCamera(scene);
        render::FrameResult frame = renderer.renderOffscreen(camera, size, size);
        EXPECT_EQ(frame.passesRun, std::vector<std::string>{"lambert"});

        glm::mat4 viewProjection = scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera);
        core::ImageRgba32f expected =
            renderLambertReference(render::packLambertScene(scene), viewProjection, glm::vec3(0.03f), size, size);
        ImageComparison c = compareImages(frame.image, expected, 0.02f);
        bool ok = c.badPixelFraction <= 0.03 && c.meanAbsError <= 0.005;
        if (!ok) writeDiffImage(std::string(IDK_BINARY_DIR) + "/" + name + "_diff.exr", frame.image, expected);
        EXPECT_LE(c.badPixelFraction, 0.03) << name;
        EXPECT_LE(c.meanAbsError, 0.005) << name;
    }
};

TEST_F(LambertFrameTest, CornellBoxMatchesRayCastOracle) {
    scene::Scene scene = app::loadDefaultScene();
    ASSERT_FALSE(scene.lights.empty());
    checkAgainstOracle(scene, "cornell_box");
}

TEST_F(LambertFrameTest, CornellBoxShowsRedLeftAndGreenRightWalls) {
    scene::Scene scene = app::loadDefaultScene();
    render::Renderer renderer(ctx(), shaders(), lambertSettings());
    renderer.setScene(scene);
    render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), 64, 64);
    auto at = [&](uint32_t x, uint32_t y) { return &frame.image.pixels[(size_t(y) * 64 + x) * 4]; };
    const float* left = at(3, 32);
    const float* right = at(60, 32);
    EXPECT_GT(left[0], 2.0f * left[1]) << "left wall should be red";
    EXPECT_GT(right[1], 2.0f * right[0]) << "right wall should be green";
    float top = at(32, 2)[0] + at(32, 2)[1] + at(32, 2)[2];
    EXPECT_GT(top, 0.0f);
}

TEST_F(LambertFrameTest, SharedBoxAssetMatchesRayCastOracle) {
    scene::Scene scene = scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/Box/glTF-Binary/Box.glb");
    checkAgainstOracle(scene, "box");
}

TEST_F(LambertFrameTest, OutputSizeFollowsTheRequest) {
    scene::Scene scene = app::loadDefaultScene();
    render::Renderer renderer(ctx(), shaders(), lambertSettings());
    renderer.setScene(scene);
    render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), 48, 32);
    EXPECT_EQ(frame.image.width, 48u);
    EXPECT_EQ(frame.image.height, 32u);
    EXPECT_EQ(frame.image.pixels.size(), 48u * 32u * 4u);
    // One timestamp pair per executed pass, named after it.
    ASSERT_EQ(frame.passTimes.size(), 1u);
    EXPECT_EQ(frame.passTimes[0].name, "lambert");
    EXPECT_GT(frame.passTimes[0].milliseconds, 0.0);
    EXPECT_NE(frame.graphText.find("lambert"), std::string::npos);
}

}  // namespace
}  // namespace idk::test
