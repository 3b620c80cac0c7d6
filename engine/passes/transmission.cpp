// transmission.cpp: the screen-space transmission pass (KHR_materials_transmission, _ior, _volume, _dispersion in
// the rasterizer). After the opaque frame is lit and the sky drawn, the lit colour is copied into a chain of
// halved levels (compute, transient RGBA16F images: level k about 2^-k of the frame); then the transmissive draws,
// sorted back to front (render/blend_draws.hpp), are forward-shaded by transparency/forward_body.h with
// include/screen_transmission.glsl: reflected lobes plus the chain read where the refracted view ray leaves the
// surface (its header lists what screen space cannot see). Depth-tested against the G-buffer's depth copy without
// writing depth, written opaque. The chain is a list of images, not one mipmapped image, because the render graph
// tracks each image whole (a pass cannot read level k - 1 while writing level k of one image without a barrier
// inside the pass); and it is read with storage loads, because a transient image in the bindless sampled array
// counts for the synchronization validation layer as read by every earlier draw that samples material textures.
// A real GPU would build one mipmapped image and sample it with one trilinear fetch. Not in IDKEngine.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "passes/passes.hpp"
#include "passes/rendering.hpp"
#include "passes/transparency_draws.hpp"
#include "shared/shadow_types.h"
#include "shared/transmission_types.h"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

// Level sizes of the chain for a frame of `extent`: halved (rounded up) down to 1 pixel in the larger axis, at
// most kTransmissionMaxLevels (the shader computes the same sizes, include/screen_transmission.glsl).
std::vector<VkExtent2D> levelSizes(VkExtent2D extent) {
    std::vector<VkExtent2D> sizes{extent};
    while (sizes.size() < gpu::kTransmissionMaxLevels && std::max(sizes.back().width, sizes.back().height) > 1) {
        const VkExtent2D s = sizes.back();
        sizes.push_back({std::max(1u, (s.width + 1) / 2), std::max(1u, (s.height + 1) / 2)});
    }
    return sizes;
}

// The opaque-colour chain of `lit` (one compute pass per level: each reads the level above).
std::vector<graph::TextureHandle> addOpaqueChain(graph::RenderGraph& graph, vk::Context& ctx,
                                                 vk::ShaderLibrary& shaders, graph::TextureHandle lit,
                                                 VkExtent2D extent) {
    const std::vector<VkExtent2D> sizes = levelSizes(extent);
    std::vector<graph::TextureHandle> levels;
    for (size_t i = 0; i < sizes.size(); ++i) {
        const graph::TextureHandle source = i == 0 ? lit : levels.back();
        const VkExtent2D src = i == 0 ? extent : sizes[i - 1], dst = sizes[i];
        auto out = std::make_shared<graph::TextureHandle>();
        graph.addPass(
            "transmission_chain" + std::to_string(i),
            [&](graph::PassBuilder& b) {
                b.read(source, graph::Access::StorageRead, kCs);
                graph::TextureDesc desc;
                desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
                desc.sizeMode = graph::SizeMode::Absolute;
                desc.extent = {dst.width, dst.height, 1};
                *out = b.write(b.create("transmission level " + std::to_string(i), desc),
                               graph::Access::StorageWrite, kCs);
            },
            [&ctx, &shaders, source, out, src, dst, scale = i == 0 ? 1u : 2u](graph::PassContext& pc) {
                VkCommandBuffer cmd = pc.commandBuffer();
                gpu::TransmissionDownPush push{pc.texture(source).storageIndex, pc.texture(*out).storageIndex,
                                               {src.width, src.height}, {dst.width, dst.height}, scale};
                vk::ComputePipelineDesc desc;
                desc.shader = vk::ShaderId::transmission_downsample_comp;
                desc.pushBytes = sizeof(push);
                desc.localSize = {gpu::kTransmissionGroupSize, gpu::kTransmissionGroupSize, 1};
                vk::bindPipeline(cmd, shaders.compute(desc));
                ctx.bindless().bind(cmd);
                vk::pushConstants(cmd, ctx, push);
                vkCmdDispatch(cmd, vk::groupCount(dst.width, gpu::kTransmissionGroupSize),
                              vk::groupCount(dst.height, gpu::kTransmissionGroupSize), 1);
            });
        levels.push_back(*out);
    }
    return levels;
}

}  // namespace

graph::TextureHandle addTransmissionPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                           const TransparencyInputs& in, graph::TextureHandle target,
                                           VkExtent2D extent, bool screen, IndirectDrawLog* log) {
    const std::vector<graph::TextureHandle> levels =
        screen ? addOpaqueChain(graph, ctx, shaders, target, extent) : std::vector<graph::TextureHandle>{};
    auto written = std::make_shared<graph::TextureHandle>();
    const TransparencyInputs t = in;
    graph.addPass(
        "transmission",
        [&](graph::PassBuilder& b) {
            *written = b.write(target, graph::Access::ColorReadWrite);
            readTransparencyInputs(b, t);
            for (graph::TextureHandle l : levels)
                b.read(l, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
        },
        [&ctx, &shaders, t, written, levels, log](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            const graph::PhysicalTexture& out = pc.texture(*written);
            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::transmission_forward_vert;
            desc.fragment = vk::ShaderId::transmission_forward_frag;
            desc.colorFormats = {out.format};
            desc.blend = {vk::BlendMode::Alpha};  // alpha 1: the fragment replaces the frame (and keeps coverage 1)
            desc.cull = VK_CULL_MODE_NONE;        // facing per material in the fragment shader, as the G-buffer
            desc.pushBytes = sizeof(gpu::TransparencyPush) + sizeof(gpu::TransmissionPush);
            const vk::Pipeline& pipeline = shaders.graphics(desc);

            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = out.view;
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the lit opaque surfaces and the sky
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            beginRendering(cmd, {out.extent.width, out.extent.height}, {&color, 1});
            vk::bindPipeline(cmd, pipeline);
            ctx.bindless().bind(cmd);
            struct {
                gpu::TransparencyPush forward;
                gpu::TransmissionPush chain;
            } push{transparencyPush(pc, t), {}};
            static_assert(sizeof(push) == sizeof(gpu::TransparencyPush) + sizeof(gpu::TransmissionPush));
            for (size_t i = 0; i < levels.size(); ++i) push.chain.levels[i] = pc.texture(levels[i]).storageIndex;
            push.chain.levelCount = uint32_t(levels.size());
            vk::pushConstants(cmd, ctx, push);
            drawTransparent(pc, t, log);
            vkCmdEndRendering(cmd);
        });
    return *written;
}

}  // namespace idk::passes
