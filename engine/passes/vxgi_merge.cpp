// vxgi_merge.cpp: the two compute-side passes of each voxelization slab (addVoxelizePasses, vxgi_voxelize.cpp,
// runs them around its draws). "vxgi_clear" zeroes the slab's write-conflict accumulators (or, on the gl-interop
// rung, the record counter and the sums), its depth keys and, in the first slab, the whole grid's cell mask.
// "vxgi_merge" resolves the accumulators into the RGBA16F grid (radiance and coverage) and into level 0 of the six
// directional volumes, and marks the level-1 cells holding an occupied voxel in the cell mask: it runs
// shaders_glsl/vxgi/merge.comp.glsl, the port of IDKEngine's VXGI/Voxelize merge compute shader (4x4x4 groups).
// Touched-voxel lists (VoxelizeInputs::lists; not on the gl-interop rung): the accumulating draws append each voxel
// at its first fragment of the frame (include/voxel_list.glsl), and "vxgi_merge_args" (merge_args.comp.glsl) sizes
// the merge's indirect dispatch to the entries of this frame's list and the previous frame's, the only voxels whose
// bits can change (occupied now, or occupied before and emptied now); it dispatches over the slab's every voxel
// where a list overflowed its bound (voxelListBytes) or the grid is new. Without lists a merge visits N^3 voxels
// where surfaces occupy O(N^2): on a GPU the saving is the empty voxels' reads (12 bytes each, 1.6 GB a frame at
// 512^3); lavapipe, whose merge time is mostly the occupied voxels' stores, measured on the Cornell box (128x128,
// 3 orbit frames, the last one's vxgi_merge, lists against none in one build): 64^3 about 18 ms against 16 (the
// lists' scattered reads cost more than the few empty voxels they spare), 128^3 95-105 against 96-111 ms, 256^3
// 417-534 against 600-609 ms.
#include "passes/vxgi_passes.hpp"

#include <memory>

#include "passes/vxgi_gl_accumulate.hpp"
#include "shared/vxgi_types.h"

