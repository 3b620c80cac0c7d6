// aliasing.hpp: the transient memory plan. Given each transient's memory requirements and lifetime (first
// and last pass position in execution order), place resources whose lifetimes are disjoint at overlapping
// byte ranges of shared heaps. Pure; the greedy rule: sort by size (largest first), then put each resource
// at the lowest aligned offset that is free during its whole lifetime.
//
// Heaps are keyed by (kind, hostVisible, memoryTypeBits): images and buffers never share a heap, which
// sidesteps bufferImageGranularity (linear and optimal resources adjacent in one allocation) entirely.
#pragma once
#include "graph/graph_backend.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace idk::graph {

struct HeapKey {
    ResourceKind kind = ResourceKind::Image;
    bool hostVisible = false;
    uint32_t memoryTypeBits = 0;
    auto operator<=>(const HeapKey&) const = default;
};

struct AliasRequest {
    uint32_t resource = kInvalidId;   // caller's id (graph resource index)
    HeapKey key;                      // key.memoryTypeBits must equal requirements.memoryTypeBits
    MemoryRequirements requirements;
    uint32_t firstPass = 0;           // inclusive positions in execution order
    uint32_t lastPass = 0;
};

struct AliasedHeap {
    HeapKey key;
    VkDeviceSize size = 0;
    VkDeviceSize alignment = 1;       // the largest alignment placed in it
};

struct AliasSlot {
    uint32_t resource = kInvalidId;
    uint32_t heap = 0;                // index into AliasingPlan::heaps
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    uint32_t firstPass = 0;
    uint32_t lastPass = 0;
};

struct AliasingPlan {
    std::vector<AliasedHeap> heaps;
    std::vector<AliasSlot> slots;     // in the order of the requests

    const AliasSlot* slotOf(uint32_t resource) const noexcept;
    VkDeviceSize totalBytes() const noexcept;                 // sum of heap sizes
    VkDeviceSize unaliasedBytes() const noexcept;             // sum of slot sizes (what no aliasing would cost)
};

bool lifetimesOverlap(const AliasSlot& a, const AliasSlot& b) noexcept;
bool bytesOverlap(const AliasSlot& a, const AliasSlot& b) noexcept;

AliasingPlan planAliasing(std::span<const AliasRequest> requests);

}  // namespace idk::graph
