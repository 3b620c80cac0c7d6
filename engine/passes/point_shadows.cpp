// point_shadows.cpp: renders one depth cube per shadow-casting point light from the scene's multi-draw-indirect
// buffer, along the capability ladder "point-shadow cube faces": native = ONE instanced indirect draw per light
// (instanceCount * 6, the vertex shader writes gl_Layer = face), fallback = six indirect draws per light into
// single-face views (the shadow table the lighting reads is uploaded by passes/light_shadow_maps.cpp). With GPU
// culling (passes/cull_shadows.cpp) every face has its own compacted commands and count, so the pass draws face by
// face with vkCmdDrawIndexedIndirectCount on either rung (face_culled.vert: the instance is gl_InstanceIndex).
// Ports IDKEngine's PointShadowManager.RenderShadowMaps (reference 2.12; there the faces are culled on the CPU).
#include <algorithm>
#include <memory>

#include "passes/culling.hpp"
#include "passes/indirect_draw.hpp"
#include "passes/passes.hpp"
#include "passes/rendering.hpp"
#include "render/point_shadow_maps.hpp"
#include "shared/shadow_types.h"

namespace idk::passes {
namespace {

constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;

void beginDepthRendering(VkCommandBuffer cmd, VkImageView view, uint32_t size, uint32_t layers) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;  // the graph's DepthWrite layout
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};  // far: nothing occludes
    beginRendering(cmd, {size, size}, {}, &depth, layers);
}

}  // namespace

std::vector<graph::TextureHandle> addPointShadowPass(graph::RenderGraph& graph, vk::Context& ctx,
                                                     vk::ShaderLibrary& shaders, const SceneBuffers& scene,
                                                     const render::PointShadowMaps& maps,
                                                     const render::PointShadowFrame& frameIn, IndirectDrawLog* log,
                                                     const ShadowCulledDraws* culledIn) {
    auto frame = std::make_shared<render::PointShadowFrame>(frameIn);
    auto out = std::make_shared<std::vector<graph::TextureHandle>>();
    const SceneBuffers s = scene;
    const ShadowCulledDraws culled = culledIn ? *culledIn : ShadowCulledDraws{};
    const bool layered = maps.layered() && !culledIn, mask = maps.alphaMask();
    // The culled per-face commands, else the maps' own (x6 on the native rung, BLEND casters) or the scene's.
    const graph::BufferHandle draws = culledIn                    ? culled.commands
                                      : frame->casterDraws.valid() ? frame->casterDraws
                                                                   : s.drawCommands;
    graph.addPass(
        "point_shadows",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kVs = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
            constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
            for (graph::TextureHandle cube : frame->cubes) out->push_back(b.write(cube, graph::Access::DepthWrite));
            b.read(s.vertices, graph::Access::StorageRead, kVs);
            b.read(s.indices, graph::Access::VertexRead);
            b.read(s.instances, graph::Access::StorageRead, mask ? kVs | kFs : kVs);
            b.read(draws, graph::Access::IndirectRead);
            if (culled.counters.valid()) b.read(culled.counters, graph::Access::IndirectRead);
            if (s.colors.valid()) b.read(s.colors, graph::Access::StorageRead, kVs);
            if (s.uv1.valid()) b.read(s.uv1, graph::Access::StorageRead, kVs);
            if (mask) {
                b.read(s.meshes, graph::Access::StorageRead, kFs);
                b.read(s.materials, graph::Access::StorageRead, kFs);
            }
        },
        [&ctx, &shaders, &maps, s, frame, draws, layered, mask, log, culled](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();

            vk::GraphicsPipelineDesc desc;
            desc.vertex = layered                   ? vk::ShaderId::point_shadows_layered_vert
                          : culled.commands.valid() ? vk::ShaderId::point_shadows_face_culled_vert
                                                    : vk::ShaderId::point_shadows_face_vert;
            if (mask) desc.fragment = vk::ShaderId::point_shadows_mask_frag;  // depth-only without MASK / BLEND
            desc.depthFormat = kShadowFormat;
            desc.depthCompare = VK_COMPARE_OP_LESS;
            desc.cull = VK_CULL_MODE_NONE;  // both sides cast (open meshes, single-sided walls)
            desc.pushBytes = sizeof(gpu::PointShadowPush);
            const vk::Pipeline& pipeline = shaders.graphics(desc);

            gpu::PointShadowPush push{};
            setSceneAddresses(push, pc, s, mask);
            const uint32_t size = maps.resolution();
            vk::bindPipeline(cmd, pipeline);  // pipeline, set and index buffer outlive the rendering scopes below
            ctx.bindless().bind(cmd);
            vkCmdBindIndexBuffer(cmd, pc.vkBuffer(s.indices), 0, VK_INDEX_TYPE_UINT32);
            VkBuffer indirect = pc.vkBuffer(draws);
            for (uint32_t c = 0; c < maps.casters().size(); ++c) {
                push.lightPosition = frame->table[maps.casters()[c]].position;
                push.nearPlane = frame->planes[c].x;
                push.farPlane = frame->planes[c].y;
                // Native: one draw, six instances per command, gl_Layer = instance. Fallback: face by face.
                for (uint32_t face = 0; face < (layered ? 1u : 6u); ++face) {
                    beginDepthRendering(cmd, layered ? maps.layeredView(c) : maps.faceView(c, face), size,
                                        layered ? 6u : 1u);
                    push.face = face;
                    vk::pushConstants(cmd, ctx, push);
                    if (culled.commands.valid()) {  // this face's compacted commands and GPU count
                        const uint32_t view = c * 6 + face;
                        vkCmdDrawIndexedIndirectCount(cmd, indirect, culled.commandOffset(view),
                                                      pc.vkBuffer(culled.counters), culled.countOffset(view),
                                                      culled.maxDraws, sizeof(VkDrawIndexedIndirectCommand));
                        if (log) log->record(pc.passName(), culled.maxDraws);  // the most it may draw
                    } else {
                        drawAllIndexedIndirect(cmd, indirect, s.drawCount);  // see passes/indirect_draw.hpp
                        if (log) log->record(pc.passName(), s.drawCount);
                    }
                    vkCmdEndRendering(cmd);
                }
            }
        });
    return *out;
}

}  // namespace idk::passes
