// taa.cpp: the TAA resolve (shaders_glsl/temporal/taa_resolve.comp.glsl) into this frame's persistent history
// ("taa color" with the per-pixel sample weight in alpha, "taa depth", "taa motion"), and a copy of the resolved
// colour into the frame's HDR image (taa_output.comp) for the passes after it. Ports IDKEngine's TAAResolve.cs.
#include "passes/temporal_passes.hpp"

#include <memory>

#include "shared/temporal_types.h"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

graph::TextureHandle persistentTarget(graph::PassBuilder& b, const char* name, VkFormat format) {
    graph::TextureDesc desc;
    desc.format = format;
    desc.persistent = true;
    return b.write(b.create(name, desc), graph::Access::StorageWrite, kCs);
}

void dispatch(VkCommandBuffer cmd, VkExtent3D extent) {
    vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kTemporalGroupSize),
                  vk::groupCount(extent.height, gpu::kTemporalGroupSize), 1);
}

}  // namespace

graph::TextureHandle addTaaPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                  const TaaInputs& in) {
    struct Handles {
        graph::TextureHandle history, historyDepth, historyMotion, color, depth, motion;
    };
    auto h = std::make_shared<Handles>();
    const TaaInputs t = in;
    graph.addPass(
        "taa_resolve",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle x : {t.color, t.depth, t.motion}) b.read(x, graph::Access::StorageRead, kCs);
            b.read(t.temporal, graph::Access::StorageRead, kCs);
            h->history = b.read(b.history("taa color"), graph::Access::StorageRead, kCs);
            h->historyDepth = b.read(b.history("taa depth"), graph::Access::StorageRead, kCs);
            h->historyMotion = b.read(b.history("taa motion"), graph::Access::StorageRead, kCs);
            h->color = persistentTarget(b, "taa color", VK_FORMAT_R16G16B16A16_SFLOAT);
            h->depth = persistentTarget(b, "taa depth", VK_FORMAT_R32_SFLOAT);
            h->motion = persistentTarget(b, "taa motion", VK_FORMAT_R32_UINT);
        },
        [&ctx, &shaders, t, h](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::temporal_taa_resolve_comp;
            desc.pushBytes = sizeof(gpu::TaaPush);
            desc.localSize = {gpu::kTemporalGroupSize, gpu::kTemporalGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::TaaPush push{};
            push.temporal = pc.buffer(t.temporal).address;
            push.color = pc.texture(t.color).storageIndex;
            push.depth = pc.texture(t.depth).storageIndex;
            push.motion = pc.texture(t.motion).storageIndex;
            push.history = pc.texture(h->history).storageIndex;
            push.historyDepth = pc.texture(h->historyDepth).storageIndex;
            push.historyMotion = pc.texture(h->historyMotion).storageIndex;
            push.outColor = pc.texture(h->color).storageIndex;
            push.outDepth = pc.texture(h->depth).storageIndex;
            push.outMotion = pc.texture(h->motion).storageIndex;
            // All three copies were written last frame or none was (the graph clears unwritten history to zero).
            push.historyValid = !t.reset && pc.historyValid(h->history) && pc.historyValid(h->historyDepth) &&
                                pc.historyValid(h->historyMotion);
            push.maxWeight = t.maxWeight;
            push.clipGamma = t.clipGamma;
            push.clampHistory = t.clampHistory;
            push.frameStatic = t.frameStatic;
            vk::pushConstants(cmd, ctx, push);
            dispatch(cmd, pc.texture(h->color).extent);
        });

    auto written = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "taa_output",
        [&](graph::PassBuilder& b) {
            b.read(h->color, graph::Access::StorageRead, kCs);
            *written = b.write(t.color, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, h, written](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::temporal_taa_output_comp;
            desc.pushBytes = sizeof(gpu::TaaOutputPush);
            desc.localSize = {gpu::kTemporalGroupSize, gpu::kTemporalGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            const VkExtent3D extent = pc.texture(*written).extent;
            gpu::TaaOutputPush push{pc.texture(h->color).storageIndex, pc.texture(*written).storageIndex,
                                    {extent.width, extent.height}};
            vk::pushConstants(cmd, ctx, push);
            dispatch(cmd, extent);
        });
    return *written;
}

}  // namespace idk::passes
