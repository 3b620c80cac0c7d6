// culling.hpp: the GPU culling passes (cull.cpp) and what they hand to the draws that consume them.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "graph/render_graph.hpp"
#include "shared/culling_types.h"
#include "shared/meshlet_types.h"
#include "vk/pipeline.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::passes {

struct CullInputs {
    graph::BufferHandle instances;  // GpuInstance[drawCount]
    graph::BufferHandle draws;      // GpuCullDraw[drawCount]
    graph::BufferHandle views;      // GpuCullView[]
    uint32_t view = 0;              // which of them
    uint32_t drawCount = 0;         // > 0
    uint32_t phase = gpu::kCullFrustum;
    bool meshTasks = false;          // write MeshTaskCommands (the mesh rung) instead of indexed draws
    graph::BufferHandle visibility;  // kCullEarly: read; kCullLate: rewritten (the handle's next version)
    graph::BufferHandle pyramid;     // kCullLate: the early phase's depth pyramid
};

// The compacted draws of one view, for vkCmdDrawIndexedIndirectCount (commands, count at counters offset 0,
// maxDraws as its maxDrawCount); each command's firstInstance is the instance it draws.
struct CulledDraws {
    graph::BufferHandle commands, counters;
    graph::BufferHandle visibility;  // kCullLate: the rewritten visibility version
    uint32_t maxDraws = 0;
    bool keepDepth = false;  // the G-buffer stores its depth attachment (a later pass draws over it)
    // Mesh rung: the commands are MeshTaskCommands; the task shader culls meshlets against views[view] (and in
    // the late phase against the pyramid) and adds its counts to `counters`.
    bool meshTasks = false;
    graph::BufferHandle meshlets, meshletIndices, draws, views, pyramid;
    // The meshlet visibility bits (kCullEarly reads them, kCullLate rewrites them; unused in kCullFrustum) and the
    // version the G-buffer pass used (set while that pass is declared).
    graph::BufferHandle meshletVisibility;
    std::shared_ptr<graph::BufferHandle> meshletVisibilityUsed = std::make_shared<graph::BufferHandle>();
    graph::BufferHandle drawInstance;  // uint per command: its instance (the task shader's gl_DrawID lookup)
    uint32_t view = 0, phase = gpu::kCullFrustum;
    // The task shader's GpuCullCounters (meshlet and triangle counts; zeroed by the cull pass's reset), and the
    // version the G-buffer pass wrote (set while that pass is declared).
    graph::BufferHandle meshCounters;
    std::shared_ptr<graph::BufferHandle> meshCountersWritten = std::make_shared<graph::BufferHandle>();
};

// gbuffer_mesh.cpp: the G-buffer pass's mesh rung (pipeline stages, declared buffers, the draw).
inline constexpr VkPipelineStageFlags2 kTaskMeshStages =
    VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT | VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT;
void useMeshShaders(vk::GraphicsPipelineDesc& desc);
void declareMeshDraws(graph::PassBuilder& b, const CulledDraws& c);
void recordMeshDraws(graph::PassContext& pc, vk::Context& ctx, const CulledDraws& c, const gpu::GBufferPush& gbuffer);

// Binds the culling kernel and dispatches it over push.drawCount draws (the pass below; conformance tests).
void recordCull(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, const gpu::CullPush& push);

CulledDraws addCullPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                        const CullInputs& inputs, const std::string& viewName);

// depth_pyramid.cpp: the Hi-Z pyramid (shared/depth_pyramid.h) of the R32F depth image `depth` (size pixels) into
// a new graph buffer; `name` names the pass and the buffer. recordDepthPyramid is its body (conformance tests call it on their own buffers).
// `reduction`: Farthest (max: culling; an occluder hides a box only behind all of a cell) or Closest (min: the SSR
// march; a ray in front of a cell's nearest surface passes the whole cell).
enum class HizReduction { Farthest, Closest };
void recordDepthPyramid(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t depthStorage,
                        glm::uvec2 size, VkDeviceAddress pyramid, HizReduction reduction = HizReduction::Farthest);
// depth_pyramid_minmax.cpp: the native rung of the ladder "hiz-reduction" (same pyramid, bit for bit): a bindless
// sampler with reduction MAX and one R32F image per level (hizLevelSize; usage SAMPLED | TRANSFER_DST), into which
// each level is copied for the next one to sample. The caller owns them (persistent, outside the render graph: only
// this rung's passes touch them, each copy waiting for all earlier work).
struct HizLevelImage {
    VkImage image = VK_NULL_HANDLE;
    uint32_t sampled = 0;  // bindless index
};
struct HizMinmaxResources {
    uint32_t sampler = 0;
    std::vector<HizLevelImage> levels;  // hizLevelCount(size) of them
};
graph::BufferHandle addDepthPyramidPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                        graph::TextureHandle depth, glm::uvec2 size, const std::string& name,
                                        const HizMinmaxResources* minmax = nullptr);
// The sampler rung's body: `depthSampled` is the depth image's bindless sampled index (SHADER_READ_ONLY_OPTIMAL);
// the pyramid buffer needs TRANSFER_SRC usage (the levels are copied from it).
void recordDepthPyramidMinmax(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t depthSampled,
                              const HizMinmaxResources& minmax, glm::uvec2 size, VkBuffer pyramidBuffer,
                              VkDeviceAddress pyramid);

// cull_shadows.cpp: the culled draws of `viewCount` views (inputs.view is ignored: views 0..viewCount-1 of
// inputs.views, frustum phase): view v's commands start at commandOffset(v), its count at countOffset(v).
struct ShadowCulledDraws {
    graph::BufferHandle commands, counters;
    uint32_t maxDraws = 0, viewCount = 0;
    VkDeviceSize commandOffset(uint32_t v) const {
        return VkDeviceSize(v) * maxDraws * sizeof(VkDrawIndexedIndirectCommand);
    }
    VkDeviceSize countOffset(uint32_t v) const { return VkDeviceSize(v) * sizeof(gpu::GpuCullCounters); }
};
ShadowCulledDraws addShadowCullPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    const CullInputs& inputs, uint32_t viewCount);

// One view's counters as read back after the frame (GpuCullCounters).
struct CullingViewStats {
    std::string view;  // "camera"
    uint32_t instancesTested = 0, instancesDrawn = 0, trianglesDrawn = 0;
    bool meshlets = false;  // mesh rung: the task shader culled meshlets and counted these
    uint32_t meshletsTested = 0, meshletsDrawn = 0;
};

// Copies GpuCullCounters buffers into a host-visible buffer, counters[i] at element i (read after the frame's fence).
void addCullStatsCopyPass(graph::RenderGraph& graph, const std::vector<graph::BufferHandle>& counters,
                          graph::BufferHandle hostBuffer);

}  // namespace idk::passes
