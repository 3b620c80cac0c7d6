// resource_pool.hpp: what outlives one frame's RenderGraph. The graph is rebuilt every frame; the pool keeps
// the physical objects it realized (aliasing heaps, transient images/buffers placed in them keyed by
// (description, heap, offset)), the two ping-pong copies of every persistent resource with their
// synchronization state, and the last accesses to each heap, so the next frame's barriers can wait on
// them. Objects unused for kUnusedFramesBeforeRelease executed frames go back to the backend.
#pragma once
#include "graph/aliasing.hpp"
#include "graph/barrier_planner.hpp"
#include "graph/graph_backend.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace idk::graph {

class RenderGraph;

class ResourcePool {
public:
    static constexpr uint64_t kUnusedFramesBeforeRelease = 4;

    explicit ResourcePool(GraphBackend& backend);   // the backend must outlive the pool
    ~ResourcePool();   // releases everything through the backend
    ResourcePool(const ResourcePool&) = delete;
    ResourcePool& operator=(const ResourcePool&) = delete;

    GraphBackend& backend() noexcept { return backend_; }
    uint64_t frameIndex() const noexcept { return frameIndex_; }   // frames executed so far
    void releaseAll();   // everything back to the backend; history restarts as "never written"

    struct Stats {
        uint32_t heaps = 0;
        VkDeviceSize heapBytes = 0;
        uint32_t transientTextures = 0;
        uint32_t transientBuffers = 0;
        uint32_t persistentResources = 0;   // each holds two copies
    };
    Stats stats() const noexcept;

private:
    friend class RenderGraph;

    struct PersistentEntry {
        std::string name;
        ResourceKind kind = ResourceKind::Image;
        TextureInfo texture;
        BufferInfo buffer;
        std::array<PhysicalTexture, 2> textures{};
        std::array<PhysicalBuffer, 2> buffers{};
        std::array<ResourceState, 2> states{};
        std::array<int64_t, 2> writtenFrame{-1, -1};   // frame index of the last write to each copy
        uint64_t lastUsedFrame = 0;
    };
    struct HeapEntry {
        HeapKey key;
        HeapDesc desc;
        HeapHandle handle;
        ResourceState tail;   // union of the last accesses of everything that lived in it
        uint64_t lastUsedFrame = 0;
    };
    struct CachedTexture {
        TextureInfo info;
        HeapHandle heap;
        VkDeviceSize offset = 0;
        PhysicalTexture physical;
        uint64_t lastUsedFrame = 0;
    };
    struct CachedBuffer {
        BufferInfo info;
        HeapHandle heap;
        VkDeviceSize offset = 0;
        PhysicalBuffer physical;
        uint64_t lastUsedFrame = 0;
    };

    // Copy index written this frame; the other one holds last frame's version (the history).
    uint32_t currentCopy() const noexcept { return static_cast<uint32_t>(frameIndex_ % 2); }

    // Compile-time reads (no side effects).
    const PersistentEntry* findPersistent(std::string_view name) const noexcept;
    ResourceState heapTail(const HeapKey& key) const noexcept;
    // The tail a heap of at least `size` will have: unknown history when acquireHeap must allocate it (new or
    // grown memory may reuse what freed resources used; see planBarriers).
    ResourceState heapTail(const HeapKey& key, VkDeviceSize size, VkDeviceSize alignment) const noexcept;

    // Execute-time realization (creates through the backend when missing).
    HeapHandle acquireHeap(const HeapKey& key, VkDeviceSize size, VkDeviceSize alignment);
    PhysicalTexture acquireTexture(const TextureInfo& info, std::string_view name, HeapHandle heap,
                                   VkDeviceSize offset);
    PhysicalBuffer acquireBuffer(const BufferInfo& info, std::string_view name, HeapHandle heap, VkDeviceSize offset);
    // Creates (or recreates, dropping history) both copies when the entry is missing or incompatible.
    PersistentEntry& acquirePersistent(std::string_view name, ResourceKind kind, const TextureInfo& texture,
                                       const BufferInfo& buffer);
    void setHeapTail(const HeapKey& key, const ResourceState& tail);
    void endFrame();   // releases objects unused for too long, advances the frame index

    void destroyEntry(PersistentEntry& entry);
    void releaseHeapAndContents(size_t heapIndex);

    GraphBackend& backend_;
    uint64_t frameIndex_ = 0;
    std::vector<HeapEntry> heaps_;
    std::vector<CachedTexture> textures_;
    std::vector<CachedBuffer> buffers_;
    std::vector<PersistentEntry> persistent_;
};

// A persistent entry can be reused for `kind` + `info` when everything matches except usage, and the wanted
// usage is a subset of what it was created with. Otherwise it is recreated and its history is lost.
bool persistentCompatible(ResourceKind kind, const TextureInfo& haveTexture, const BufferInfo& haveBuffer,
                          const TextureInfo& wantTexture, const BufferInfo& wantBuffer) noexcept;

}  // namespace idk::graph
