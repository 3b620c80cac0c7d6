// render_stats_test.cpp: `idk render --json` (app::runRender) lists exactly the passes the scene needs. Box has no
// lights and no BLEND material: no shadow pass, no transparency pass; PNG output adds tonemap, EXR output does
// not (the G-buffer is the default --culling hiz passes); the GPU memory categories follow the scene (no light buffer without lights).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

#include "app/commands.hpp"
#include "support/culled_gbuffer_passes.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

nlohmann::json renderJson(const std::vector<std::string>& args) {
    ::testing::internal::CaptureStdout();
    int code = app::runRender(args);
    std::string out = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(code, 0) << out;
    return nlohmann::json::parse(out);
}

class RenderStatsTest : public GpuTest {
protected:
    std::string box = std::string(IDK_SHARED_DIR) + "/scenes/Box/glTF-Binary/Box.glb";
    std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "render_stats_test";
};

TEST_F(RenderStatsTest, PngFrameOfASceneWithoutLightsOrBlendRunsExactlyTheDeferredPasses) {
    nlohmann::json j = renderJson({box, "--out", (dir / "box.png").string(), "--size", "32x32", "--json"});
    EXPECT_EQ(j["passes"].get<std::vector<std::string>>(),
              withCulledGBuffer({}, {"deferred_lighting", "sky", "tonemap"}));
    EXPECT_EQ(j["indirectDraws"]["gbuffer"]["indirectCalls"], 1);
    EXPECT_EQ(j["indirectDraws"]["gbuffer"]["draws"], 1);
    const nlohmann::json& memory = j["memoryBytes"];
    for (const char* category : {"geometry", "instances", "materials", "textures", "environment", "render targets"})
        EXPECT_TRUE(memory.contains(category)) << category << " missing in " << memory.dump();
    EXPECT_FALSE(memory.contains("lights")) << "no light buffer without lights";
    EXPECT_TRUE(std::filesystem::exists(dir / "box.png"));
}

TEST_F(RenderStatsTest, ExrFrameSkipsTheTonemapPass) {
    nlohmann::json j = renderJson({box, "--out", (dir / "box.exr").string(), "--size", "32x32", "--json"});
    EXPECT_EQ(j["passes"].get<std::vector<std::string>>(),
              withCulledGBuffer({}, {"deferred_lighting", "sky"}));
}

TEST_F(RenderStatsTest, LambertShadingIsStillAvailable) {
    nlohmann::json j =
        renderJson({"--shading", "lambert", "--out", (dir / "lambert.png").string(), "--size", "16x16", "--json"});
    EXPECT_EQ(j["passes"].get<std::vector<std::string>>(), std::vector<std::string>{"lambert"});
}

TEST_F(RenderStatsTest, SceneWithLightsHasALightBuffer) {
    nlohmann::json j = renderJson({"--out", (dir / "cornell.png").string(), "--size", "16x16", "--json"});
    EXPECT_TRUE(j["memoryBytes"].contains("lights"));
}

}  // namespace
}  // namespace idk::test
