// barrier_planner.cpp: RAW / WAR / WAW / read-after-read / layout-transition rules (see the header).
#include "graph/barrier_planner.hpp"

namespace idk::graph {
namespace {

constexpr int trackedIndex(VkAccessFlags2 bit) noexcept {
    for (size_t i = 0; i < kTrackedReadAccessBits.size(); ++i) {
        if (kTrackedReadAccessBits[i] == bit) return static_cast<int>(i);
    }
    return -1;
}

bool covers(VkPipelineStageFlags2 visible, VkPipelineStageFlags2 needed) noexcept {
    if (visible & VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT) return true;
    return (visible & needed) == needed;
}

// True when the last write is already visible to every (stage, read access) pair of this read.
bool readIsCovered(const ResourceState& s, VkPipelineStageFlags2 stages, VkAccessFlags2 reads) noexcept {
    if (s.writeStages == VK_PIPELINE_STAGE_2_NONE && s.unflushedWrites == VK_ACCESS_2_NONE) return true;  // nothing to see
    if (s.unflushedWrites != VK_ACCESS_2_NONE) return false;
    while (reads != 0) {
        const VkAccessFlags2 bit = reads & (~reads + 1);   // lowest set bit
        reads &= ~bit;
        const int index = trackedIndex(bit);
        if (index < 0 || !covers(s.visibleStages[static_cast<size_t>(index)], stages)) return false;
    }
    return true;
}

void markVisible(ResourceState& s, VkPipelineStageFlags2 stages, VkAccessFlags2 reads) noexcept {
    while (reads != 0) {
        const VkAccessFlags2 bit = reads & (~reads + 1);
        reads &= ~bit;
        const int index = trackedIndex(bit);
        if (index >= 0) s.visibleStages[static_cast<size_t>(index)] |= stages;
    }
}

// State right after a write at `stages` with `access`: only this write matters from now on.
ResourceState afterWrite(VkImageLayout layout, VkPipelineStageFlags2 stages, VkAccessFlags2 access) noexcept {
    ResourceState s;
    s.layout = layout;
    s.writeStages = stages;
    s.unflushedWrites = access & kWriteAccessMask;
    s.lastWriteAccess = s.unflushedWrites;
    return s;
}

}  // namespace

VkPipelineStageFlags2 effectiveStages(const Use& use) noexcept {
    if (use.stages != VK_PIPELINE_STAGE_2_NONE) return use.stages;
    return accessInfo(use.access, use.kind).defaultStages;
}

Transition applyUse(const ResourceState& previous, const Use& next) noexcept {
    const AccessInfo info = accessInfo(next.access, next.kind);
    if (!info.valid) return {std::nullopt, previous};

    const VkPipelineStageFlags2 stages = effectiveStages(next);
    const VkAccessFlags2 access = info.access;
    const VkAccessFlags2 reads = access & ~kWriteAccessMask;
    const bool isImage = next.kind == ResourceKind::Image;
    const VkPipelineStageFlags2 earlierStages = previous.writeStages | previous.readStages;

    PlannedBarrier b;
    b.kind = next.kind;
    b.dstStages = stages;
    b.aliasing = previous.aliasedMemory;
    if (isImage) b.oldLayout = b.newLayout = previous.layout;

    // Rule 1: layout transitions always need a barrier.
    // SYNC: a layout transition reads and writes every texel, so it is ordered after ALL earlier accesses
    // (last write: RAW/WAW, every reader since: WAR) and makes unflushed writes available first. It is
    // itself made visible to the destination scope, so the first access after it needs nothing more.
    if (isImage && (next.discard || previous.layout != info.layout)) {
        b.srcStages = earlierStages;
        // SYNC: an earlier barrier may already have made the last write available (write -> barrier -> read ->
        // transition). The spec needs nothing more then (the execution dependency chains through the read), but
        // the synchronization validation layer (1.3.239) reports WRITE_AFTER_WRITE for a transition whose source
        // access scope misses the last write, so the write's access is repeated: a redundant availability operation.
        b.srcAccess = previous.unflushedWrites | previous.lastWriteAccess;
        b.dstAccess = access;
        // SYNC: UNDEFINED as old layout lets the driver drop the contents (first use of a transient, memory
        // that belonged to another resource, a persistent copy about to be overwritten).
        b.oldLayout = next.discard ? VK_IMAGE_LAYOUT_UNDEFINED : previous.layout;
        b.newLayout = info.layout;
        ResourceState after;
        if (info.isWrite) {
            after = afterWrite(info.layout, stages, access);
        } else {
            after.layout = info.layout;
            after.writeStages = stages;   // the transition is the last write; later readers chain on `stages`
            after.readStages = stages;
            markVisible(after, stages, reads);
            // SYNC: a transition with no destination stage (Present) cannot be chained on; anything after it
            // (only possible once the image is re-acquired) must wait on everything.
            if (stages == VK_PIPELINE_STAGE_2_NONE) after.writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        }
        return {b, after};
    }

    // Rule 2: write after anything (WAW and/or WAR).
    if (info.isWrite) {
        const ResourceState after = afterWrite(previous.layout, stages, access);
        if (earlierStages == VK_PIPELINE_STAGE_2_NONE && previous.unflushedWrites == VK_ACCESS_2_NONE) {
            return {std::nullopt, after};   // nothing happened before (fresh buffer): no hazard
        }
        b.srcStages = earlierStages != VK_PIPELINE_STAGE_2_NONE ? earlierStages : VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.srcAccess = previous.unflushedWrites;
        // SYNC: WAR needs only an execution dependency (a read leaves nothing in caches to flush). WAW also
        // needs a memory dependency: the earlier write available (srcAccess, if not done yet) and the new
        // write's access in the destination scope, so the two writes land in order.
        b.dstAccess = previous.writeStages != VK_PIPELINE_STAGE_2_NONE ? access : VK_ACCESS_2_NONE;
        return {b, after};
    }

    // Rule 3: read. RAW when the last write is not visible to this read yet; otherwise read-after-read.
    ResourceState after = previous;
    after.aliasedMemory = false;
    after.readStages |= stages;
    if (readIsCovered(previous, stages, reads)) {
        return {std::nullopt, after};
    }
    b.srcStages = previous.writeStages != VK_PIPELINE_STAGE_2_NONE ? previous.writeStages
                                                                   : VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    // SYNC: when an earlier barrier already made the write available, it did so for other destination stages;
    // this barrier does not chain on that one (its source scope is the write's stages, not those), so the write's
    // availability is repeated here to sit in one dependency chain with this visibility operation (a transfer read
    // of a buffer that a transfer wrote and a vertex shader read since, for example).
    b.srcAccess = previous.unflushedWrites | previous.lastWriteAccess;
    b.dstAccess = access;
    after.unflushedWrites = VK_ACCESS_2_NONE;
    markVisible(after, stages, reads);
    return {b, after};
}

std::optional<PlannedBarrier> planBarrier(const ResourceState& previous, const Use& next) noexcept {
    return applyUse(previous, next).barrier;
}

ResourceState stateAfterAccess(Access access, ResourceKind kind, VkPipelineStageFlags2 stages) noexcept {
    const AccessInfo info = accessInfo(access, kind);
    if (!info.valid) return {};
    if (stages == VK_PIPELINE_STAGE_2_NONE) stages = info.defaultStages;
    if (info.isWrite) return afterWrite(info.layout, stages, info.access);
    ResourceState s;
    s.layout = info.layout;
    s.readStages = stages;
    return s;
}

ResourceState unknownHistoryState() noexcept {
    ResourceState s;
    s.writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    s.lastWriteAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
    return s;
}

bool isUnknownHistory(const ResourceState& s) noexcept {
    return s.layout == VK_IMAGE_LAYOUT_UNDEFINED && s.writeStages == VK_PIPELINE_STAGE_2_NONE &&
           s.readStages == VK_PIPELINE_STAGE_2_NONE && s.unflushedWrites == VK_ACCESS_2_NONE &&
           s.lastWriteAccess == VK_ACCESS_2_NONE;
}

ResourceState mergeForAliasing(const ResourceState& a, const ResourceState& b) noexcept {
    ResourceState s;
    s.writeStages = a.writeStages | b.writeStages;
    s.readStages = a.readStages | b.readStages;
    s.unflushedWrites = a.unflushedWrites | b.unflushedWrites;
    s.lastWriteAccess = a.lastWriteAccess | b.lastWriteAccess;
    s.aliasedMemory = a.aliasedMemory || b.aliasedMemory || s.writeStages != VK_PIPELINE_STAGE_2_NONE ||
                      s.readStages != VK_PIPELINE_STAGE_2_NONE || s.unflushedWrites != VK_ACCESS_2_NONE;
    return s;
}

}  // namespace idk::graph
