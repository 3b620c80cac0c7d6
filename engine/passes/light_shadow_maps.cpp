// light_shadow_maps.cpp: renders every layer of the directional cascades and spot maps (render/light_shadow_maps
// .hpp) from the scene's multi-draw-indirect buffer, one depth-only draw per layer with that layer's projection;
// and uploads the frame's shadow table (per-light GpuPointShadow entries, then the GpuShadowMap records) that the
// lighting passes read. Ports the shadow-map rendering of IDKEngine's shadow pass for its missing light types.
#include <algorithm>
#include <memory>

#include "passes/indirect_draw.hpp"
#include "passes/passes.hpp"
#include "passes/rendering.hpp"
#include "render/light_shadow_maps.hpp"
#include "shared/shadow_types.h"

namespace idk::passes {

graph::BufferHandle addShadowTablePass(graph::RenderGraph& graph, std::vector<uint8_t> bytes) {
    graph::BufferDesc desc;
    desc.size = std::max<size_t>(4, bytes.size());
    auto table = std::make_shared<graph::BufferHandle>(graph.createBuffer("shadow table", desc));
    auto data = std::make_shared<std::vector<uint8_t>>(std::move(bytes));
    graph.addPass(
        "shadow_table", [&](graph::PassBuilder& b) { *table = b.write(*table, graph::Access::TransferDst); },
        [table, data](graph::PassContext& pc) {
            // vkCmdUpdateBuffer takes at most 65536 bytes per call, in multiples of 4 (entries are 40 and 80 B).
            for (size_t offset = 0; offset < data->size(); offset += 65536)
                vkCmdUpdateBuffer(pc.commandBuffer(), pc.vkBuffer(*table), offset,
                                  std::min<size_t>(65536, data->size() - offset), data->data() + offset);
        });
    return *table;
}

std::vector<graph::TextureHandle> addLightShadowMapPass(graph::RenderGraph& graph, vk::Context& ctx,
                                                        vk::ShaderLibrary& shaders, const SceneBuffers& scene,
                                                        const render::LightShadowMaps& maps,
                                                        const render::LightShadowFrame& frame,
                                                        IndirectDrawLog* log) {
    auto out = std::make_shared<std::vector<graph::TextureHandle>>();
    const SceneBuffers s = scene;
    const bool mask = maps.alphaMask();
    // The maps' own commands when BLEND draws cast (render/shadow_caster_draws.hpp), else the scene's.
    const graph::BufferHandle draws = frame.casterDraws.valid() ? frame.casterDraws : s.drawCommands;
    auto projections = std::make_shared<std::vector<std::vector<render::ShadowProjection>>>(frame.projections);
    graph.addPass(
        "light_shadow_maps",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kVs = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
            constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
            for (graph::TextureHandle image : frame.images) out->push_back(b.write(image, graph::Access::DepthWrite));
            b.read(s.vertices, graph::Access::StorageRead, kVs);
            b.read(s.indices, graph::Access::VertexRead);
            b.read(s.instances, graph::Access::StorageRead, mask ? kVs | kFs : kVs);
            b.read(draws, graph::Access::IndirectRead);
            if (s.colors.valid()) b.read(s.colors, graph::Access::StorageRead, kVs);
            if (s.uv1.valid()) b.read(s.uv1, graph::Access::StorageRead, kVs);
            if (mask) {
                b.read(s.meshes, graph::Access::StorageRead, kFs);
                b.read(s.materials, graph::Access::StorageRead, kFs);
            }
        },
        [&ctx, &shaders, &maps, s, draws, projections, mask, log](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::light_shadows_map_vert;
            if (mask) desc.fragment = vk::ShaderId::light_shadows_mask_frag;  // depth-only without MASK / BLEND
            desc.depthFormat = VK_FORMAT_D32_SFLOAT;
            desc.depthCompare = VK_COMPARE_OP_LESS;
            desc.cull = VK_CULL_MODE_NONE;  // both sides cast (open meshes, single-sided walls)
            desc.pushBytes = sizeof(gpu::ShadowMapPush);
            const vk::Pipeline& pipeline = shaders.graphics(desc);

            gpu::ShadowMapPush push{};
            setSceneAddresses(push, pc, s, mask);
            vk::bindPipeline(cmd, pipeline);
            ctx.bindless().bind(cmd);
            vkCmdBindIndexBuffer(cmd, pc.vkBuffer(s.indices), 0, VK_INDEX_TYPE_UINT32);
            VkBuffer indirect = pc.vkBuffer(draws);
            const uint32_t size = maps.resolution();
            for (uint32_t c = 0; c < maps.casters().size(); ++c) {
                for (uint32_t l = 0; l < maps.layers(c); ++l) {
                    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                    depth.imageView = maps.layerView(c, l);
                    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;  // the graph's DepthWrite
                    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
                    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
                    depth.clearValue.depthStencil = {1.0f, 0};  // far: nothing occludes
                    beginRendering(cmd, {size, size}, {}, &depth, 1);
                    push.viewProjection = (*projections)[c][l].viewProjection;
                    vk::pushConstants(cmd, ctx, push);
                    drawAllIndexedIndirect(cmd, indirect, s.drawCount);  // see passes/indirect_draw.hpp
                    if (log) log->record(pc.passName(), s.drawCount);
                    vkCmdEndRendering(cmd);
                }
            }
        });
    return *out;
}

}  // namespace idk::passes
