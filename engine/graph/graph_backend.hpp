// graph_backend.hpp: what the render graph needs from the Vulkan device layer, as one small interface.
// The graph never creates Vulkan objects itself; the engine implements this on top of engine/vk (memory,
// bindless, queries), tests implement it with fakes. All calls come from the recording thread.
#pragma once
#include "graph/graph_types.hpp"

#include <string_view>

namespace idk::graph {

struct MemoryRequirements {
    VkDeviceSize size = 0;
    VkDeviceSize alignment = 1;   // a power of two
    uint32_t memoryTypeBits = 0;
};

// An opaque memory block the backend allocated for aliased transients (e.g. a VkDeviceMemory or a range
// of the backend's own sub-allocator). 0 is "none".
struct HeapHandle {
    uint64_t value = 0;
    bool operator==(const HeapHandle&) const = default;
};

struct HeapDesc {
    VkDeviceSize size = 0;
    VkDeviceSize alignment = 1;
    uint32_t memoryTypeBits = 0;   // the heap's memory type must be one of these
    bool hostVisible = false;      // HOST_VISIBLE | HOST_COHERENT required (buffers read by the CPU)
    ResourceKind kind = ResourceKind::Image;   // heaps hold only images or only buffers (see aliasing.hpp)
};

// Where a transient lives: bind it at `offset` inside `heap`.
struct MemoryPlacement {
    HeapHandle heap;
    VkDeviceSize offset = 0;
};

class GraphBackend {
public:
    virtual ~GraphBackend() = default;

    // ---- Queries used by compile(): no side effects, no GPU work. ----
    // Maintenance4's vkGetDeviceImageMemoryRequirements / vkGetDeviceBufferMemoryRequirements answer these
    // without creating an object.
    virtual MemoryRequirements textureRequirements(const TextureInfo& info) = 0;
    virtual MemoryRequirements bufferRequirements(const BufferInfo& info) = 0;

    // ---- Physical objects, created by execute() and cached across frames by the ResourcePool. ----
    virtual HeapHandle allocateHeap(const HeapDesc& desc) = 0;
    // placement == nullptr: a dedicated allocation (persistent/history copies). Otherwise bind the new
    // object at placement->offset of placement->heap (the graph guarantees size and alignment fit).
    // The backend registers bindless slots it wants (sampled/storage per usage) and fills them in.
    virtual PhysicalTexture createTexture(const TextureInfo& info, std::string_view debugName,
                                          const MemoryPlacement* placement) = 0;
    virtual PhysicalBuffer createBuffer(const BufferInfo& info, std::string_view debugName,
                                        const MemoryPlacement* placement) = 0;
    // Releases may be called while frames that use the object are in flight: the backend must defer the
    // real destruction (and bindless slot reuse) until those frames retire. Objects placed in a heap are
    // always released before (or together with) their heap.
    virtual void destroyTexture(const PhysicalTexture& texture) = 0;
    virtual void destroyBuffer(const PhysicalBuffer& buffer) = 0;
    virtual void releaseHeap(HeapHandle heap) = 0;

    // ---- Per-frame timing hooks (optional). ----
    // beginFrame: before any pass of the frame is recorded (reset a query pool for passCount passes here).
    virtual void beginFrame(VkCommandBuffer /*cmd*/, uint32_t /*passCount*/) {}
    // Around each executed pass; passIndex counts executed passes from 0 in execution order.
    virtual void timestampBegin(VkCommandBuffer /*cmd*/, uint32_t /*passIndex*/, std::string_view /*passName*/) {}
    virtual void timestampEnd(VkCommandBuffer /*cmd*/, uint32_t /*passIndex*/) {}
};

}  // namespace idk::graph
