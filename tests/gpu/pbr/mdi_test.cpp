// mdi_test.cpp: the G-buffer is ONE multi-draw-indirect: a hook on volk's vkCmdDrawIndexedIndirect(Count) (and the
// direct draw entry points) counts what the frame really records, and the draw count (maxDrawCount) must equal the
// number of (instance, primitive) pairs of the scene, including EXT_mesh_gpu_instancing copies; the only direct draw
// is the tonemap's fullscreen triangle, and no pass records a plain vkCmdDrawIndexedIndirect (every uncounted draw
// goes through passes/indirect_draw.hpp: lavapipe applies an earlier count draw's count to plain ones). Also checks
// the packed draw commands against the mesh ranges and the renderer's own per-pass log.
#include <gtest/gtest.h>

#include <algorithm>

#include "app/default_scene.hpp"
#include "render/gpu_scene.hpp"
#include "render/renderer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

struct DrawCounts {
    uint32_t indexedIndirectCalls = 0, indexedIndirectDraws = 0, plainIndirectCalls = 0, directDraws = 0;
};
DrawCounts gCounts;
PFN_vkCmdDrawIndexedIndirect gIndexedIndirect = nullptr;
PFN_vkCmdDrawIndexedIndirectCount gIndexedIndirectCount = nullptr;
PFN_vkCmdDrawIndexed gIndexed = nullptr;
PFN_vkCmdDraw gDraw = nullptr;

void VKAPI_CALL countIndexedIndirect(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset, uint32_t drawCount,
                                     uint32_t stride) {
    ++gCounts.indexedIndirectCalls;
    ++gCounts.plainIndirectCalls;
    gCounts.indexedIndirectDraws += drawCount;
    gIndexedIndirect(cmd, buffer, offset, drawCount, stride);
}
void VKAPI_CALL countIndexedIndirectCount(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset,
                                          VkBuffer countBuffer, VkDeviceSize countOffset, uint32_t maxDrawCount,
                                          uint32_t stride) {
    ++gCounts.indexedIndirectCalls;
    gCounts.indexedIndirectDraws += maxDrawCount;
    gIndexedIndirectCount(cmd, buffer, offset, countBuffer, countOffset, maxDrawCount, stride);
}
void VKAPI_CALL countIndexed(VkCommandBuffer cmd, uint32_t a, uint32_t b, uint32_t c, int32_t d, uint32_t e) {
    ++gCounts.directDraws;
    gIndexed(cmd, a, b, c, d, e);
}
void VKAPI_CALL countDraw(VkCommandBuffer cmd, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    ++gCounts.directDraws;
    gDraw(cmd, a, b, c, d);
}

// Swaps volk's global entry points for the counters while alive.
struct DrawHook {
    DrawHook() {
        gCounts = {};
        gIndexedIndirect = std::exchange(vkCmdDrawIndexedIndirect, &countIndexedIndirect);
        gIndexedIndirectCount = std::exchange(vkCmdDrawIndexedIndirectCount, &countIndexedIndirectCount);
        gIndexed = std::exchange(vkCmdDrawIndexed, &countIndexed);
        gDraw = std::exchange(vkCmdDraw, &countDraw);
    }
    ~DrawHook() {
        vkCmdDrawIndexedIndirect = gIndexedIndirect;
        vkCmdDrawIndexedIndirectCount = gIndexedIndirectCount;
        vkCmdDrawIndexed = gIndexed;
        vkCmdDraw = gDraw;
    }
};

uint32_t instancePrimitivePairs(const scene::Scene& s) {
    uint32_t pairs = 0;
    for (const scene::Instance& i : s.instances)
        for (const scene::Primitive& p : s.meshes[i.mesh].primitives) pairs += !p.indices.empty();
    return pairs;
}

class MdiTest : public GpuTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(MdiTest, GBufferIsOneIndirectDrawWithOneDrawPerInstancePrimitive) {
    std::string name = GetParam();
    scene::Scene scene =
        name == "cornell" ? app::loadDefaultScene() : scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + name);
    const uint32_t pairs = instancePrimitivePairs(scene);
    ASSERT_GT(pairs, 0u);

    render::Renderer renderer(ctx(), shaders());
    // The unculled G-buffer is this test's subject (culling's count-driven and mesh-shader draws are
    // tests/gpu/culling's); hiz is the default.
    renderer.settings().culling.mode = frame::CullingMode::Off;
    renderer.setScene(scene);
    render::FrameResult frame;
    DrawCounts counts;
    {
        DrawHook hook;
        frame = renderer.renderOffscreen(scene::defaultCamera(scene), 32, 32);
        counts = gCounts;
    }
    // Every indirect call is in the renderer's log (point_shadows and transparency add theirs), the G-buffer's is
    // exactly one over every pair.
    uint32_t loggedCalls = 0, loggedDraws = 0;
    for (const auto& e : frame.indirectDraws) {
        loggedCalls += e.calls;
        loggedDraws += e.draws;
    }
    EXPECT_EQ(counts.indexedIndirectCalls, loggedCalls) << name;
    EXPECT_EQ(counts.indexedIndirectDraws, loggedDraws) << name;
    EXPECT_EQ(counts.plainIndirectCalls, 0u) << name << ": a plain indirect draw bypassed passes/indirect_draw.hpp";
    EXPECT_EQ(counts.directDraws, 1u) << name << ": the tonemap's fullscreen triangle, no scene geometry";
    auto gbuffer = std::find_if(frame.indirectDraws.begin(), frame.indirectDraws.end(),
                                [](const auto& e) { return e.pass == "gbuffer"; });
    ASSERT_NE(gbuffer, frame.indirectDraws.end());
    EXPECT_EQ(gbuffer->calls, 1u);
    EXPECT_EQ(gbuffer->draws, pairs);
    EXPECT_NE(frame.graphText.find("'scene draw commands' v0 IndirectRead"), std::string::npos);

    // Each packed draw covers exactly its instance's mesh range.
    render::GpuSceneData data = render::packGpuScene(scene, {});
    ASSERT_EQ(data.draws.size(), pairs);
    ASSERT_EQ(data.instances.size(), pairs);
    for (size_t i = 0; i < data.draws.size(); ++i) {
        const gpu::GpuMesh& mesh = data.meshes[data.instances[i].mesh];
        EXPECT_EQ(data.draws[i].firstIndex, mesh.firstIndex);
        EXPECT_EQ(data.draws[i].indexCount, mesh.indexCount);
        EXPECT_EQ(data.draws[i].vertexOffset, mesh.baseVertex);
        const bool blend = data.materials[mesh.material].alphaMode == gpu::kAlphaBlend;
        EXPECT_EQ(data.draws[i].instanceCount, blend ? 0u : 1u) << "BLEND draws belong to the transparency pass";
        EXPECT_LT(mesh.material, data.materials.size());
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, MdiTest,
                         ::testing::Values("cornell", "Box/glTF-Binary/Box.glb",
                                           "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb",
                                           "SimpleInstancing/glTF-Binary/SimpleInstancing.glb",
                                           "AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                             std::string n = info.param;
                             n = n.substr(0, n.find('/'));
                             return n;
                         });

}  // namespace
}  // namespace idk::test
