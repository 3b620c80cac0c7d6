// vrs_reconstruct.cpp: the software VRS rung's reconstruction (vrs/reconstruct.comp.glsl): after lighting and sky
// shaded one anchor per coarse cell, every other pixel is interpolated edge-aware from the anchors around it.
// Reads and writes the HDR target in place (anchors are only read, the others only written).
#include <memory>

#include "passes/vrs_passes.hpp"
#include "shared/deferred_types.h"

namespace idk::passes {

graph::TextureHandle addVrsReconstructPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                           const GBufferOutputs& gbuffer, graph::BufferHandle frame,
                                           graph::BufferHandle rates, graph::TextureHandle target,
                                           bool fillSentinel) {
    auto written = std::make_shared<graph::TextureHandle>();
    const graph::TextureHandle depth = gbuffer.depth, normal = gbuffer.normal;
    graph.addPass(
        fillSentinel ? "vrs_sentinel" : "vrs_reconstruct",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(depth, graph::Access::StorageRead, kCs);
            b.read(normal, graph::Access::StorageRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            b.read(rates, graph::Access::StorageRead, kCs);
            *written = b.write(target, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, depth, normal, frame, rates, written, fillSentinel](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vrs_reconstruct_comp;
            desc.pushBytes = sizeof(gpu::VrsReconstructPush);
            desc.localSize = {8, 8, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::VrsReconstructPush push{};
            push.frame = pc.buffer(frame).address;
            push.rates = pc.buffer(rates).address;
            push.depth = pc.texture(depth).storageIndex;
            push.normal = pc.texture(normal).storageIndex;
            push.target = pc.texture(*written).storageIndex;
            push.fillSentinel = fillSentinel ? 1u : 0u;
            vk::pushConstants(cmd, ctx, push);
            VkExtent3D extent = pc.texture(*written).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, 8), vk::groupCount(extent.height, 8), 1);
        });
    return *written;
}

}  // namespace idk::passes
