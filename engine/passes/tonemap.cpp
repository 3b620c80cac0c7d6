// tonemap.cpp: a fullscreen triangle applying the AgX display transform to exposure * linear radiance and
// writing sRGB-encoded 8-bit values into the colour target (the PNG path; `idk render --out x.exr` skips this
// pass and keeps the linear radiance). Ports IDKEngine's TonemapAndGammaCorrect/compute.glsl (reference 2.20)
// without the bloom/volumetric inputs or dithering; the curve's sources are in tonemap/tonemap.frag.glsl.
// Deviation: a fragment pass (see shared/deferred_types.h TonemapPush for why).
#include "passes/passes.hpp"
#include "passes/rendering.hpp"

#include <memory>

#include "shared/deferred_types.h"

namespace idk::passes {

graph::TextureHandle addTonemapPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    graph::TextureHandle hdr, graph::TextureHandle target, float exposure) {
    auto written = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "tonemap",
        [&](graph::PassBuilder& b) {
            b.read(hdr, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
            *written = b.write(target, graph::Access::ColorWrite);
        },
        [&ctx, &shaders, hdr, written, exposure](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            const graph::PhysicalTexture& out = pc.texture(*written);
            VkExtent2D extent{out.extent.width, out.extent.height};
            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::fullscreen_triangle_vert;
            desc.fragment = vk::ShaderId::tonemap_tonemap_frag;
            desc.colorFormats = {out.format};
            desc.cull = VK_CULL_MODE_NONE;
            desc.depthTest = desc.depthWrite = false;
            desc.pushBytes = sizeof(gpu::TonemapPush);
            const vk::Pipeline& pipeline = shaders.graphics(desc);

            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = out.view;
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every pixel is written
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            beginRendering(cmd, extent, {&color, 1});
            vk::bindPipeline(cmd, pipeline);
            ctx.bindless().bind(cmd);
            gpu::TonemapPush push{pc.texture(hdr).storageIndex, exposure};
            vk::pushConstants(cmd, ctx, push);
            vkCmdDraw(cmd, 3, 1, 0, 0);
            vkCmdEndRendering(cmd);
        });
    return *written;
}

}  // namespace idk::passes
