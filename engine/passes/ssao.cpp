// ssao.cpp: one compute dispatch (8x8 tiles) of shaders_glsl/ssao/ssao.comp.glsl over the G-buffer. Ports
// IDKEngine's SSAO.cs (reference 2.16).
#include "passes/ssao.hpp"

#include <memory>

#include "shared/ssao_types.h"
#include "vk/bindless.hpp"

namespace idk::passes {

graph::TextureHandle addSsaoPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                 const GBufferOutputs& gbuffer, graph::BufferHandle frame, const SsaoParams& params) {
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    auto out = std::make_shared<graph::TextureHandle>();
    const graph::TextureHandle depth = gbuffer.depth, normal = gbuffer.normal;
    graph.addPass(
        "ssao",
        [&](graph::PassBuilder& b) {
            b.read(depth, graph::Access::StorageRead, kCs);
            b.read(normal, graph::Access::StorageRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            graph::TextureDesc desc;
            desc.format = VK_FORMAT_R32_SFLOAT;
            *out = b.write(b.create("ssao visibility", desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, depth, normal, frame, out, params](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::ssao_ssao_comp;
            desc.pushBytes = sizeof(gpu::SsaoPush);
            desc.localSize = {gpu::kSsaoGroupSize, gpu::kSsaoGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::SsaoPush push{pc.buffer(frame).address, pc.texture(depth).storageIndex,
                               pc.texture(normal).storageIndex, pc.texture(*out).storageIndex, params.samples,
                               params.radius, params.frameIndex};
            vk::pushConstants(cmd, ctx, push);
            const VkExtent3D extent = pc.texture(*out).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kSsaoGroupSize),
                          vk::groupCount(extent.height, gpu::kSsaoGroupSize), 1);
        });
    return *out;
}

}  // namespace idk::passes
