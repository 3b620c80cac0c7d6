// graph_plan.cpp: the planning half of RenderGraph::compile(), pure: resolved descriptions and usage,
// history validity, transient lifetimes and the aliasing plan, and every barrier of the frame.
#include "graph/render_graph.hpp"
#include "graph/text_format.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace idk::graph {

using detail::Origin;
using detail::PassUse;
using detail::ResourcePlan;

namespace {

constexpr VkPipelineStageFlags2 kShaderStages =
    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT |
    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
    VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT | VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT;
constexpr VkPipelineStageFlags2 kDrawStages =
    VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
    VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;

uint32_t fullMipCount(VkExtent3D e) {
    const uint32_t largest = std::max({e.width, e.height, e.depth, 1u});
    return static_cast<uint32_t>(std::bit_width(largest));
}

}  // namespace

// Resolved descriptions (absolute extents, mips, usage from executed accesses), lifetimes, history validity.
void RenderGraph::resolveResources(std::vector<std::string>& errors) {
    detail::CompiledGraph& c = *compiled_;
    for (uint32_t pos = 0; pos < c.order.size(); ++pos) {
        for (const PassUse& use : passes_[c.order[pos]].uses) {
            ResourcePlan& plan = c.resources[use.resource];
            if (!plan.used) plan.firstPos = pos;
            plan.used = true;
            plan.lastPos = pos;
            plan.writtenThisFrame = plan.writtenThisFrame || use.write;
            if (resources_[use.resource].kind == ResourceKind::Image) {
                plan.texture.usage |= imageUsageFor(use.access);
            } else {
                plan.buffer.usage |= bufferUsageFor(use.access);
                if (use.access == Access::HostRead) plan.buffer.hostVisible = true;
            }
        }
    }
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        ResourcePlan& plan = c.resources[r];
        if (node.origin == Origin::History) continue;   // takes its pair's description below
        if (node.origin == Origin::Imported) {
            if (node.kind == ResourceKind::Image) {
                const PhysicalTexture& t = node.importedTexture;
                plan.texture = TextureInfo{t.format, t.extent.depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D,
                                           t.extent, t.mips, t.layers, false, plan.texture.usage};
            } else {
                plan.buffer.size = node.importedBuffer.size;
            }
            continue;
        }
        if (node.kind == ResourceKind::Buffer) {
            plan.buffer.size = node.bufferDesc.size;
            plan.buffer.usage |= node.bufferDesc.extraUsage;
            if (node.bufferDesc.size == 0) errors.push_back(strformat("render graph: buffer '{}' has size 0", node.name));
            continue;
        }
        const TextureDesc& d = node.textureDesc;
        TextureInfo& info = plan.texture;
        info.format = d.format;
        if (d.sizeMode == SizeMode::OutputRelative) {
            const auto scaled = [](uint32_t size, float scale) {
                return std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(static_cast<double>(size) * scale)));
            };
            info.extent = {scaled(node.relativeTo.width, d.scaleX), scaled(node.relativeTo.height, d.scaleY), 1};
        } else {
            info.extent = d.extent;
        }
        info.type = info.extent.depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
        info.mips = d.mips == 0 ? fullMipCount(info.extent) : d.mips;
        info.layers = d.layers;
        info.cube = d.cube;
        info.usage |= d.extraUsage;
        if (d.format == VK_FORMAT_UNDEFINED) {
            errors.push_back(strformat("render graph: texture '{}' has no format", node.name));
        }
        if (info.extent.width == 0 || info.extent.height == 0 || info.extent.depth == 0 || info.layers == 0) {
            errors.push_back(strformat("render graph: texture '{}' has a zero extent or layer count", node.name));
        }
        if (info.mips > fullMipCount(info.extent)) {
            errors.push_back(strformat("render graph: texture '{}' asks for {} mips, more than its {}x{}x{} extent "
                                         "allows", node.name, info.mips, info.extent.width, info.extent.height,
                                         info.extent.depth));
        }
        if (d.cube && (d.layers % 6 != 0 || info.extent.width != info.extent.height || info.type != VK_IMAGE_TYPE_2D)) {
            errors.push_back(strformat("render graph: cube texture '{}' needs square 2D faces and layers % 6 == 0",
                                         node.name));
        }
    }

    // Persistent pairs share one description: usage of both nodes, TRANSFER_DST for the first-frame clear,
    // and the pool's usage when everything else matches (so a smaller usage does not recreate the copies).
    const uint64_t frame = pool_.frameIndex();
    const uint32_t historyCopy = 1 - pool_.currentCopy();
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        if (node.origin != Origin::History && node.origin != Origin::Persistent) continue;
        ResourcePlan& plan = c.resources[r];
        const auto* entry = pool_.findPersistent(node.origin == Origin::History ? node.persistentName : node.name);
        if (node.origin == Origin::Persistent && plan.pairedWith != kInvalidId) continue;   // done with its history
        TextureInfo texture = plan.texture;
        BufferInfo buffer = plan.buffer;
        if (node.origin == Origin::History) {
            if (plan.pairedWith != kInvalidId) {
                const ResourcePlan& current = c.resources[plan.pairedWith];
                texture.usage |= current.texture.usage;
                const VkImageUsageFlags usage = texture.usage;
                texture = current.texture;
                texture.usage = usage;
                const VkBufferUsageFlags bufferUsage = buffer.usage | current.buffer.usage;
                const bool host = buffer.hostVisible || current.buffer.hostVisible;
                buffer = current.buffer;
                buffer.usage = bufferUsage;
                buffer.hostVisible = host;
            } else {   // kept from an earlier frame: its description is the pool's
                const VkImageUsageFlags usage = texture.usage;
                const VkBufferUsageFlags bufferUsage = buffer.usage;
                texture = entry->texture;
                texture.usage |= usage;
                buffer = entry->buffer;
                buffer.usage |= bufferUsage;
            }
        }
        texture.usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        buffer.usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        const ResourceKind kind = node.kind;
        bool reusable = false;
        if (entry && entry->kind == kind) {
            TextureInfo withUsage = texture;
            withUsage.usage |= entry->texture.usage;
            BufferInfo bufferWithUsage = buffer;
            bufferWithUsage.usage |= entry->buffer.usage;
            if (persistentCompatible(kind, entry->texture, entry->buffer, withUsage, bufferWithUsage)) {
                texture = withUsage;
                buffer = bufferWithUsage;
                reusable = true;
            }
        }
        plan.texture = texture;
        plan.buffer = buffer;
        if (node.origin == Origin::History) {
            plan.historyValid = reusable && frame > 0 &&
                                entry->writtenFrame[historyCopy] == static_cast<int64_t>(frame - 1);
            if (plan.pairedWith != kInvalidId) {
                c.resources[plan.pairedWith].texture = texture;
                c.resources[plan.pairedWith].buffer = buffer;
            }
        }
    }
}

