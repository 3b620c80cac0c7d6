// animation_frame_test.cpp: whole frames at a given time (`idk render --time T [--animation N]`): goldens (128x128,
// metric in support/golden.hpp) of Fox mid-run (clip 2 "Run" at T = 0.55 s, side view) and SimpleMorph (T = 1.5 s);
// the same T gives bit-identical images (after another time in between, and from a fresh renderer); `--stats
// --json` lists skinning and "animation" memory only for scenes with skins or morphs. IDKEngine has no such tests.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/cli.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "support/golden.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 128;

std::string shared(const char* path) { return std::string(IDK_SHARED_DIR) + "/scenes/" + path; }

// One display frame of `path` posed at `time` (animation `animation`, -1: all), textures fully streamed in,
// seen from `zoom` x the auto-fit distance of the rest-pose bounds (morph targets may leave them), at orbit angle
// `theta` (0: from +Z like the default camera) and 10 degrees up.
std::vector<uint8_t> renderAt(const char* path, double time, int animation, float theta, float zoom) {
    scene::Scene scene = scene::loadGltf(shared(path));
    scene::evaluateAnimations(scene, time, animation);
    render::Renderer renderer(sharedContext(), sharedShaders());
    renderer.setScene(scene);
    render::SceneTextureStream textures(sharedContext(), renderer, scene);
    textures.finishSynchronously();
    const float radius = 0.5f * glm::length(scene.bounds.max - scene.bounds.min);
    scene::CameraView camera =
        scene::orbitCamera(scene.bounds.centre(), zoom * scene::autoFitDistance(radius), theta, glm::radians(80.0f));
    return renderer.renderOffscreen(camera, kSize, kSize).display;
}

class AnimationFrameTest : public GpuTest {};

TEST_F(AnimationFrameTest, FoxMidRunMatchesGolden) {
    std::vector<uint8_t> frame = renderAt("Fox/glTF-Binary/Fox.glb", 0.55, 2, glm::radians(90.0f), 1.0f);  // side view
    GoldenResult g = compareWithGolden("anim_fox_run", frame, kSize, kSize);
    EXPECT_TRUE(g.passed) << g.message;
}

TEST_F(AnimationFrameTest, SimpleMorphMatchesGolden) {
    std::vector<uint8_t> frame = renderAt("SimpleMorph/glTF/SimpleMorph.gltf", 1.5, -1, 0.0f, 2.0f);
    GoldenResult g = compareWithGolden("anim_simple_morph", frame, kSize, kSize);
    EXPECT_TRUE(g.passed) << g.message;
}

TEST_F(AnimationFrameTest, SameTimeGivesBitIdenticalFrames) {
    scene::Scene fox = scene::loadGltf(shared("Fox/glTF-Binary/Fox.glb"));
    render::Renderer renderer(ctx(), shaders());
    renderer.setScene(fox);
    scene::CameraView camera = scene::defaultCamera(fox);
    auto at = [&](double t) {
        scene::evaluateAnimations(fox, t, 2);
        renderer.setPose(fox);
        return renderer.renderOffscreen(camera, 64, 64).display;
    };
    std::vector<uint8_t> a = at(0.3), b = at(0.8), c = at(0.3);
    EXPECT_TRUE(a == c) << "the same time rendered twice differs";
    EXPECT_FALSE(a == b) << "t = 0.3 and t = 0.8 look the same: the pose did not reach the GPU";

    // A fresh renderer whose scene was posed before upload (the path `idk render --time` takes).
    scene::Scene posed = scene::loadGltf(shared("Fox/glTF-Binary/Fox.glb"));
    scene::evaluateAnimations(posed, 0.3, 2);
    render::Renderer fresh(ctx(), shaders());
    fresh.setScene(posed);
    EXPECT_TRUE(fresh.renderOffscreen(camera, 64, 64).display == a);
}

nlohmann::json renderJson(const std::vector<std::string>& args) {
    ::testing::internal::CaptureStdout();
    int code = app::runRender(args);
    std::string out = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(code, 0) << out;
    return nlohmann::json::parse(out);
}

bool contains(const nlohmann::json& passes, const char* name) {
    auto list = passes.get<std::vector<std::string>>();
    return std::find(list.begin(), list.end(), name) != list.end();
}

TEST_F(AnimationFrameTest, StatsShowSkinningOnlyForScenesThatNeedIt) {
    std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "animation_frame_test";
    std::string png = (dir / "frame.png").string();
    nlohmann::json box = renderJson({shared("Box/glTF-Binary/Box.glb"), "--out", png, "--size", "16x16", "--json"});
    EXPECT_FALSE(contains(box["passes"], "skinning"));
    EXPECT_FALSE(contains(box["passes"], "pose_upload"));
    EXPECT_FALSE(box["memoryBytes"].contains("animation")) << box["memoryBytes"].dump();

    nlohmann::json fox = renderJson({shared("Fox/glTF-Binary/Fox.glb"), "--out", png, "--size", "16x16", "--time",
                                     "0.55", "--animation", "2", "--json"});
    EXPECT_TRUE(contains(fox["passes"], "skinning"));
    EXPECT_TRUE(fox["memoryBytes"].contains("animation"));
    auto passes = fox["passes"].get<std::vector<std::string>>();
    EXPECT_LT(std::find(passes.begin(), passes.end(), "skinning"), std::find(passes.begin(), passes.end(), "gbuffer"))
        << "skinning runs before the G-buffer";

    nlohmann::json morph =
        renderJson({shared("SimpleMorph/glTF/SimpleMorph.gltf"), "--out", png, "--size", "16x16", "--json"});
    EXPECT_TRUE(contains(morph["passes"], "skinning")) << "morph targets go through the same pass";
}

TEST_F(AnimationFrameTest, BadTimeOptionsAreCliErrors) {
    std::string out = (std::filesystem::path(IDK_BINARY_DIR) / "animation_frame_test" / "bad.png").string();
    std::string fox = shared("Fox/glTF-Binary/Fox.glb");
    EXPECT_THROW(app::runRender({fox, "--out", out, "--animation", "3"}), core::CliError);  // 3 clips: 0..2
    EXPECT_THROW(app::runRender({fox, "--out", out, "--animation", "1.5"}), core::CliError);
    EXPECT_THROW(app::runRender({fox, "--out", out, "--time", "nan"}), core::CliError);
    EXPECT_THROW(app::runRender({fox, "--out", out, "--time", "soon"}), core::CliError);
}

}  // namespace
}  // namespace idk::test
