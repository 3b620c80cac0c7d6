// vrs_lighting_rate.cpp: the hardware VRS rungs' lighting + sky (vrs/lighting_rate.frag.glsl): one fullscreen
// triangle with dynamic rendering, its fragment rates taken from the rate image (vrs_rate_image.cpp):
// - VK_KHR_fragment_shading_rate: the image is the rendering's VkRenderingFragmentShadingRateAttachmentInfoKHR
//   (texel = tile), the pipeline carries ..._FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR, and the combiner ops
//   {KEEP, REPLACE} make the attachment's rate the fragment's (pipeline rate 1x1, no primitive rate);
// - VK_NV_shading_rate_image: the image is bound with vkCmdBindShadingRateImageNV and its texels index the
//   viewport's palette (vk/pipeline.cpp builds it from vk/shading_rate.cpp), as IDKEngine does in OpenGL.
// Lavapipe has neither extension: this pass is compiled (and its shader) but runs only on GPUs that have one.
#include <memory>

#include "passes/vrs_passes.hpp"
#include "shared/deferred_types.h"
#include "shared/ssr_types.h"
#include "shared/vrs_hardware_types.h"
#include "shared/vxgi_types.h"

namespace idk::passes {

graph::TextureHandle addVrsLightingRatePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                            const VrsHardwareLighting& h, graph::TextureHandle target,
                                            graph::BufferHandle& countedInvocations) {
    auto written = std::make_shared<graph::TextureHandle>();
    auto counted = std::make_shared<graph::BufferHandle>();
    const VrsHardwareLighting in = h;
    graph.addPass(
        "vrs_lighting_rate",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
            const LightingInputs& l = in.inputs;
            for (graph::TextureHandle t : {in.gbuffer.albedo, in.gbuffer.normal, in.gbuffer.material,
                                           in.gbuffer.emissive, in.gbuffer.depth})
                b.read(t, graph::Access::StorageRead, kFs);
            if (in.gbuffer.layers.valid()) b.read(in.gbuffer.layers, graph::Access::StorageRead, kFs);
            if (in.gbuffer.layerSpill.valid()) b.read(in.gbuffer.layerSpill, graph::Access::StorageRead, kFs);
            b.read(in.environment, graph::Access::SampledRead, kFs);
            b.read(in.frame, graph::Access::StorageRead, kFs);
            if (in.lights.valid()) b.read(in.lights, graph::Access::StorageRead, kFs);
            if (l.materials.valid()) b.read(l.materials, graph::Access::StorageRead, kFs);
            if (l.shadows.table.valid()) {
                b.read(l.shadows.table, graph::Access::StorageRead, kFs);
                for (graph::TextureHandle cube : l.shadows.cubes) b.read(cube, graph::Access::SampledRead, kFs);
                if (l.shadows.mask.valid()) b.read(l.shadows.mask, graph::Access::StorageRead, kFs);
            }
            b.read(l.vrsRates, graph::Access::StorageRead, kFs);
            if (l.ambientOcclusion.valid()) b.read(l.ambientOcclusion, graph::Access::StorageRead, kFs);
            if (l.indirect.diffuse.valid()) {
                b.read(l.indirect.diffuse, graph::Access::StorageRead, kFs);
                b.read(l.indirect.specular, graph::Access::StorageRead, kFs);
            }
            if (l.reflections.valid()) b.read(l.reflections, graph::Access::StorageRead, kFs);
            b.read(in.rateImage, graph::Access::ShadingRateRead);
            *counted = b.write(in.invocations, graph::Access::StorageReadWrite, kFs);
            *written = b.write(target, graph::Access::ColorWrite);
        },
        [&ctx, &shaders, in, written, counted](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            const graph::PhysicalTexture& out = pc.texture(*written);
            const bool nv = in.source == vk::ShadingRateSource::NvImage;
            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::fullscreen_triangle_vert;
            desc.fragment = vk::ShaderId::vrs_lighting_rate_frag;
            desc.colorFormats = {out.format};
            desc.depthTest = desc.depthWrite = false;
            desc.cull = VK_CULL_MODE_NONE;
            desc.pushBytes = sizeof(gpu::VrsLightingRatePush);
            desc.shadingRate = in.source;
            const vk::Pipeline& pipeline = shaders.graphics(desc);

            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = out.view;
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // the triangle covers every pixel: lighting or sky
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            const VkExtent2D extent{out.extent.width, out.extent.height};
            VkRenderingFragmentShadingRateAttachmentInfoKHR rateAttachment{
                VK_STRUCTURE_TYPE_RENDERING_FRAGMENT_SHADING_RATE_ATTACHMENT_INFO_KHR};
            rateAttachment.imageView = pc.view(in.rateImage);
            rateAttachment.imageLayout = VK_IMAGE_LAYOUT_FRAGMENT_SHADING_RATE_ATTACHMENT_OPTIMAL_KHR;
            rateAttachment.shadingRateAttachmentTexelSize = {in.texelSize, in.texelSize};
            VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO, nv ? nullptr : &rateAttachment};
            rendering.renderArea = {{0, 0}, extent};
            rendering.layerCount = 1;
            rendering.colorAttachmentCount = 1;
            rendering.pColorAttachments = &color;
            vkCmdBeginRendering(cmd, &rendering);
            const VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0, 1};
            const VkRect2D scissor{{0, 0}, extent};
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            vk::bindPipeline(cmd, pipeline);
            if (nv) {
                vkCmdBindShadingRateImageNV(cmd, pc.view(in.rateImage), VK_IMAGE_LAYOUT_SHADING_RATE_OPTIMAL_NV);
            } else {
                // combinerOps[0] KEEP: the pipeline rate (1x1; no primitive rates); [1] REPLACE: the attachment's.
                const VkExtent2D one{1, 1};
                const VkFragmentShadingRateCombinerOpKHR ops[2] = {VK_FRAGMENT_SHADING_RATE_COMBINER_OP_KEEP_KHR,
                                                                   VK_FRAGMENT_SHADING_RATE_COMBINER_OP_REPLACE_KHR};
                vkCmdSetFragmentShadingRateKHR(cmd, &one, ops);
            }
            ctx.bindless().bind(cmd);
            gpu::VrsLightingRatePush push{};
            gpu::LightingPush& p = push.lighting;
            const LightingInputs& l = in.inputs;
            p.frame = pc.buffer(in.frame).address;
            p.albedo = pc.texture(in.gbuffer.albedo).storageIndex;
            p.normal = pc.texture(in.gbuffer.normal).storageIndex;
            p.material = pc.texture(in.gbuffer.material).storageIndex;
            p.emissive = pc.texture(in.gbuffer.emissive).storageIndex;
            p.depth = pc.texture(in.gbuffer.depth).storageIndex;
            p.target = 0;  // unused: the colour attachment is the target
            p.pointShadows = l.shadows.table.valid() ? pc.buffer(l.shadows.table).address : 0;
            p.materials = l.materials.valid() ? pc.buffer(l.materials).address : 0;
            p.vrsRates = pc.buffer(l.vrsRates).address;
            p.ambientOcclusion = l.ambientOcclusion.valid() ? pc.texture(l.ambientOcclusion).storageIndex
                                                            : gpu::kLightingNoAo;
            p.vxgiDiffuse = l.indirect.diffuse.valid() ? pc.texture(l.indirect.diffuse).storageIndex : gpu::kNoVxgi;
            p.vxgiSpecular = l.indirect.specular.valid() ? pc.texture(l.indirect.specular).storageIndex : gpu::kNoVxgi;
            p.ssr = l.reflections.valid() ? pc.texture(l.reflections).storageIndex : gpu::kSsrNoImage;
            p.layers = in.gbuffer.layers.valid() ? pc.texture(in.gbuffer.layers).storageIndex : gpu::kLightingNoLayers;
            p.layerSpill = in.gbuffer.layerSpill.valid() ? pc.texture(in.gbuffer.layerSpill).storageIndex
                                                          : gpu::kLightingNoLayers;
            push.invocations = pc.buffer(*counted).address;
            vk::pushConstants(cmd, ctx, push);
            vkCmdDraw(cmd, 3, 1, 0, 0);
            vkCmdEndRendering(cmd);
        });
    countedInvocations = *counted;
    return *written;
}

}  // namespace idk::passes
