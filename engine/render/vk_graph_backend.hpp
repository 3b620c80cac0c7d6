// vk_graph_backend.hpp: the render graph's GraphBackend on the engine's Vulkan device layer: memory
// requirements through maintenance4 (no object needed), aliasing heaps and dedicated allocations from the
// MemoryAllocator, images/buffers with debug names and bindless slots, deferred destruction, and per-pass
// timestamps.
#pragma once
#include <map>
#include <memory>
#include <optional>

#include "graph/graph_backend.hpp"
#include "vk/context.hpp"
#include "vk/timestamps.hpp"

namespace idk::render {

// A vk::Image as the graph's physical texture (for RenderGraph::importTexture; bindless indices left unset).
graph::PhysicalTexture physicalOf(const vk::Image& image);

class VkGraphBackend final : public graph::GraphBackend {
public:
    explicit VkGraphBackend(vk::Context& ctx);
    ~VkGraphBackend() override;

    graph::MemoryRequirements textureRequirements(const graph::TextureInfo& info) override;
    graph::MemoryRequirements bufferRequirements(const graph::BufferInfo& info) override;
    graph::HeapHandle allocateHeap(const graph::HeapDesc& desc) override;
    graph::PhysicalTexture createTexture(const graph::TextureInfo& info, std::string_view debugName,
                                         const graph::MemoryPlacement* placement) override;
    graph::PhysicalBuffer createBuffer(const graph::BufferInfo& info, std::string_view debugName,
                                       const graph::MemoryPlacement* placement) override;
    void destroyTexture(const graph::PhysicalTexture& texture) override;
    void destroyBuffer(const graph::PhysicalBuffer& buffer) override;
    void releaseHeap(graph::HeapHandle heap) override;

    void beginFrame(VkCommandBuffer cmd, uint32_t passCount) override;
    void timestampBegin(VkCommandBuffer cmd, uint32_t passIndex, std::string_view passName) override;
    void timestampEnd(VkCommandBuffer cmd, uint32_t passIndex) override;

    // GPU time of each pass of the last executed frame (call after its submission completed).
    std::vector<vk::ScopeTiming> passTimings() const { return timestamps_.read(); }

private:
    std::optional<vk::MemoryAllocation> takeDedicated(uint64_t backendData);

    vk::Context& ctx_;
    vk::TimestampQueries timestamps_;
    std::vector<uint32_t> scopes_;  // pass index -> timestamp scope
    uint64_t nextId_ = 1;
    std::map<uint64_t, vk::MemoryAllocation> heaps_;
    std::map<uint64_t, vk::MemoryAllocation> dedicated_;  // backendData -> allocation of non-aliased objects
};

}  // namespace idk::render
