// upscale.cpp: the temporal upscaler's resolve (shaders_glsl/temporal/upscale_resolve.comp.glsl) from the
// render-size lit image into the output-size persistent history "upscale color", and the copy of the
// reconstruction into the frame's output-size HDR target (upscale_output.comp). Plays the role of IDKEngine's FSR2
// wrapper (our own reconstruction: FSR2 is not a Debian package).
#include "passes/temporal_passes.hpp"

#include <memory>
#include "shared/temporal_types.h"
#include "shared/upscale_types.h"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

void dispatch(VkCommandBuffer cmd, VkExtent2D extent) {
    vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kTemporalGroupSize),
                  vk::groupCount(extent.height, gpu::kTemporalGroupSize), 1);
}

}  // namespace

graph::TextureHandle addUpscalePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                      const UpscaleInputs& in) {
    struct Handles {
        graph::TextureHandle history, color;
    };
    auto h = std::make_shared<Handles>();
    const UpscaleInputs u = in;
    graph.addPass(
        "upscale_resolve",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle x : {u.color, u.depth, u.motion}) b.read(x, graph::Access::StorageRead, kCs);
            if (u.opaque.valid()) b.read(u.opaque, graph::Access::StorageRead, kCs);
            b.read(u.temporal, graph::Access::StorageRead, kCs);
            h->history = b.read(b.history("upscale color"), graph::Access::StorageRead, kCs);
            graph::TextureDesc desc;
            desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            desc.sizeMode = graph::SizeMode::Absolute;  // output size, while the graph's relative extent is the render's
            desc.extent = {u.outputExtent.width, u.outputExtent.height, 1};
            desc.persistent = true;
            h->color = b.write(b.create("upscale color", desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, u, h](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::temporal_upscale_resolve_comp;
            desc.pushBytes = sizeof(gpu::UpscalePush);
            desc.localSize = {gpu::kTemporalGroupSize, gpu::kTemporalGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::UpscalePush push{};
            push.temporal = pc.buffer(u.temporal).address;
            push.color = pc.texture(u.color).storageIndex;
            push.depth = pc.texture(u.depth).storageIndex;
            push.motion = pc.texture(u.motion).storageIndex;
            push.opaque = u.opaque.valid() ? pc.texture(u.opaque).storageIndex : 0xFFFFFFFFu;
            push.history = pc.texture(h->history).storageIndex;
            push.outColor = pc.texture(h->color).storageIndex;
            push.outputExtent = {u.outputExtent.width, u.outputExtent.height};
            // A history of another size (the scale changed) was not written last frame: the graph cleared it.
            push.historyValid = !u.reset && pc.historyValid(h->history);
            push.maxWeight = u.maxWeight;
            push.clipGamma = u.clipGamma;
            push.sigma = u.sigma;
            push.frameStatic = u.frameStatic;
            vk::pushConstants(cmd, ctx, push);
            dispatch(cmd, u.outputExtent);
        });

    auto written = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "upscale_output",
        [&](graph::PassBuilder& b) {
            b.read(h->color, graph::Access::StorageRead, kCs);
            b.read(u.color, graph::Access::StorageRead, kCs);
            *written = b.write(u.target, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, h, written, u](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::temporal_upscale_output_comp;
            desc.pushBytes = sizeof(gpu::UpscaleOutputPush);
            desc.localSize = {gpu::kTemporalGroupSize, gpu::kTemporalGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            const VkExtent3D render = pc.texture(u.color).extent;
            gpu::UpscaleOutputPush push{pc.texture(h->color).storageIndex, pc.texture(u.color).storageIndex,
                                        pc.texture(*written).storageIndex, 0,
                                        {u.outputExtent.width, u.outputExtent.height},
                                        {render.width, render.height}};
            vk::pushConstants(cmd, ctx, push);
            dispatch(cmd, u.outputExtent);
        });
    return *written;
}

}  // namespace idk::passes
