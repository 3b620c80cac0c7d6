// camera_controller_test.cpp: the fly camera (tools/camera_controller.hpp): the original's dynamics (terminal
// speed a / k with k = -144 log10(0.95), Shift x5, the rest snap), mouse look with the pitch clamp, bit-exact
// determinism, view round trips, and scripted key input driving the camera into the walls of the real Cornell box
// (scenes/cornell_box.gltf): it stops at its radius from the wall, slides along it, never leaves the box.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "scene/gltf_loader.hpp"
#include "tools/camera_controller.hpp"
#include "tools/scene_triangles.hpp"

namespace idk::tools {
namespace {

constexpr float kDt = 1.0f / 60.0f;

bool sameBits(const FlyCameraState& a, const FlyCameraState& b) {
    return std::memcmp(&a.position, &b.position, sizeof a.position) == 0 && std::memcmp(&a.yaw, &b.yaw, 4) == 0 &&
           std::memcmp(&a.pitch, &b.pitch, 4) == 0 && std::memcmp(&a.velocity, &b.velocity, sizeof a.velocity) == 0;
}

TEST(FlyCamera, ReachesTheOriginalsTerminalSpeedAndStops) {
    FlyCameraParams params;
    FlyCameraState s;
    FlyInput w;
    w.forward = true;
    for (int i = 0; i < 600; ++i) s = stepFlyCamera(s, w, kDt, params, nullptr);
    // Per step: v' = (v + a dt) * exp(-k dt), k = -144 log10(0.95): the fixed point is a dt e / (1 - e).
    const float e = std::exp(144.0f * std::log10(0.95f) * kDt);
    const float terminal = params.acceleration * kDt * e / (1.0f - e);
    EXPECT_NEAR(glm::length(s.velocity), terminal, 1e-3f * terminal);
    EXPECT_NEAR(s.velocity.z, -terminal, 1e-3f * terminal);  // yaw 0 looks down -Z
    FlyInput fast = w;
    fast.fast = true;
    for (int i = 0; i < 600; ++i) s = stepFlyCamera(s, fast, kDt, params, nullptr);
    EXPECT_NEAR(glm::length(s.velocity), 5.0f * terminal, 5e-3f * terminal);
    // Released: drag brings it to an exact stop (the rest snap), after which it does not move at all.
    for (int i = 0; i < 600; ++i) s = stepFlyCamera(s, FlyInput{}, kDt, params, nullptr);
    EXPECT_EQ(s.velocity, glm::vec3(0.0f));
    const FlyCameraState rest = stepFlyCamera(s, FlyInput{}, kDt, params, nullptr);
    EXPECT_TRUE(sameBits(rest, s));
}

TEST(FlyCamera, MouseLookTurnsRightAndClampsPitch) {
    FlyCameraParams params;
    FlyInput look;
    look.mouseDelta = {1000.0f, 0.0f};  // 90 degrees at 0.09 degrees per pixel
    FlyCameraState s = stepFlyCamera(FlyCameraState{}, look, kDt, params, nullptr);
    const glm::vec3 f = flyForward(s.yaw, s.pitch);
    EXPECT_NEAR(f.x, 1.0f, 1e-5f);  // turned right from -Z: +X
    look.mouseDelta = {0.0f, -5000.0f};  // far up
    s = stepFlyCamera(s, look, kDt, params, nullptr);
    EXPECT_NEAR(s.pitch, 89.99f * 3.14159265f / 180.0f, 1e-5f);
    look.mouseDelta = {0.0f, 1e5f};
    s = stepFlyCamera(s, look, kDt, params, nullptr);
    EXPECT_NEAR(s.pitch, -89.99f * 3.14159265f / 180.0f, 1e-5f);
    const scene::CameraView view = toCameraView(s, scene::CameraView{});
    EXPECT_NEAR(glm::dot(view.forward, view.up), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(view.up), 1.0f, 1e-5f);
}

TEST(FlyCamera, ViewRoundTrip) {
    scene::CameraView view;
    view.position = {1, 2, 3};
    view.forward = glm::normalize(glm::vec3(0.3f, -0.4f, 0.8f));
    view.up = glm::normalize(glm::cross(glm::cross(view.forward, glm::vec3(0, 1, 0)), view.forward));
    view.yfov = 0.7f;
    const scene::CameraView back = toCameraView(fromCameraView(view), view);
    EXPECT_NEAR(glm::length(back.forward - view.forward), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(back.up - view.up), 0.0f, 1e-5f);
    EXPECT_EQ(back.position, view.position);
    EXPECT_EQ(back.yfov, 0.7f);
}

class CornellBox : public ::testing::Test {
protected:
    void SetUp() override {
        scene_ = scene::loadGltf(std::filesystem::path(IDK_SOURCE_DIR) / "scenes/cornell_box.gltf");
        world_ = CollisionWorld::fromScene(scene_);
        params_.radius = 0.05f;
    }
    // The box (from the file): x in [-0.556, 0], y in [0, 0.5488], back wall z = -0.5592, open at z = 0.
    scene::Scene scene_;
    CollisionWorld world_;
    FlyCameraParams params_;
};

TEST_F(CornellBox, ScriptedWalkIntoTheBackWallStopsThenSlides) {
    size_t triangles = 0;
    for (const scene::Instance& inst : scene_.instances)
        for (const scene::Primitive& prim : scene_.meshes[inst.mesh].primitives) triangles += prim.indices.size() / 3;
    ASSERT_EQ(world_.triangles().size(), triangles);
    // High up (above both blocks), looking at the back wall, W held at the original's full acceleration (30 m/s^2:
    // several radii per frame at top speed in this 0.56 m box).
    FlyCameraState s;
    s.position = {-0.45f, 0.45f, -0.1f};
    FlyInput w;
    w.forward = true;
    w.fast = true;
    const float wallZ = -0.5592f;
    const float skin = params_.collision.skinWidth;
    for (int i = 0; i < 60; ++i) {
        s = stepFlyCamera(s, w, kDt, params_, &world_);
        ASSERT_GE(s.position.z, wallZ + params_.radius) << "frame " << i;
    }
    EXPECT_NEAR(s.position.z, wallZ + params_.radius + skin, 1e-4f);
    EXPECT_NEAR(s.position.x, -0.45f, 1e-5f);
    EXPECT_NEAR(s.velocity.z, 0.0f, 1e-6f);  // no velocity left into the wall
    // Held against the wall: not a bit of jitter.
    const FlyCameraState pressed = s;
    for (int i = 0; i < 30; ++i) s = stepFlyCamera(s, w, kDt, params_, &world_);
    EXPECT_TRUE(sameBits(s, pressed));

    // Turn 45 degrees right and keep W held: slides along the back wall towards +X until the green wall's
    // corner, staying at the back wall.
    FlyInput turn = w;
    turn.mouseDelta = {500.0f, 0.0f};
    s = stepFlyCamera(s, turn, kDt, params_, &world_);
    float previousX = s.position.x;
    int slidingFrames = 0;
    for (int i = 0; i < 120; ++i) {
        s = stepFlyCamera(s, w, kDt, params_, &world_);
        ASSERT_NEAR(s.position.z, wallZ + params_.radius + skin, 1e-4f) << "left the wall at frame " << i;
        if (s.position.x > previousX + 1e-5f) ++slidingFrames;
        previousX = s.position.x;
    }
    EXPECT_GT(slidingFrames, 4);
    EXPECT_NEAR(s.position.x, -(params_.radius + skin), 1e-4f);  // in the corner with the green wall (x = 0)
}

TEST_F(CornellBox, RandomFlyingAtTopSpeedNeverLeavesTheBoxNorEntersTheBlocks) {
    // The box closed by a glass front at z = 0, so the flight stays inside.
    std::vector<bvh::Triangle> tris = sceneWorldTriangles(scene_);
    tris.push_back({{-0.556f, 0, 0}, {0, 0, 0}, {0, 0.5488f, 0}});
    tris.push_back({{-0.556f, 0, 0}, {0, 0.5488f, 0}, {-0.556f, 0.5488f, 0}});
    const CollisionWorld closed = CollisionWorld::fromTriangles(tris);
    std::mt19937 rng(3);
    FlyCameraState s;
    s.position = {-0.278f, 0.4f, -0.3f};
    const float r = params_.radius;
    float travelled = 0.0f;
    for (int i = 0; i < 3000; ++i) {
        FlyInput in;
        const unsigned bits = rng();
        in.forward = bits & 1;
        in.back = bits & 2;
        in.left = bits & 4;
        in.right = bits & 8;
        in.up = (bits & 48) == 48;
        in.fast = true;
        in.mouseDelta = {float(int(rng() % 200) - 100), float(int(rng() % 200) - 100)};
        const glm::vec3 before = s.position;
        s = stepFlyCamera(s, in, kDt, params_, &closed);
        const glm::vec3 p = s.position;
        travelled += glm::length(p - before);
        ASSERT_TRUE(p.x >= -0.556f + r && p.x <= -r && p.y >= r && p.y <= 0.5488f - r && p.z >= -0.5592f + r &&
                    p.z <= -r)
            << "frame " << i << " at " << p.x << ", " << p.y << ", " << p.z;
        for (const bvh::Triangle& tri : tris)
            ASSERT_GE(glm::length(p - closestPointOnTriangle(tri, p)), r) << "frame " << i << " inside an object";
    }
    EXPECT_GT(travelled, 20.0f);  // it really flew about (the box is 0.56 m across)
}

TEST_F(CornellBox, SameInputsGiveBitIdenticalPaths) {
    std::mt19937 rng(11);
    std::vector<FlyInput> inputs(500);
    std::vector<float> dts(500);
    for (size_t i = 0; i < inputs.size(); ++i) {
        const unsigned bits = rng();
        inputs[i].forward = bits & 1;
        inputs[i].left = bits & 2;
        inputs[i].up = bits & 4;
        inputs[i].fast = bits & 8;
        inputs[i].mouseDelta = {float(rng() % 50) - 25.0f, float(rng() % 50) - 25.0f};
        dts[i] = 1.0f / float(30 + rng() % 120);
    }
    auto run = [&]() {
        const CollisionWorld world = CollisionWorld::fromScene(scene_);
        FlyCameraState s;
        s.position = {-0.278f, 0.3f, -0.2f};
        std::vector<FlyCameraState> path;
        for (size_t i = 0; i < inputs.size(); ++i) path.push_back(s = stepFlyCamera(s, inputs[i], dts[i], params_, &world));
        return path;
    };
    const std::vector<FlyCameraState> a = run(), b = run();
    for (size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(sameBits(a[i], b[i])) << "step " << i;
}

}  // namespace
}  // namespace idk::tools
