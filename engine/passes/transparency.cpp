// transparency.cpp: draws the scene's BLEND primitives after the opaque lighting and the sky, back to front (the
// CPU-sorted second indirect buffer of render/blend_draws.cpp, ONE vkCmdDrawIndexedIndirect), forward-shaded with
// the deferred path's BRDF, lights, point shadows and environment ambient, "over"-blended into the HDR target and
// depth-tested against the G-buffer's depth copy without writing depth. Ports IDKEngine's RecordTransparent pass
// (reference 2.14) with sorting in place of its k-buffer and resolve (order-independent transparency comes later).
#include <memory>

#include "passes/passes.hpp"
#include "passes/rendering.hpp"
#include "passes/transparency_draws.hpp"
#include "shared/shadow_types.h"

namespace idk::passes {

graph::TextureHandle addTransparencyPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const TransparencyInputs& in, graph::TextureHandle target,
                                         IndirectDrawLog* log) {
    auto written = std::make_shared<graph::TextureHandle>();
    const TransparencyInputs t = in;
    graph.addPass(
        "transparency",
        [&](graph::PassBuilder& b) {
            *written = b.write(target, graph::Access::ColorReadWrite);
            readTransparencyInputs(b, t);
        },
        [&ctx, &shaders, t, written, log](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            const graph::PhysicalTexture& out = pc.texture(*written);
            VkExtent2D extent{out.extent.width, out.extent.height};
            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::transparency_forward_vert;
            desc.fragment = vk::ShaderId::transparency_forward_frag;
            desc.colorFormats = {out.format};
            desc.blend = {vk::BlendMode::Alpha};  // rgb: a src + (1 - a) dst; alpha (coverage): a + (1 - a) dst
            desc.cull = VK_CULL_MODE_NONE;        // facing per material in the fragment shader, as the G-buffer
            desc.pushBytes = sizeof(gpu::TransparencyPush);
            const vk::Pipeline& pipeline = shaders.graphics(desc);

            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = out.view;
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the lit opaque surfaces and the sky
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            beginRendering(cmd, extent, {&color, 1});
            vk::bindPipeline(cmd, pipeline);
            ctx.bindless().bind(cmd);
            gpu::TransparencyPush push = transparencyPush(pc, t);
            vk::pushConstants(cmd, ctx, push);
            drawTransparent(pc, t, log);
            vkCmdEndRendering(cmd);
        });
    return *written;
}

}  // namespace idk::passes