// Transients used this frame go into shared heaps; host-read buffers live to the end of the frame (the
// CPU reads them after the fence, so nothing may reuse their bytes later in the frame).
void RenderGraph::planMemory() {
    detail::CompiledGraph& c = *compiled_;
    std::vector<AliasRequest> requests;
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const ResourcePlan& plan = c.resources[r];
        if (resources_[r].origin != Origin::Transient || !plan.used) continue;
        AliasRequest request;
        request.resource = r;
        const bool isImage = resources_[r].kind == ResourceKind::Image;
        request.requirements = isImage ? pool_.backend().textureRequirements(plan.texture)
                                       : pool_.backend().bufferRequirements(plan.buffer);
        request.key = HeapKey{resources_[r].kind, !isImage && plan.buffer.hostVisible,
                              request.requirements.memoryTypeBits};
        request.firstPass = plan.firstPos;
        request.lastPass = request.key.hostVisible ? static_cast<uint32_t>(c.order.size() - 1) : plan.lastPos;
        requests.push_back(request);
    }
    c.aliasing = planAliasing(requests);
    for (uint32_t i = 0; i < c.aliasing.slots.size(); ++i) c.resources[c.aliasing.slots[i].resource].slot = i;
}

// Simulates the frame in execution order, resource by resource, with the pure planner.
void RenderGraph::planBarriers() {
    detail::CompiledGraph& c = *compiled_;
    const uint32_t currentCopy = pool_.currentCopy();
    std::vector<ResourceState> states(resources_.size());
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        ResourcePlan& plan = c.resources[r];
        if (node.origin == Origin::Imported) {
            states[r] = node.importedState;
        } else if (node.origin == Origin::Persistent || node.origin == Origin::History) {
            const auto* entry = pool_.findPersistent(node.origin == Origin::History ? node.persistentName : node.name);
            const bool reusable = entry && entry->kind == node.kind &&
                                  persistentCompatible(node.kind, entry->texture, entry->buffer, plan.texture, plan.buffer);
            const uint32_t copy = node.origin == Origin::History ? 1 - currentCopy : currentCopy;
            if (reusable) states[r] = entry->states[copy];
        }
        // SYNC: an image whose history the graph does not know (imported without a state, or persistent and new)
        // may sit in memory that resources freed earlier used: the allocator recycles memory once the GPU is done
        // with it, which the host knows from a timeline wait but the synchronization validation layer (1.3.239)
        // does not see. Its first barrier waits on all earlier commands, so no earlier submission's access to those
        // bytes can race it. Once per new image; on a GPU the extra wait is for work that is long finished.
        if (node.kind == ResourceKind::Image && node.origin != Origin::Transient && isUnknownHistory(states[r])) {
            states[r] = unknownHistoryState();
        }
        if (node.origin == Origin::History && !plan.historyValid && plan.used) {
            // SYNC: never-written history is cleared before the first pass: discard (UNDEFINED), clear as a
            // transfer write; the first reader then waits on that write like on any other.
            Transition t = applyUse(states[r], Use{node.kind, Access::TransferDst, VK_PIPELINE_STAGE_2_NONE, true});
            if (t.barrier) {
                t.barrier->resource = r;
                c.prologueBarriers.push_back(*t.barrier);
            }
            c.prologueClears.push_back(r);
            states[r] = t.after;
        }
        plan.initial = states[r];
    }

    // SYNC (validation): the stages of every shader that ran earlier in this frame, and whether any wrote storage.
    // The synchronization validation layer of Debian 12 (1.3.239) cannot tell which element of a bindless
    // descriptor array a shader indexes, so it charges each draw and dispatch with an access to every image of the
    // arrays it binds (fixed upstream in 1.3.268, which skips descriptor arrays). A layout transition of an image
    // then looks like a hazard against a pass that never touched it. Each image layout transition therefore also
    // waits on these. It is an execution dependency on passes the graph runs in order anyway; on a GPU it can cost
    // a little overlap at a transition, never correctness.
    VkPipelineStageFlags2 shaderStagesSoFar = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 shaderWritesSoFar = VK_ACCESS_2_NONE;
    for (uint32_t pos = 0; pos < c.order.size(); ++pos) {
        VkPipelineStageFlags2 passShaderStages = VK_PIPELINE_STAGE_2_NONE;
        VkAccessFlags2 passShaderWrites = VK_ACCESS_2_NONE;
        for (const PassUse& use : passes_[c.order[pos]].uses) {
            const uint32_t r = use.resource;
            const detail::ResourceNode& node = resources_[r];
            ResourcePlan& plan = c.resources[r];
            if (node.origin == Origin::Transient && pos == plan.firstPos) {
                // SYNC (aliasing): the first use of a transient starts from UNDEFINED and waits on the last
                // accesses of every earlier occupant of its bytes: this frame's (lifetimes ended before pos)
                // and earlier frames' (the heap's tail), because the same memory is reused in submission order.
                ResourceState seed;
                if (plan.slot != kInvalidId) {
                    const AliasSlot& slot = c.aliasing.slots[plan.slot];
                    const AliasedHeap& heap = c.aliasing.heaps[slot.heap];
                    seed = mergeForAliasing(pool_.heapTail(heap.key, heap.size, heap.alignment), {});
                    for (const AliasSlot& other : c.aliasing.slots) {
                        if (other.resource != r && bytesOverlap(slot, other) && other.lastPass < pos) {
                            seed = mergeForAliasing(seed, states[other.resource]);
                        }
                    }
                }
                // SYNC (validation): a transient image's first use also waits on this frame's earlier accesses of
                // every other image. Nothing requires it (their bytes are elsewhere), but the synchronization
                // validation layer (1.3.239) cannot see where an optimal-tiling image's texels lie in its
                // VkDeviceMemory and reports WRITE_AFTER_WRITE against earlier writes to other images of the same
                // memory. The extra execution dependency orders passes that the graph runs in order anyway.
                if (node.kind == ResourceKind::Image) {
                    for (uint32_t o = 0; o < resources_.size(); ++o) {
                        if (o != r && resources_[o].kind == ResourceKind::Image && c.resources[o].used &&
                            c.resources[o].firstPos < pos) {
                            seed = mergeForAliasing(seed, states[o]);
                        }
                    }
                }
                states[r] = seed;
                plan.initial = seed;
            }
            const bool discard = use.version == 0 && (node.origin == Origin::Transient || node.origin == Origin::Persistent);
            const Use next{node.kind, use.access, use.stages, discard};
            Transition t = applyUse(states[r], next);
            if (t.barrier) {
                t.barrier->resource = r;
                if (node.kind == ResourceKind::Image && t.barrier->oldLayout != t.barrier->newLayout) {
                    t.barrier->srcStages |= shaderStagesSoFar;
                    t.barrier->srcAccess |= shaderWritesSoFar;
                }
                c.passes[pos].barriers.push_back(*t.barrier);
            }
            states[r] = t.after;
            VkPipelineStageFlags2 stages = effectiveStages(next) & kShaderStages;
            // A draw binds the arrays in its vertex and fragment shaders whatever stages its declared uses name.
            if (effectiveStages(next) & kDrawStages)
                stages |= VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
            passShaderStages |= stages;
            // Any shader may write through the storage-image array it binds, as far as the layer can tell.
            if (stages != VK_PIPELINE_STAGE_2_NONE) passShaderWrites |= VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        }
        shaderStagesSoFar |= passShaderStages;
        shaderWritesSoFar |= passShaderWrites;
    }

    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        if (node.origin == Origin::Imported && node.finalUse) {
            Transition t = applyUse(states[r], Use{node.kind, node.finalUse->access, node.finalUse->stages, false});
            if (t.barrier) {
                t.barrier->resource = r;
                // SYNC (validation): a final layout transition waits on the frame's shaders as one between passes
                // does (above): the layer charges each draw and dispatch after the image's last declared use with a
                // storage write of it (e.g. the OIT composite after the cone tracer's last read of the VXGI grid,
                // whose SHADER_READ_ONLY -> GENERAL transition then reported WRITE_AFTER_WRITE). On a GPU the
                // frame's last transitions wait for its last shaders, which end-of-frame work nearly does anyway.
                if (node.kind == ResourceKind::Image && t.barrier->oldLayout != t.barrier->newLayout) {
                    t.barrier->srcStages |= shaderStagesSoFar;
                    t.barrier->srcAccess |= shaderWritesSoFar;
                }
                c.finalBarriers.push_back(*t.barrier);
            }
            states[r] = t.after;
        }
        c.resources[r].final = states[r];
    }
}

}  // namespace idk::graph
