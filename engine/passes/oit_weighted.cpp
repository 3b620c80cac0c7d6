// oit_weighted.cpp: the weighted blended rung of order-independent transparency: the BLEND draws (in any order)
// into two additive RGBA16F targets (oit/weighted.frag), then a compute composite over the lit HDR image
// (oit/composite.comp). Same inputs as the sorted rung (passes/transparency.cpp), whose result is the exact
// reference. Ports the weighted variant of IDKEngine's OIT passes (reference 2.14: record + resolve).
#include <array>
#include <memory>

#include "passes/passes.hpp"
#include "passes/rendering.hpp"
#include "passes/transparency_draws.hpp"
#include "shared/oit_types.h"
#include "shared/shadow_types.h"

namespace idk::passes {

graph::TextureHandle addWeightedOitPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                          const TransparencyInputs& t, graph::TextureHandle target,
                                          IndirectDrawLog* log) {
    graph::TextureDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    auto accum = std::make_shared<graph::TextureHandle>(graph.createTexture("oit accumulation", desc));
    auto reveal = std::make_shared<graph::TextureHandle>(graph.createTexture("oit revealage", desc));
    auto written = std::make_shared<graph::TextureHandle>();
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    graph.addPass(
        "oit_accumulate",
        [&](graph::PassBuilder& b) {  // the sorted rung's reads (passes/transparency.cpp), other targets
            *accum = b.write(*accum, graph::Access::ColorReadWrite);
            *reveal = b.write(*reveal, graph::Access::ColorReadWrite);
            readTransparencyInputs(b, t);
        },
        [&ctx, &shaders, t, accum, reveal, log](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            const graph::PhysicalTexture& a = pc.texture(*accum);
            const graph::PhysicalTexture& r = pc.texture(*reveal);
            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::transparency_forward_vert;
            desc.fragment = vk::ShaderId::oit_weighted_frag;
            desc.colorFormats = {a.format, r.format};
            desc.blend = {vk::BlendMode::Additive, vk::BlendMode::Additive};  // order-independent sums
            desc.cull = VK_CULL_MODE_NONE;
            desc.pushBytes = sizeof(gpu::TransparencyPush);
            const vk::Pipeline& pipeline = shaders.graphics(desc);
            std::array<VkRenderingAttachmentInfo, 2> colors{};
            for (size_t i = 0; i < 2; ++i) {
                colors[i].sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
                colors[i].imageView = (i == 0 ? a : r).view;
                colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
                colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // zero sums
                colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            }
            beginRendering(cmd, {a.extent.width, a.extent.height}, colors);
            vk::bindPipeline(cmd, pipeline);
            ctx.bindless().bind(cmd);
            gpu::TransparencyPush push = transparencyPush(pc, t);
            vk::pushConstants(cmd, ctx, push);
            drawTransparent(pc, t, log);
            vkCmdEndRendering(cmd);
        });
    graph.addPass(
        "oit_composite",
        [&](graph::PassBuilder& b) {
            b.read(*accum, graph::Access::StorageRead, kCs);
            b.read(*reveal, graph::Access::StorageRead, kCs);
            *written = b.write(target, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, accum, reveal, written](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::oit_composite_comp;
            desc.pushBytes = sizeof(gpu::OitCompositePush);
            desc.localSize = {gpu::kOitGroupSize, gpu::kOitGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::OitCompositePush push{pc.texture(*accum).storageIndex, pc.texture(*reveal).storageIndex,
                                       pc.texture(*written).storageIndex, 0};
            vk::pushConstants(cmd, ctx, push);
            VkExtent3D e = pc.texture(*written).extent;
            vkCmdDispatch(cmd, vk::groupCount(e.width, gpu::kOitGroupSize), vk::groupCount(e.height, gpu::kOitGroupSize),
                          1);
        });
    return *written;
}

}  // namespace idk::passes
