// graph_execute.cpp: RenderGraph::execute(): realizes physical resources through the pool/backend, then
// records, per pass in order: debug label, timestamp, the planned barriers (one vkCmdPipelineBarrier2), the
// pass callback, timestamp; then the final transitions of imported resources; then commits to the pool
// what the next frame needs (persistent copies' states, heap tails).
#include "graph/render_graph.hpp"
#include "graph/text_format.hpp"

namespace idk::graph {

using detail::Origin;
using detail::ResourcePlan;

namespace {

void beginLabel(VkCommandBuffer cmd, const std::string& name) {
    if (vkCmdBeginDebugUtilsLabelEXT == nullptr || vkCmdEndDebugUtilsLabelEXT == nullptr) return;
    VkDebugUtilsLabelEXT label{};
    label.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT;
    label.pLabelName = name.c_str();
    vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
}

void endLabel(VkCommandBuffer cmd) {
    if (vkCmdBeginDebugUtilsLabelEXT == nullptr || vkCmdEndDebugUtilsLabelEXT == nullptr) return;
    vkCmdEndDebugUtilsLabelEXT(cmd);
}

VkImageSubresourceRange wholeImage(VkFormat format) {
    // SYNC: images are tracked as a whole (see barrier_planner.hpp), so every barrier covers all mips and
    // layers, and both aspects of depth+stencil formats (separateDepthStencilLayouts is core since 1.2, but
    // keeping both aspects in one layout is always valid).
    return VkImageSubresourceRange{aspectMaskFor(format), 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
}

}  // namespace

void RenderGraph::execute(VkCommandBuffer cmd) {
    if (executed_) throw GraphError("render graph: execute() called twice; build a new graph for the next frame");
    if (!compiled_) compile();
    if (vkCmdPipelineBarrier2 == nullptr) {
        throw GraphError("render graph: vkCmdPipelineBarrier2 is not loaded (volkLoadDevice on a Vulkan 1.3 device)");
    }
    executed_ = true;
    realizeResources();

    const detail::CompiledGraph& c = *compiled_;
    GraphBackend& backend = pool_.backend();
    backend.beginFrame(cmd, static_cast<uint32_t>(c.order.size()));
    recordBarriers(cmd, c.prologueBarriers);
    recordHistoryClears(cmd);
    for (uint32_t pos = 0; pos < c.order.size(); ++pos) {
        const detail::PassNode& pass = passes_[c.order[pos]];
        beginLabel(cmd, pass.name);
        backend.timestampBegin(cmd, pos, pass.name);
        recordBarriers(cmd, c.passes[pos].barriers);
        if (pass.exec) {
            PassContext context(*this, c.order[pos], cmd);
            pass.exec(context);
        }
        backend.timestampEnd(cmd, pos);
        endLabel(cmd);
    }
    recordBarriers(cmd, c.finalBarriers);
    commitToPool();
}

void RenderGraph::realizeResources() {
    const detail::CompiledGraph& c = *compiled_;
    physicalTextures_.assign(resources_.size(), PhysicalTexture{});
    physicalBuffers_.assign(resources_.size(), PhysicalBuffer{});

    // Heaps first: growing one releases the transients placed in the old one.
    std::vector<HeapHandle> heaps;
    for (const AliasedHeap& heap : c.aliasing.heaps) heaps.push_back(pool_.acquireHeap(heap.key, heap.size, heap.alignment));

    const uint32_t currentCopy = pool_.currentCopy();
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        const ResourcePlan& plan = c.resources[r];
        const bool isImage = node.kind == ResourceKind::Image;
        switch (node.origin) {
            case Origin::Imported:
                physicalTextures_[r] = node.importedTexture;
                physicalBuffers_[r] = node.importedBuffer;
                break;
            case Origin::Transient:
                if (plan.slot != kInvalidId) {
                    const AliasSlot& slot = c.aliasing.slots[plan.slot];
                    if (isImage) {
                        physicalTextures_[r] = pool_.acquireTexture(plan.texture, node.name, heaps[slot.heap], slot.offset);
                    } else {
                        physicalBuffers_[r] = pool_.acquireBuffer(plan.buffer, node.name, heaps[slot.heap], slot.offset);
                    }
                }
                break;
            case Origin::Persistent:
            case Origin::History: {
                if (node.origin == Origin::History && !plan.used) break;
                const std::string& name = node.origin == Origin::History ? node.persistentName : node.name;
                const auto& entry = pool_.acquirePersistent(name, node.kind, plan.texture, plan.buffer);
                const uint32_t copy = node.origin == Origin::History ? 1 - currentCopy : currentCopy;
                physicalTextures_[r] = entry.textures[copy];
                physicalBuffers_[r] = entry.buffers[copy];
                break;
            }
        }
    }
}

void RenderGraph::recordBarriers(VkCommandBuffer cmd, std::span<const PlannedBarrier> barriers) const {
    if (barriers.empty()) return;
    std::vector<VkImageMemoryBarrier2> images;
    std::vector<VkMemoryBarrier2> memory;
    images.reserve(barriers.size());
    memory.reserve(barriers.size());
    for (const PlannedBarrier& b : barriers) {
        // SYNC: buffers use global memory barriers (coarse but simple; one buffer range per barrier buys
        // nothing on the drivers we target). An image whose memory last belonged to another resource also
        // gets one, because an image barrier's access scopes cover only accesses made through that image.
        if (b.kind == ResourceKind::Buffer || b.aliasing) {
            VkMemoryBarrier2 m{};
            m.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
            m.srcStageMask = b.srcStages;
            m.srcAccessMask = b.srcAccess;
            m.dstStageMask = b.dstStages;
            m.dstAccessMask = b.dstAccess;
            memory.push_back(m);
        }
        if (b.kind == ResourceKind::Image) {
            const PhysicalTexture& texture = physicalTextures_[b.resource];
            VkImageMemoryBarrier2 i{};
            i.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
            i.srcStageMask = b.srcStages;
            i.srcAccessMask = b.srcAccess;
            i.dstStageMask = b.dstStages;
            i.dstAccessMask = b.dstAccess;
            i.oldLayout = b.oldLayout;
            i.newLayout = b.newLayout;
            i.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            i.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            i.image = texture.image;
            i.subresourceRange = wholeImage(texture.format);
            images.push_back(i);
        }
    }
    VkDependencyInfo dependency{};
    dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
    dependency.memoryBarrierCount = static_cast<uint32_t>(memory.size());
    dependency.pMemoryBarriers = memory.data();
    dependency.imageMemoryBarrierCount = static_cast<uint32_t>(images.size());
    dependency.pImageMemoryBarriers = images.data();
    vkCmdPipelineBarrier2(cmd, &dependency);
}

// First-frame (or after resize) history: defined as all zeros.
void RenderGraph::recordHistoryClears(VkCommandBuffer cmd) const {
    for (uint32_t r : compiled_->prologueClears) {
        if (resources_[r].kind == ResourceKind::Buffer) {
            if (vkCmdFillBuffer == nullptr) throw GraphError("render graph: vkCmdFillBuffer is not loaded");
            vkCmdFillBuffer(cmd, physicalBuffers_[r].buffer, 0, VK_WHOLE_SIZE, 0);
            continue;
        }
        const PhysicalTexture& texture = physicalTextures_[r];
        const VkImageSubresourceRange range = wholeImage(texture.format);
        if (isDepthOrStencilFormat(texture.format)) {
            if (vkCmdClearDepthStencilImage == nullptr) throw GraphError("render graph: vkCmdClearDepthStencilImage is not loaded");
            const VkClearDepthStencilValue zero{0.0f, 0};
            vkCmdClearDepthStencilImage(cmd, texture.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        } else {
            if (vkCmdClearColorImage == nullptr) throw GraphError("render graph: vkCmdClearColorImage is not loaded");
            const VkClearColorValue zero{};
            vkCmdClearColorImage(cmd, texture.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        }
    }
}

void RenderGraph::commitToPool() {
    const detail::CompiledGraph& c = *compiled_;
    const uint32_t currentCopy = pool_.currentCopy();
    const auto frame = static_cast<int64_t>(pool_.frameIndex());
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        const ResourcePlan& plan = c.resources[r];
        if (node.origin != Origin::Persistent && node.origin != Origin::History) continue;
        const std::string& name = node.origin == Origin::History ? node.persistentName : node.name;
        for (ResourcePool::PersistentEntry& entry : pool_.persistent_) {
            if (entry.name != name) continue;
            const uint32_t copy = node.origin == Origin::History ? 1 - currentCopy : currentCopy;
            if (plan.used) entry.states[copy] = plan.final;
            if (node.origin == Origin::Persistent && plan.writtenThisFrame) entry.writtenFrame[copy] = frame;
        }
    }
    for (const AliasedHeap& heap : c.aliasing.heaps) {
        ResourceState tail = pool_.heapTail(heap.key);
        for (const AliasSlot& slot : c.aliasing.slots) {
            if (c.aliasing.heaps[slot.heap].key == heap.key) tail = mergeForAliasing(tail, c.resources[slot.resource].final);
        }
        pool_.setHeapTail(heap.key, tail);
    }
    pool_.endFrame();
}

}  // namespace idk::graph
