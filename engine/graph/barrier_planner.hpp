// barrier_planner.hpp: the pure hazard rules. Given what has happened to a resource so far (ResourceState)
// and the next access (Use), compute the synchronization2 barrier needed before it (if any) and the state
// after it. No Vulkan calls: the render graph turns PlannedBarriers into vkCmdPipelineBarrier2 later.
//
// Granularity: images are tracked per WHOLE resource (all mips and layers share one state and one layout);
// passes that read one mip and write another (Hi-Z, bloom chains) declare StorageReadWrite on the whole
// image. Buffers are tracked per whole buffer and synchronized with global memory barriers.
#pragma once
#include "graph/access.hpp"

#include <array>
#include <cstdint>
#include <optional>

namespace idk::graph {

// Read access bits whose visibility is tracked per stage (see ResourceState::visibleStages).
inline constexpr std::array<VkAccessFlags2, 10> kTrackedReadAccessBits{
    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,          VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT,        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
    VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,        VK_ACCESS_2_INDEX_READ_BIT,
    VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT,        VK_ACCESS_2_UNIFORM_READ_BIT,
    VK_ACCESS_2_TRANSFER_READ_BIT,                VK_ACCESS_2_HOST_READ_BIT,
};

// What a later access must synchronize with. A default-constructed state is "never used": nothing to wait
// for, layout UNDEFINED (the first use of a transient starts there and its contents are discarded).
struct ResourceState {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;           // images only
    // Stages of the last write, or the destination stages of the last layout transition (a transition is
    // a write). RAW and WAW wait on these. NONE = no write to wait for (imported content already visible).
    VkPipelineStageFlags2 writeStages = VK_PIPELINE_STAGE_2_NONE;
    // Write access bits of the last write that no barrier has made available yet (srcAccessMask).
    VkAccessFlags2 unflushedWrites = VK_ACCESS_2_NONE;
    // Write access bits of the last write even after a barrier flushed them (NONE once a layout transition
    // followed it). A later layout transition repeats them in its srcAccessMask: see Rule 1 in the .cpp.
    VkAccessFlags2 lastWriteAccess = VK_ACCESS_2_NONE;
    // Union of the stages of every read since the last write: a later write (or layout transition) waits on
    // ALL of them (WAR), even when the reads needed no barrier among themselves.
    VkPipelineStageFlags2 readStages = VK_PIPELINE_STAGE_2_NONE;
    // For each kTrackedReadAccessBits[i], the stages to which the last write has been made visible. A read
    // whose (stage, access) pairs are all covered needs no barrier (read-after-read); one in a new stage or
    // with a new access type still needs the last write made visible to it (a delayed RAW).
    std::array<VkPipelineStageFlags2, kTrackedReadAccessBits.size()> visibleStages{};
    // The memory last belonged to ANOTHER resource (aliasing in a heap, or last frame's occupant): the
    // barrier must also be emitted as a global memory barrier, because an image barrier's access scopes
    // only cover accesses made through that image.
    bool aliasedMemory = false;

    bool operator==(const ResourceState&) const = default;
};

// The next access to a resource.
struct Use {
    ResourceKind kind = ResourceKind::Image;
    Access access = Access::SampledRead;
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;   // NONE: the table's default stages
    bool discard = false;   // previous contents are not needed: images transition from UNDEFINED
};

// One barrier. For images an image memory barrier (whole resource) with a layout transition when
// oldLayout != newLayout; for buffers a global memory barrier.
struct PlannedBarrier {
    uint32_t resource = ~0u;   // graph resource index; the planner leaves it unset, the graph fills it
    ResourceKind kind = ResourceKind::Image;
    VkPipelineStageFlags2 srcStages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 srcAccess = VK_ACCESS_2_NONE;
    VkPipelineStageFlags2 dstStages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 dstAccess = VK_ACCESS_2_NONE;
    VkImageLayout oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout newLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    bool aliasing = false;     // see ResourceState::aliasedMemory

    bool operator==(const PlannedBarrier&) const = default;
};

struct Transition {
    std::optional<PlannedBarrier> barrier;
    ResourceState after;
};

// The rules, in order:
//  1. image + (layout differs or discard): barrier with layout transition; waits on the last write and all
//     readers, flushes unflushed writes (old layout UNDEFINED when discarding).
//  2. write: WAW/WAR barrier if anything happened before: waits on last write + all readers, flushes
//     unflushed writes; dstAccess = the write's access only when there was an earlier write (WAW needs a
//     memory dependency); a pure WAR (only reads before) is an execution dependency (dstAccess NONE).
//  3. read: RAW barrier if a write is unflushed or not yet visible to every (stage, access) of this read;
//     otherwise no barrier (read-after-read), but the read's stages are accumulated for rule 2.
// Precondition: the use is valid for its kind (accessInfo(...).valid); invalid uses return no barrier and
// an unchanged state (the graph reports them as errors before planning).
Transition applyUse(const ResourceState& previous, const Use& next) noexcept;

// The barrier part of applyUse.
std::optional<PlannedBarrier> planBarrier(const ResourceState& previous, const Use& next) noexcept;

// The state of a resource whose last access was `access` at `stages` (NONE = table default), with no barrier
// since: use it for resources imported right after being written/read earlier in the command buffer.
ResourceState stateAfterAccess(Access access, ResourceKind kind,
                               VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE) noexcept;

// Union of two states for memory that several earlier resources occupied (aliasing): waits on everything
// either waited on; layout UNDEFINED (the contents belong to someone else) and aliasedMemory set.
// The state of memory with unknown history (a new image, a new heap): every earlier command may have written it.
// The first barrier on it then waits on ALL_COMMANDS with MEMORY_WRITE (see planBarriers for why).
ResourceState unknownHistoryState() noexcept;
bool isUnknownHistory(const ResourceState& s) noexcept;  // nothing known: UNDEFINED, no stages, no accesses
ResourceState mergeForAliasing(const ResourceState& a, const ResourceState& b) noexcept;

// The stages a use runs in (its own, or the table default).
VkPipelineStageFlags2 effectiveStages(const Use& use) noexcept;

}  // namespace idk::graph
