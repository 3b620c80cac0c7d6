// aliasing.cpp: greedy interval packing of transient resources into shared heaps (see the header).
#include "graph/aliasing.hpp"

#include <algorithm>
#include <map>
#include <numeric>

namespace idk::graph {
namespace {

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) noexcept {
    if (alignment <= 1) return value;
    return (value + alignment - 1) / alignment * alignment;
}

}  // namespace

const AliasSlot* AliasingPlan::slotOf(uint32_t resource) const noexcept {
    for (const AliasSlot& slot : slots) {
        if (slot.resource == resource) return &slot;
    }
    return nullptr;
}

VkDeviceSize AliasingPlan::totalBytes() const noexcept {
    VkDeviceSize total = 0;
    for (const AliasedHeap& heap : heaps) total += heap.size;
    return total;
}

VkDeviceSize AliasingPlan::unaliasedBytes() const noexcept {
    VkDeviceSize total = 0;
    for (const AliasSlot& slot : slots) total += slot.size;
    return total;
}

bool lifetimesOverlap(const AliasSlot& a, const AliasSlot& b) noexcept {
    return a.firstPass <= b.lastPass && b.firstPass <= a.lastPass;
}

bool bytesOverlap(const AliasSlot& a, const AliasSlot& b) noexcept {
    return a.heap == b.heap && a.offset < b.offset + b.size && b.offset < a.offset + a.size;
}

AliasingPlan planAliasing(std::span<const AliasRequest> requests) {
    AliasingPlan plan;
    plan.slots.resize(requests.size());

    // Heaps in order of first appearance of their key, so plans are deterministic.
    std::map<HeapKey, uint32_t> heapOf;
    for (const AliasRequest& r : requests) {
        if (heapOf.emplace(r.key, static_cast<uint32_t>(plan.heaps.size())).second) {
            plan.heaps.push_back(AliasedHeap{r.key, 0, 1});
        }
    }

    // Largest first; ties by first use, then request order (stable, deterministic).
    std::vector<size_t> order(requests.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        if (requests[a].requirements.size != requests[b].requirements.size) {
            return requests[a].requirements.size > requests[b].requirements.size;
        }
        return requests[a].firstPass < requests[b].firstPass;
    });

    std::vector<std::vector<size_t>> placedInHeap(plan.heaps.size());
    std::vector<const AliasSlot*> conflicts;
    for (size_t index : order) {
        const AliasRequest& r = requests[index];
        AliasSlot& slot = plan.slots[index];
        slot.resource = r.resource;
        slot.heap = heapOf.at(r.key);
        slot.size = std::max<VkDeviceSize>(r.requirements.size, 1);
        slot.firstPass = r.firstPass;
        slot.lastPass = std::max(r.firstPass, r.lastPass);
        const VkDeviceSize alignment = std::max<VkDeviceSize>(r.requirements.alignment, 1);

        // Everything already placed in this heap whose lifetime overlaps ours, by offset.
        conflicts.clear();
        for (size_t other : placedInHeap[slot.heap]) {
            if (lifetimesOverlap(slot, plan.slots[other])) conflicts.push_back(&plan.slots[other]);
        }
        std::sort(conflicts.begin(), conflicts.end(),
                  [](const AliasSlot* a, const AliasSlot* b) { return a->offset < b->offset; });

        // Lowest gap: walk the conflicts by start offset; skip those ending before the candidate; the first
        // one starting after candidate + size proves the gap (all later ones start even later).
        VkDeviceSize candidate = 0;
        for (const AliasSlot* c : conflicts) {
            if (c->offset + c->size <= candidate) continue;
            if (c->offset >= candidate + slot.size) break;
            candidate = alignUp(c->offset + c->size, alignment);
        }
        slot.offset = candidate;
        placedInHeap[slot.heap].push_back(index);

        AliasedHeap& heap = plan.heaps[slot.heap];
        heap.size = std::max(heap.size, slot.offset + slot.size);
        heap.alignment = std::max(heap.alignment, alignment);
    }
    return plan;
}

}  // namespace idk::graph
