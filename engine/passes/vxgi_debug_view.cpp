// vxgi_debug_view.cpp: "vxgi_debug_voxels", the voxel debug view (--gi-debug voxels): every pixel of the final
// HDR colour becomes the radiance of the first cell of level L the camera ray meets with coverage above
// kVxgiDebugCoverage (shaders_glsl/vxgi/debug_voxels.comp.glsl), black where it meets none. Ports the role of
// IDKEngine's VXGI/Voxelize/DebugVisualization/compute.glsl (idkengine-internals.md 1.5 step 4).
#include "passes/vxgi_passes.hpp"

#include <memory>

#include "shared/vxgi_debug_types.h"
#include "shared/vxgi_types.h"

namespace idk::passes {

graph::TextureHandle addVxgiDebugViewPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                          const VxgiDebugViewInputs& in) {
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    gpu::VxgiDebugPush base{};
    base.level = in.level;
    for (uint32_t d = 0; d < 6; ++d) {
        base.volumes[d] = in.volumeStorage[d];
        base.opacity[d] = in.volumeStorage[6 + d];
    }
    base.gridMin = in.box.gridMin;
    base.voxelSize = in.box.voxelSize;
    base.gridSize = in.box.size;
    // Level 0 reads the grid; a coarser level reads all six directional volumes (the ray's three facing ones
    // differ per pixel). Either way through storage views of one level the graph does not see, so the whole
    // image is declared.
    std::vector<graph::TextureHandle> volumes;
    if (in.level == 0) volumes.push_back(in.grid);
    else
        for (graph::TextureHandle d : in.directions)
            if (d.valid()) volumes.push_back(d);
    auto out = std::make_shared<graph::TextureHandle>(in.target);  // the execute callback runs after this returns
    const graph::BufferHandle frame = in.frame;
    graph.addPass(
        "vxgi_debug_voxels",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle v : volumes) b.read(v, graph::Access::StorageRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            *out = b.write(*out, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, frame, base, out](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vxgi_debug_voxels_comp;
            desc.pushBytes = sizeof(gpu::VxgiDebugPush);
            desc.localSize = {gpu::kConeGroupSize, gpu::kConeGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::VxgiDebugPush push = base;
            push.frame = pc.buffer(frame).address;
            push.target = pc.texture(*out).storageIndex;
            vk::pushConstants(cmd, ctx, push);
            const VkExtent3D extent = pc.texture(*out).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kConeGroupSize),
                          vk::groupCount(extent.height, gpu::kConeGroupSize), 1);
        });
    return *out;
}

}  // namespace idk::passes
