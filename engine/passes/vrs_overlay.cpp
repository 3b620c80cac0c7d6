// vrs_overlay.cpp: --vrs-debug's rate overlay (vrs/overlay.comp.glsl): tints the lit HDR image per tile by the
// rate just classified, before the tonemap, like IDKEngine's shading-rate debug view.
#include <memory>

#include "passes/vrs_passes.hpp"

namespace idk::passes {

graph::TextureHandle addVrsOverlayPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       graph::BufferHandle rates, graph::TextureHandle target) {
    auto written = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "vrs_overlay",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(rates, graph::Access::StorageRead, kCs);
            *written = b.write(target, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, rates, written](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vrs_overlay_comp;
            desc.pushBytes = sizeof(gpu::VrsOverlayPush);
            desc.localSize = {8, 8, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::VrsOverlayPush push{};
            push.rates = pc.buffer(rates).address;
            push.target = pc.texture(*written).storageIndex;
            vk::pushConstants(cmd, ctx, push);
            VkExtent3D extent = pc.texture(*written).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, 8), vk::groupCount(extent.height, 8), 1);
        });
    return *written;
}

}  // namespace idk::passes
