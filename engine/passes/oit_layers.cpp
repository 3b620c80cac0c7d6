// oit_layers.cpp: the fixed-layer rung of order-independent transparency (`--oit layers`): per pixel the
// kOitLayerCount (10, the original's TRANSPARENT_LAYERS) nearest BLEND fragments, kept by lock-free atomic
// insertion into storage-buffer arrays, then composited front to back over the lit image. Four passes:
//   oit_layers_clear   fill the depth keys with kOitEmptyKey and the claim bits with 0 (transfer);
//   oit_layers_depth   the BLEND draws, depth only: each fragment inserts its depth (oit/layers_depth.frag);
//   oit_layers_shade   the same draws, forward-shaded: each fragment stores its colour in its depth's slot;
//   oit_layers_resolve composite the slots in order over the HDR target (oit/layers_resolve.comp).
// Ports IDKEngine's RecordTransparent + ResolveTransparent k-buffer (reference 2.14). Departure: the original
// shades once and keeps the first 10 arrivals (order of rasterization); keeping the 10 nearest needs the depths
// before the colours, hence a second geometry pass; beyond 10 layers it loses only the most hidden ones.
// Memory: 10 x (4 B key + 8 B half colour) + 4 B claims = 124 B per pixel, as the original's.
#include <array>
#include <memory>

#include "passes/passes.hpp"
#include "passes/rendering.hpp"
#include "passes/transparency_draws.hpp"
#include "shared/oit_types.h"
#include "shared/shadow_types.h"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

struct LayerArrays {
    graph::BufferHandle keys, claims, colors;
};


// The arrays' addresses; the depth pass declares only the keys (a pass may touch only what it declared).
gpu::OitLayerBuffers layerBuffers(graph::PassContext& pc, const LayerArrays& a, VkExtent2D extent, bool keysOnly) {
    return {pc.buffer(a.keys).address, keysOnly ? 0 : pc.buffer(a.claims).address,
            keysOnly ? 0 : pc.buffer(a.colors).address, extent.width, extent.width * extent.height};
}

// One raster pass over the BLEND draws with no attachments (the fragments write the arrays).
void drawLayers(graph::PassContext& pc, vk::Context& ctx, vk::ShaderLibrary& shaders, const TransparencyInputs& t,
                const LayerArrays& a, VkExtent2D extent, vk::ShaderId fragment, IndirectDrawLog* log) {
    VkCommandBuffer cmd = pc.commandBuffer();
    vk::GraphicsPipelineDesc desc;
    desc.vertex = vk::ShaderId::oit_layers_vert;
    desc.fragment = fragment;
    desc.depthTest = false;  // the opaque test is the fragment's (against the G-buffer depth copy)
    desc.depthWrite = false;
    desc.cull = VK_CULL_MODE_NONE;
    desc.pushBytes = sizeof(gpu::OitLayersPush);
    const vk::Pipeline& pipeline = shaders.graphics(desc);
    beginRendering(cmd, extent, {});
    vk::bindPipeline(cmd, pipeline);
    ctx.bindless().bind(cmd);
    gpu::OitLayersPush push{};
    push.forward = transparencyPush(pc, t);
    push.layers = layerBuffers(pc, a, extent, fragment == vk::ShaderId::oit_layers_depth_frag);
    vk::pushConstants(cmd, ctx, push);
    drawTransparent(pc, t, log);
    vkCmdEndRendering(cmd);
}

}  // namespace

graph::TextureHandle addLayeredOitPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const TransparencyInputs& t, graph::TextureHandle target,
                                         IndirectDrawLog* log) {
    // The arrays cover the frame (the HDR target is output-sized); every pass below works within this extent.
    const VkExtent2D extent = graph.outputExtent();
    const VkDeviceSize pixels = VkDeviceSize(extent.width) * extent.height;
    auto a = std::make_shared<LayerArrays>();
    graph::BufferDesc desc;
    desc.size = pixels * gpu::kOitLayerCount * sizeof(uint32_t);
    a->keys = graph.createBuffer("oit layer depths", desc);
    desc.size = pixels * sizeof(uint32_t);
    a->claims = graph.createBuffer("oit layer claims", desc);
    desc.size = pixels * gpu::kOitLayerCount * 2 * sizeof(uint32_t);
    a->colors = graph.createBuffer("oit layer colours", desc);
    auto written = std::make_shared<graph::TextureHandle>();

    graph.addPass(
        "oit_layers_clear",
        [&](graph::PassBuilder& b) {
            a->keys = b.write(a->keys, graph::Access::TransferDst);
            a->claims = b.write(a->claims, graph::Access::TransferDst);
        },
        [a](graph::PassContext& pc) {
            vkCmdFillBuffer(pc.commandBuffer(), pc.vkBuffer(a->keys), 0, VK_WHOLE_SIZE, gpu::kOitEmptyKey);
            vkCmdFillBuffer(pc.commandBuffer(), pc.vkBuffer(a->claims), 0, VK_WHOLE_SIZE, 0);
        });
    graph.addPass(
        "oit_layers_depth",
        [&](graph::PassBuilder& b) {
            readTransparencyInputs(b, t);
            a->keys = b.write(a->keys, graph::Access::StorageReadWrite, kFs);  // atomicMin insertion
        },
        [&ctx, &shaders, t, a, extent, log](graph::PassContext& pc) {
            drawLayers(pc, ctx, shaders, t, *a, extent, vk::ShaderId::oit_layers_depth_frag, log);
        });
    graph.addPass(
        "oit_layers_shade",
        [&](graph::PassBuilder& b) {
            readTransparencyInputs(b, t);
            b.read(a->keys, graph::Access::StorageRead, kFs);
            a->claims = b.write(a->claims, graph::Access::StorageReadWrite, kFs);  // atomicOr claims
            a->colors = b.write(a->colors, graph::Access::StorageWrite, kFs);
        },
        [&ctx, &shaders, t, a, extent, log](graph::PassContext& pc) {
            drawLayers(pc, ctx, shaders, t, *a, extent, vk::ShaderId::oit_layers_shade_frag, log);
        });
    graph.addPass(
        "oit_layers_resolve",
        [&](graph::PassBuilder& b) {
            b.read(a->keys, graph::Access::StorageRead, kCs);
            b.read(a->claims, graph::Access::StorageRead, kCs);
            b.read(a->colors, graph::Access::StorageRead, kCs);
            *written = b.write(target, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, a, extent, written](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::oit_layers_resolve_comp;
            desc.pushBytes = sizeof(gpu::OitResolvePush);
            desc.localSize = {gpu::kOitGroupSize, gpu::kOitGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::OitResolvePush push{};
            push.layers = layerBuffers(pc, *a, extent, false);
            push.target = pc.texture(*written).storageIndex;
            vk::pushConstants(cmd, ctx, push);
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kOitGroupSize),
                          vk::groupCount(extent.height, gpu::kOitGroupSize), 1);
        });
    return *written;
}

}  // namespace idk::passes
