// vrs_motion_test.cpp: the VRS classifier's speed comes from the temporal motion vectors (object, skinned and camera
// motion), also with --aa none: InterpolationTest's nodes move (pose_upload) between two frames while the camera
// stands still over the static sky. Checked: the motion-vector pass runs without the TAA resolve; the classifier's
// captured inputs (lit image, velocity) give its rates exactly through the CPU oracle; the velocity is non-zero on
// the moving objects; every tile's rate is at least what camera-only motion (zero for a still camera) gives, and
// the moving objects' tiles, and only they, are coarser.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "frame/vrs_oracle.hpp"
#include "render/renderer.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kWidth = 128, kHeight = 96;

bool ran(const render::FrameResult& f, const char* pass) {
    return std::find(f.passesRun.begin(), f.passesRun.end(), pass) != f.passesRun.end();
}

class VrsMotionTest : public GpuTest {};

TEST_F(VrsMotionTest, MovingObjectsUnderAStillCameraGetCoarserRates) {
    scene::Scene scene = scene::loadGltf(std::string(IDK_SHARED_DIR) +
                                         "/scenes/InterpolationTest/glTF-Binary/InterpolationTest.glb");
    const double t0 = 0.5, t1 = 0.6;
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.vrs.enabled = true;
    settings.vrs.frameSeconds = float(t1 - t0);  // the motion between the two frames, per second
    ASSERT_EQ(settings.temporal.aa, frame::AntiAliasing::None);
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    renderer.vrs().captureClassification(true);
    const scene::CameraView camera = scene::defaultCamera(scene);

    scene::evaluateAnimations(scene, t0);
    renderer.setPose(scene);
    renderer.renderOffscreen(camera, kWidth, kHeight);
    scene::evaluateAnimations(scene, t1);
    renderer.setPose(scene);
    const render::FrameResult f = renderer.renderOffscreen(camera, kWidth, kHeight);
    EXPECT_TRUE(ran(f, "motion_vectors"));
    EXPECT_TRUE(ran(f, "vrs_velocity"));
    EXPECT_TRUE(ran(f, "vrs_classify"));
    EXPECT_FALSE(ran(f, "taa_resolve")) << "--aa none: motion vectors for VRS only, no TAA";

    const frame::VrsCapture c = renderer.vrs().capturedClassification();
    ASSERT_EQ(c.width, kWidth);
    ASSERT_EQ(c.lit.size(), size_t(kWidth) * kHeight);
    ASSERT_EQ(c.velocity.size(), size_t(kWidth) * kHeight);
    const frame::VrsSettings& vrs = settings.vrs;
    const frame::VrsTileRates oracle = frame::classifyTilesCpu(c.lit, c.velocity, kWidth, kHeight, c.tileSize,
                                                               vrs.frameSeconds, vrs.speedFactor, vrs.lumVarianceFactor);
    EXPECT_EQ(c.rates, oracle.rates) << "the classifier differs from its CPU oracle on the captured frame";
    const frame::VrsTileRates cameraOnly = frame::classifyTilesCpu(c.lit, {}, kWidth, kHeight, c.tileSize,
                                                                   vrs.frameSeconds, vrs.speedFactor,
                                                                   vrs.lumVarianceFactor);
    ASSERT_EQ(cameraOnly.rates.size(), c.rates.size());

    // A tile moves when one of its pixels moves by more than 0.05 px (the still camera's reprojection of the sky
    // leaves rounding noise around 1e-7 UV).
    std::vector<bool> moving(c.rates.size(), false);
    float fastest = 0.0f;
    size_t movingPixels = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const float px = glm::length(c.velocity[size_t(y) * kWidth + x] * glm::vec2(kWidth, kHeight));
            fastest = std::max(fastest, px);
            if (px > 0.05f) {
                movingPixels++;
                moving[(y / c.tileSize) * c.tilesX + x / c.tileSize] = true;
            }
        }
    size_t coarser = 0, movingTiles = 0;
    for (size_t t = 0; t < c.rates.size(); ++t) {
        movingTiles += moving[t];
        EXPECT_GE(c.rates[t], cameraOnly.rates[t]) << "tile " << t << ": motion can only coarsen";
        if (c.rates[t] > cameraOnly.rates[t]) {
            coarser++;
            EXPECT_TRUE(moving[t]) << "tile " << t << " is coarser without moving";
        }
    }
    std::cout << "[ vrs ] " << movingPixels << " moving pixels (fastest " << fastest << " px/frame) in " << movingTiles
              << " of " << c.rates.size() << " tiles; " << coarser << " tiles coarser than camera-only motion gives\n";
    EXPECT_GT(movingPixels, 100u) << "the objects must move";
    EXPECT_LT(movingTiles, c.rates.size()) << "the background must stand still";
    EXPECT_GT(coarser, 0u) << "object motion must coarsen some tiles";
}

}  // namespace
}  // namespace idk::test