namespace idk::passes {

VkDeviceSize voxelListBytes(uint32_t n) { return VkDeviceSize(64) * n * n; }

void addVoxelClearPass(graph::RenderGraph& graph, const VoxelizeInputs& in, const VoxelSlab& slab,
                       VoxelSlabImages& acc) {
    const uint32_t n = in.box.size;
    const bool first = slab.index == 0;
    const bool gl = in.gl != nullptr;
    auto mine = std::make_shared<VoxelSlabImages>();  // this slab's versions, for the execute callback
    graph.addPass(
        "vxgi_clear" + slab.suffix,
        [&](graph::PassBuilder& b) {
            if (first) {
                graph::TextureDesc cellDesc;
                cellDesc.format = kVoxelCellMaskFormat;
                cellDesc.sizeMode = graph::SizeMode::Absolute;
                const uint32_t c = voxelCellMaskSize(n);
                cellDesc.extent = {c, c, c};
                acc.cells = b.write(b.create("vxgi cell mask", cellDesc), graph::Access::TransferDst);
                graph::TextureDesc keyDesc;
                keyDesc.format = kVoxelDepthKeyFormat;
                keyDesc.sizeMode = graph::SizeMode::Absolute;
                keyDesc.extent = voxelDepthKeyExtent(n, slab.depth);
                acc.keys = b.create("vxgi depth keys", keyDesc);
            }
            acc.keys = b.write(acc.keys, graph::Access::TransferDst);
            if (first && acc.list.valid()) acc.list = b.write(acc.list, graph::Access::TransferDst);
            if (gl) {  // the record counter (the header) and the sums start at zero
                acc.records = b.write(acc.records, graph::Access::TransferDst);
                acc.sums = b.write(acc.sums, graph::Access::TransferDst);
            } else {
                const VoxelAccumulatorImages images = voxelAccumulatorImages(in.atomics);
                graph::TextureDesc desc;
                desc.format = images.format;
                desc.sizeMode = graph::SizeMode::Absolute;
                desc.extent = {n, n, slab.depth};
                acc.count = images.count;
                const char* names[8] = {"vxgi accum r",        "vxgi accum g",        "vxgi accum b",
                                        "vxgi accum facing x", "vxgi accum facing y", "vxgi accum facing z",
                                        "vxgi accum facing w", "vxgi accum count"};
                for (uint32_t i = 0; i < acc.count; ++i)
                    acc.images[i] =
                        b.write(first ? b.create(names[i], desc) : acc.images[i], graph::Access::TransferDst);
            }
            *mine = acc;
        },
        [mine, first](graph::PassContext& pc) {
            VkClearColorValue zero{};
            VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            VkCommandBuffer cmd = pc.commandBuffer();
            if (first)  // one mask for the whole grid: each slab's merge marks its cells
                vkCmdClearColorImage(cmd, pc.image(mine->cells), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1,
                                     &range);
            vkCmdClearColorImage(cmd, pc.image(mine->keys), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
            if (first && mine->list.valid())  // the append counter: the slabs append in turn
                vkCmdFillBuffer(cmd, pc.vkBuffer(mine->list), 0, gpu::kVoxelListHeaderWords * 4, 0);
            if (mine->records.valid()) {
                vkCmdFillBuffer(cmd, pc.vkBuffer(mine->records), 0, gpu::kVoxelRecordHeaderWords * 4, 0);
                vkCmdFillBuffer(cmd, pc.vkBuffer(mine->sums), 0, VK_WHOLE_SIZE, 0);
                return;
            }
            for (uint32_t i = 0; i < mine->count; ++i)
                vkCmdClearColorImage(cmd, pc.image(mine->images[i]), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1,
                                     &range);
        });
}

graph::TextureHandle addVoxelMergePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const VoxelizeInputs& in, const VoxelSlab& slab, VoxelSlabImages& acc,
                                       graph::TextureHandle grid, VxgiDirectionHandles& directions) {
    const uint32_t n = in.box.size;
    const uint32_t mode = voxelAtomicsMode(in.atomics);
    const bool full = in.fullMerge;
    const bool first = slab.index == 0;
    const VxgiDirectionIndices level0 = in.directionLevel0;
    const uint32_t slabZ = slab.z, depth = slab.depth;
    VxgiGlAccumulator* gl = in.gl;
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    // The lists' indices: this frame's, the previous frame's (kVoxelNoList: none, or no lists at all).
    const uint32_t list = in.lists ? in.lists->currentIndex : gpu::kVoxelNoList;
    const graph::BufferHandle previous = in.lists ? in.lists->previous : graph::BufferHandle{};
    const uint32_t prevList = previous.valid() ? in.lists->previousIndex : gpu::kVoxelNoList;
    graph::BufferHandle args;
    if (in.lists) {
        auto argsOut = std::make_shared<graph::BufferHandle>();
        graph.addPass(
            "vxgi_merge_args" + slab.suffix,
            [&](graph::PassBuilder& b) {
                graph::BufferDesc desc;
                desc.size = 3 * sizeof(uint32_t);  // VkDispatchIndirectCommand
                args = b.write(b.create("vxgi merge args" + slab.suffix, desc), graph::Access::StorageWrite, kCs);
                b.read(acc.list, graph::Access::StorageRead, kCs);
                if (previous.valid()) b.read(previous, graph::Access::StorageRead, kCs);
                *argsOut = args;
            },
            [&ctx, &shaders, argsOut, list, prevList, n, depth](graph::PassContext& pc) {
                VkCommandBuffer cmd = pc.commandBuffer();
                vk::ComputePipelineDesc desc;
                desc.shader = vk::ShaderId::vxgi_merge_args_comp;
                desc.pushBytes = sizeof(gpu::VoxelMergeArgsPush);
                desc.localSize = {1, 1, 1};
                vk::bindPipeline(cmd, shaders.compute(desc));
                ctx.bindless().bind(cmd);
                gpu::VoxelMergeArgsPush push{};
                push.args = pc.buffer(*argsOut).address;
                push.list = list;
                push.prevList = prevList;
                push.gridSize = n;
                push.slabDepth = depth;
                vk::pushConstants(cmd, ctx, push);
                vkCmdDispatch(cmd, 1, 1, 1);
            });
    }
    auto merged = std::make_shared<VoxelSlabImages>();
    auto target = std::make_shared<graph::TextureHandle>();
    auto indirect = std::make_shared<graph::BufferHandle>(args);
    graph.addPass(
        "vxgi_merge" + slab.suffix,
        [&](graph::PassBuilder& b) {
            if (args.valid()) {
                b.read(args, graph::Access::IndirectRead);
                b.read(acc.list, graph::Access::StorageRead, kCs);
                if (previous.valid()) b.read(previous, graph::Access::StorageRead, kCs);
            }
            for (uint32_t i = 0; i < acc.count; ++i) b.read(acc.images[i], graph::Access::StorageRead, kCs);
            if (acc.sums.valid()) b.read(acc.sums, graph::Access::StorageRead, kCs);
            // Read too: a voxel empty now and all zero in the grid already is not stored again
            // (merge.comp.glsl); and a later slab's merge keeps what the earlier slabs' stored.
            const bool writeOnly = full && first;
            grid = b.write(grid, writeOnly ? graph::Access::StorageWrite : graph::Access::StorageReadWrite, kCs);
            acc.cells =
                b.write(acc.cells, first ? graph::Access::StorageWrite : graph::Access::StorageReadWrite, kCs);
            // Level 0 through its own view; the graph tracks each volume whole (the mips read it next).
            for (graph::TextureHandle& d : directions)
                if (d.valid()) d = b.write(d, graph::Access::StorageReadWrite, kCs);
            b.sideEffect();  // the grid is persistent state: later frames and readers outside the graph use it
            *merged = acc;
            *target = grid;
        },
        [&ctx, &shaders, merged, target, indirect, n, mode, gl, level0, full, slabZ, depth, list,
         prevList](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vxgi_merge_comp;
            desc.pushBytes = sizeof(gpu::VoxelMergePush);
            desc.localSize = {gpu::kVoxelGroupSize, gpu::kVoxelGroupSize, gpu::kVoxelGroupSize};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::VoxelMergePush push{};
            for (uint32_t i = 0; i < merged->count; ++i) push.accum[i] = pc.texture(merged->images[i]).storageIndex;
            if (gl) push.accum[0] = gl->sumsIndex();
            push.grid = pc.texture(*target).storageIndex;
            for (uint32_t d = 0; d < 6; ++d) {
                push.directions[d] = level0[d];
                push.opacity[d] = level0[6 + d];
            }
            push.gridSize = n;
            push.mode = mode;
            push.full = full ? 1u : 0u;
            push.cells = pc.texture(merged->cells).storageIndex;
            push.slabZ = slabZ;
            push.slabDepth = depth;
            push.list = list;
            push.prevList = prevList;
            vk::pushConstants(cmd, ctx, push);
            if (indirect->valid()) {
                vkCmdDispatchIndirect(cmd, pc.vkBuffer(*indirect), 0);
                return;
            }
            const uint32_t groups = vk::groupCount(n, gpu::kVoxelGroupSize);
            vkCmdDispatch(cmd, groups, groups, vk::groupCount(depth, gpu::kVoxelGroupSize));
        });
    return grid;
}

}  // namespace idk::passes
