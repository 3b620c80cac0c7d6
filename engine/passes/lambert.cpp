// lambert.cpp: draws every scene triangle with Lambert shading into an HDR colour target with a transient
// depth buffer. The first pass of the port (the deferred PBR renderer replaces it); no direct IDKEngine
// counterpart, its shading follows the original's forward "light spheres" style without textures.
#include "passes/passes.hpp"
#include "passes/rendering.hpp"

#include <memory>

#include "shared/lambert_types.h"

namespace idk::passes {

LambertOutputs addLambertPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                              const render::GpuLambertScene& scene, graph::TextureHandle target,
                              const LambertSettings& settings) {
    // The setup callback fills the handles; the execute callback runs later and reads them through this pointer.
    auto out = std::make_shared<LambertOutputs>();
    constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    VkFormat colorFormat = settings.colorFormat;
    graph.addPass(
        "lambert",
        [&](graph::PassBuilder& b) {
            out->color = b.write(target, graph::Access::ColorWrite);
            graph::TextureDesc depth;
            depth.format = kDepthFormat;
            out->depth = b.write(b.create("lambert depth", depth), graph::Access::DepthWrite);
        },
        [&ctx, &shaders, &scene, settings, colorFormat, out](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            VkExtent2D extent = pc.outputExtent();

            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::lambert_lambert_vert;
            desc.fragment = vk::ShaderId::lambert_lambert_frag;
            desc.colorFormats = {colorFormat};
            desc.depthFormat = kDepthFormat;
            desc.depthCompare = VK_COMPARE_OP_LESS;  // scene::camera convention: depth 0 near, 1 far
            desc.cull = VK_CULL_MODE_NONE;            // the Cornell box's walls are seen from inside
            desc.pushBytes = sizeof(gpu::LambertPush);
            const vk::Pipeline& pipeline = shaders.graphics(desc);

            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = pc.view(out->color);
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            color.clearValue.color = {{settings.clearColor.r, settings.clearColor.g, settings.clearColor.b,
                                       settings.clearColor.a}};
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depth.imageView = pc.view(out->depth);
            depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;  // depth is not needed after this pass
            depth.clearValue.depthStencil = {1.0f, 0};
            beginRendering(cmd, extent, {&color, 1}, &depth);

            vk::bindPipeline(cmd, pipeline);
            ctx.bindless().bind(cmd);
            gpu::LambertPush push{settings.viewProjection, settings.ambient, scene.vertexIndex.value,
                                  scene.materialIndex.value, scene.lightIndex.value, scene.lightCount};
            vk::pushConstants(cmd, ctx, push);
            if (scene.vertexCount > 0) vkCmdDraw(cmd, scene.vertexCount, 1, 0, 0);
            vkCmdEndRendering(cmd);
        });
    return *out;
}

}  // namespace idk::passes
