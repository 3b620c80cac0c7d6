// render_graph.hpp: declare -> compile -> execute. Passes declare what they read and write through typed,
// versioned handles; compile() (pure, no GPU) validates, culls, orders, plans every barrier and layout
// transition and the transient memory aliasing; execute() realizes physical resources through the
// backend and records labels, timestamps, barriers and the passes' callbacks. Passes hold no barriers.
//
// Typical frame:
//   RenderGraph graph(pool, {width, height});
//   TextureHandle color;
//   graph.addPass("gbuffer", [&](PassBuilder& b) {
//       color = b.write(b.create("color", TextureDesc{.format = VK_FORMAT_R16G16B16A16_SFLOAT}), Access::ColorWrite);
//   }, [&](PassContext& ctx) { /* vkCmdBeginRendering with ctx.view(color) ... */ });
//   graph.compile();            // throws GraphError on a malformed graph
//   graph.execute(cmd);
#pragma once
#include "graph/graph_nodes.hpp"
#include "graph/resource_pool.hpp"

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace idk::graph {

class RenderGraph;

// Given to a pass's setup callback: declares the pass's resources and accesses.
class PassBuilder {
public:
    TextureHandle create(std::string_view name, const TextureDesc& desc);
    BufferHandle create(std::string_view name, const BufferDesc& desc);
    // stages NONE: the Access table's default stages. read() returns the same handle; write() returns the
    // next version, which later readers must use. One access per resource per pass.
    TextureHandle read(TextureHandle texture, Access access, VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE);
    TextureHandle write(TextureHandle texture, Access access, VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE);
    BufferHandle read(BufferHandle buffer, Access access, VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE);
    BufferHandle write(BufferHandle buffer, Access access, VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE);
    TextureHandle history(std::string_view persistentName);        // = RenderGraph::history
    BufferHandle historyBuffer(std::string_view persistentName);
    void sideEffect();                              // never culled (readback, debug output, timing)
    void after(std::string_view passName);          // run after that pass if it runs (pure ordering edge)

private:
    friend class RenderGraph;
    PassBuilder(RenderGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
    RenderGraph& graph_;
    uint32_t pass_;
};

// Given to a pass's exec callback: the command buffer and the physical objects behind declared handles.
class PassContext {
public:
    VkCommandBuffer commandBuffer() const noexcept { return cmd_; }
    std::string_view passName() const noexcept;
    // Throw GraphError when the pass did not declare the resource (a missing declaration = a missing barrier).
    const PhysicalTexture& texture(TextureHandle handle) const;
    const PhysicalBuffer& buffer(BufferHandle handle) const;
    VkImage image(TextureHandle handle) const { return texture(handle).image; }
    VkImageView view(TextureHandle handle) const { return texture(handle).view; }
    VkBuffer vkBuffer(BufferHandle handle) const { return buffer(handle).buffer; }
    // False on frames where last frame's copy did not exist or was not written: it was cleared to zero.
    bool historyValid(TextureHandle handle) const;
    bool historyValid(BufferHandle handle) const;
    VkExtent2D outputExtent() const noexcept;

private:
    friend class RenderGraph;
    PassContext(const RenderGraph& graph, uint32_t pass, VkCommandBuffer cmd) : graph_(graph), pass_(pass), cmd_(cmd) {}
    uint32_t checkDeclared(uint32_t resource, ResourceKind kind) const;
    const RenderGraph& graph_;
    uint32_t pass_;
    VkCommandBuffer cmd_;
};

class RenderGraph {
public:
    RenderGraph(ResourcePool& pool, VkExtent2D outputExtent);
    RenderGraph(const RenderGraph&) = delete;
    RenderGraph& operator=(const RenderGraph&) = delete;

    // ---- Declaration. Misuse is recorded and reported by compile(), with the pass and resource named. ----
    void addPass(std::string_view name, const std::function<void(PassBuilder&)>& setup,
                 std::function<void(PassContext&)> exec);
    TextureHandle createTexture(std::string_view name, const TextureDesc& desc);
    BufferHandle createBuffer(std::string_view name, const BufferDesc& desc);
    // `current`: the resource's state now (e.g. stateAfterAccess(...), or {.layout = UNDEFINED,
    // .writeStages = COLOR_ATTACHMENT_OUTPUT} for a just-acquired swapchain image whose acquire semaphore is
    // waited on at that stage). `finalUse`: where the graph leaves it after the last pass.
    TextureHandle importTexture(std::string_view name, const PhysicalTexture& texture, const ResourceState& current,
                                std::optional<FinalUse> finalUse = std::nullopt);
    BufferHandle importBuffer(std::string_view name, const PhysicalBuffer& buffer, const ResourceState& current,
                              std::optional<FinalUse> finalUse = std::nullopt);
    // Last frame's version of the persistent resource `persistentName` (created with desc.persistent this
    // frame or kept from an earlier frame). Read-only. When last frame did not write it (first frame,
    // resize, ...) it reads as all zeros: the graph clears it before the first pass.
    TextureHandle history(std::string_view persistentName);
    BufferHandle historyBuffer(std::string_view persistentName);
    // Keeps the pass that wrote this version (and everything it needs) alive.
    void markOutput(TextureHandle texture);
    void markOutput(BufferHandle buffer);

    // ---- Compile: pure (queries the backend's memory requirements only). Throws GraphError. ----
    void compile();
    // ---- Execute: compiles first if needed; records into cmd; commits persistent state to the pool. ----
    void execute(VkCommandBuffer cmd);

    // ---- Inspection (after compile). ----
    std::vector<std::string> executionOrder() const;
    bool isCulled(std::string_view passName) const;
    std::span<const PlannedBarrier> barriersBefore(std::string_view passName) const;
    std::span<const PlannedBarrier> prologueBarriers() const;   // fresh history copies -> TRANSFER_DST
    std::span<const PlannedBarrier> finalBarriers() const;      // imported resources -> FinalUse
    const AliasingPlan& aliasingPlan() const;
    const AliasSlot* aliasSlot(TextureHandle texture) const;    // nullptr: not an aliased transient
    const AliasSlot* aliasSlot(BufferHandle buffer) const;
    ResourceState finalState(TextureHandle texture) const;      // e.g. to import it again next frame
    ResourceState finalState(BufferHandle buffer) const;
    const TextureInfo& textureInfo(TextureHandle texture) const;
    const BufferInfo& bufferInfo(BufferHandle buffer) const;
    bool historyValid(uint32_t resource) const;
    std::string_view resourceName(uint32_t resource) const;
    VkExtent2D outputExtent() const noexcept { return outputExtent_; }
    // OutputRelative textures created, and passes added, after this call are sized relative to `extent` instead of
    // the output extent (PassContext::outputExtent() returns it): a temporal upscaler renders the frame up to its
    // resolve at a lower resolution, then sets the output extent back. Defaults to the output extent.
    void setRelativeExtent(VkExtent2D extent);
    VkExtent2D relativeExtent() const noexcept { return relativeExtent_; }
    std::string toText() const;       // passes in order, culled passes, barriers, resources, memory plan
    std::string toGraphviz() const;   // dot: passes (culled ones grey), resource versions, edges

private:
    friend class PassBuilder;
    friend class PassContext;

    uint32_t addResource(detail::ResourceNode node, uint32_t pass);
    uint32_t historyResource(std::string_view persistentName, ResourceKind kind);
    uint32_t declareUse(uint32_t pass, ResourceKind kind, uint32_t resource, uint32_t version, Access access,
                        VkPipelineStageFlags2 stages, bool write);
    void markOutputVersion(ResourceKind kind, uint32_t resource, uint32_t version);
    void error(std::string message);
    std::string passLabel(uint32_t pass) const;
    const detail::CompiledGraph& compiled() const;
    uint32_t passIndex(std::string_view name) const;
    uint32_t checkedResource(uint32_t resource, ResourceKind kind, const char* what) const;

    // compile() steps (graph_compile.cpp, graph_plan.cpp).
    void validatePasses(std::vector<std::string>& errors, std::vector<std::vector<uint32_t>>& afterEdges);
    void resolveHistory(std::vector<std::string>& errors);
    std::vector<bool> findLivePasses() const;
    void orderPasses(const std::vector<bool>& alive, const std::vector<std::vector<uint32_t>>& afterEdges,
                     std::vector<std::string>& errors);
    void resolveResources(std::vector<std::string>& errors);
    void planMemory();
    void planBarriers();
    std::string describeCycle(const std::vector<uint32_t>& remaining) const;

    // execute() steps (graph_execute.cpp).
    void realizeResources();
    void recordBarriers(VkCommandBuffer cmd, std::span<const PlannedBarrier> barriers) const;
    void recordHistoryClears(VkCommandBuffer cmd) const;
    void commitToPool();

    ResourcePool& pool_;
    VkExtent2D outputExtent_;
    VkExtent2D relativeExtent_;
    std::vector<detail::ResourceNode> resources_;
    std::vector<detail::PassNode> passes_;
    std::vector<std::string> errors_;
    std::optional<detail::CompiledGraph> compiled_;
    bool executed_ = false;
    std::vector<PhysicalTexture> physicalTextures_;   // per resource, filled by execute()
    std::vector<PhysicalBuffer> physicalBuffers_;
};

}  // namespace idk::graph
