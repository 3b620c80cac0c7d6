// ssr.cpp: the screen-space reflection passes: "ssr_hiz" (passes::recordDepthPyramid with the closest-depth reduction),
// "ssr_trace" (ssr/ssr_trace.comp, 8x8 tiles) and "ssr_keep" (ssr/ssr_keep.comp: the lit image into graph
// history). Ports IDKEngine's SSR.cs (reference 2.16) with a Hi-Z march.
#include "passes/ssr.hpp"

#include "passes/culling.hpp"

#include <memory>

#include "shared/depth_pyramid.h"
#include "shared/ssr_types.h"
#include "vk/bindless.hpp"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr const char* kLitImage = "ssr lit image";

}  // namespace

graph::BufferHandle addSsrPyramidPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                      graph::TextureHandle depth, glm::uvec2 size) {
    graph::BufferDesc desc;
    desc.size = VkDeviceSize(gpu::hizLevelOffset(size, gpu::hizLevelCount(size))) * sizeof(float);
    const graph::BufferHandle created = graph.createBuffer("ssr closest-depth pyramid", desc);
    auto out = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "ssr_hiz",
        [&](graph::PassBuilder& b) {
            b.read(depth, graph::Access::StorageRead, kCs);
            *out = b.write(created, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, depth, out, size](graph::PassContext& pc) {
            recordDepthPyramid(pc.commandBuffer(), ctx, shaders, pc.texture(depth).storageIndex, size,
                               pc.buffer(*out).address, HizReduction::Closest);
        });
    return *out;
}

graph::TextureHandle addSsrTracePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                     const SsrInputs& in) {
    struct Handles {
        graph::TextureHandle history, target;
    };
    auto h = std::make_shared<Handles>();
    const SsrInputs s = in;
    graph.addPass(
        "ssr_trace",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle t : {s.gbuffer.depth, s.gbuffer.normal, s.gbuffer.material})
                b.read(t, graph::Access::StorageRead, kCs);
            b.read(s.frame, graph::Access::StorageRead, kCs);
            b.read(s.pyramid, graph::Access::StorageRead, kCs);
            h->history = b.read(b.history(kLitImage), graph::Access::StorageRead, kCs);
            graph::TextureDesc desc;
            desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            h->target = b.write(b.create("ssr reflections", desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, s, h](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::ssr_ssr_trace_comp;
            desc.pushBytes = sizeof(gpu::SsrPush);
            desc.localSize = {gpu::kSsrGroupSize, gpu::kSsrGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::SsrPush push{};
            push.previousViewProjection = s.previousViewProjection;
            push.frame = pc.buffer(s.frame).address;
            push.pyramid = pc.buffer(s.pyramid).address;
            push.depth = pc.texture(s.gbuffer.depth).storageIndex;
            push.normal = pc.texture(s.gbuffer.normal).storageIndex;
            push.material = pc.texture(s.gbuffer.material).storageIndex;
            push.history = pc.texture(h->history).storageIndex;
            push.target = pc.texture(h->target).storageIndex;
            push.maxSteps = s.maxSteps;
            push.thickness = s.thickness;
            // The graph clears a history copy that last frame did not write (first frame, resize) to zero.
            push.historyValid = s.havePrevious && pc.historyValid(h->history) ? 1u : 0u;
            vk::pushConstants(cmd, ctx, push);
            const VkExtent3D extent = pc.texture(h->target).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kSsrGroupSize),
                          vk::groupCount(extent.height, gpu::kSsrGroupSize), 1);
        });
    return h->target;
}

void addSsrKeepPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders, graph::TextureHandle hdr) {
    auto kept = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "ssr_keep",
        [&](graph::PassBuilder& b) {
            b.read(hdr, graph::Access::StorageRead, kCs);
            graph::TextureDesc desc;
            desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            desc.persistent = true;
            *kept = b.write(b.create(kLitImage, desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, hdr, kept](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::ssr_ssr_keep_comp;
            desc.pushBytes = sizeof(gpu::SsrKeepPush);
            desc.localSize = {gpu::kSsrGroupSize, gpu::kSsrGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            const VkExtent3D extent = pc.texture(*kept).extent;
            const gpu::SsrKeepPush push{pc.texture(hdr).storageIndex, pc.texture(*kept).storageIndex,
                                        {extent.width, extent.height}};
            vk::pushConstants(cmd, ctx, push);
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kSsrGroupSize),
                          vk::groupCount(extent.height, gpu::kSsrGroupSize), 1);
        });  // a write to a persistent resource: never culled, though only the next frame reads it
}

}  // namespace idk::passes
