// blend_frame_test.cpp: whole frames with BLEND materials and point shadows, and what `idk render --json` reports
// for them. Golden (display PNG, metric in support/golden.hpp): AlphaBlendModeTest at 256x256 with every texture
// streamed in. Pass lists and memory categories: the transparency pass and its "transparency" buffers exist only
// with BLEND draws, the point_shadows pass and "shadow maps" only with a shadow-casting light; `--fallback`
// renders the shadow cube face by face (six indirect calls per light instead of one).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

#include "app/commands.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/gltf_loader.hpp"
#include "support/culled_gbuffer_passes.hpp"
#include "support/golden.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

const std::string kAlphaBlend =
    std::string(IDK_SHARED_DIR) + "/scenes/AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb";
const std::string kBox = std::string(IDK_SHARED_DIR) + "/scenes/Box/glTF-Binary/Box.glb";

class BlendFrameTest : public GpuTest {};

TEST_F(BlendFrameTest, AlphaBlendModeTestMatchesGolden) {
    constexpr uint32_t kSize = 256;
    scene::Scene scene = scene::loadGltf(kAlphaBlend);
    render::Renderer renderer(ctx(), shaders());
    renderer.setScene(scene);
    render::SceneTextureStream textures(ctx(), renderer, scene);
    textures.finishSynchronously();
    render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize);
    ASSERT_EQ(frame.display.size(), size_t(kSize) * kSize * 4);
    GoldenResult g = compareWithGolden("blend_alpha_blend_mode_test", frame.display, kSize, kSize);
    EXPECT_TRUE(g.passed) << g.message;
}

nlohmann::json renderJson(const std::vector<std::string>& args) {
    ::testing::internal::CaptureStdout();
    int code = app::runRender(args);
    std::string out = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(code, 0) << out;
    return nlohmann::json::parse(out);
}

std::vector<std::string> passes(const nlohmann::json& j) { return j["passes"].get<std::vector<std::string>>(); }

class PassListTest : public GpuTest {
protected:
    std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "blend_frame_test";
    std::string out(const char* name) { return (dir / name).string(); }
};

TEST_F(PassListTest, BlendSceneWithoutLightsAddsTransparencyButNoShadows) {
    nlohmann::json j = renderJson({kAlphaBlend, "--out", out("blend.png"), "--size", "32x32", "--json"});
    EXPECT_EQ(passes(j), withCulledGBuffer({"scene_update"}, {"deferred_lighting", "sky", "transparency", "tonemap"}));
    EXPECT_EQ(j["indirectDraws"]["transparency"]["indirectCalls"], 1);
    EXPECT_TRUE(j["memoryBytes"].contains("transparency"));
    EXPECT_FALSE(j["memoryBytes"].contains("shadow maps"));
}

TEST_F(PassListTest, LitSceneWithoutBlendAddsShadowsButNoTransparency) {
    nlohmann::json j = renderJson({"--out", out("cornell.png"), "--size", "32x32", "--json"});
    // The cube's six faces are culled (one dispatch per face) and drawn face by face from their culled commands.
    EXPECT_EQ(passes(j), withCulledGBuffer({"shadow_table", "cull_reset_shadows", "cull_shadows", "cull_stats_shadows",
                                            "point_shadows"},
                                           {"deferred_lighting", "sky", "tonemap"}));
    EXPECT_EQ(j["indirectDraws"]["point_shadows"]["indirectCalls"], 6) << "one culled draw per face of the one light";
    EXPECT_TRUE(j["memoryBytes"].contains("shadow maps"));
    EXPECT_FALSE(j["memoryBytes"].contains("transparency"));
}

TEST_F(PassListTest, FallbackRungDrawsSixTimesPerLight) {
    nlohmann::json j = renderJson({"--fallback", "--out", out("cornell_fallback.png"), "--size", "32x32", "--json"});
    EXPECT_EQ(j["indirectDraws"]["point_shadows"]["indirectCalls"], 6);
}

TEST_F(PassListTest, SceneWithNeitherHasNeitherPassNorMemory) {
    nlohmann::json j = renderJson({kBox, "--out", out("box.png"), "--size", "32x32", "--json"});
    EXPECT_EQ(passes(j), withCulledGBuffer({}, {"deferred_lighting", "sky", "tonemap"}));
    EXPECT_FALSE(j["memoryBytes"].contains("shadow maps"));
    EXPECT_FALSE(j["memoryBytes"].contains("transparency"));
}

}  // namespace
}  // namespace idk::test
