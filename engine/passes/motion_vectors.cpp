// motion_vectors.cpp: screen-space motion of every G-buffer surface, from this and last frame's instance
// transforms and vertex positions (skinned and morphed copies included) and camera matrices. One
// vkCmdDrawIndexedIndirect over the G-buffer's draw list; the fragment shader keeps the fragment whose depth the
// G-buffer kept. Ports the velocity output of IDKEngine's GBuffer pass (reference 2.5: RG16F, UV-space delta).
// Deviation: a separate pass so the G-buffer is untouched while TAA is off; a real GPU would write it as one more
// G-buffer target (one geometry pass instead of two).
#include "passes/indirect_draw.hpp"
#include "passes/rendering.hpp"
#include "passes/temporal_passes.hpp"

#include <memory>

#include "shared/temporal_types.h"

namespace idk::passes {

graph::TextureHandle addMotionVectorPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const MotionVectorInputs& in, IndirectDrawLog* log) {
    auto out = std::make_shared<graph::TextureHandle>();
    const MotionVectorInputs m = in;
    graph.addPass(
        "motion_vectors",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kVs = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
            constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
            graph::TextureDesc desc;
            desc.format = VK_FORMAT_R32_UINT;
            *out = b.write(b.create("motion vectors", desc), graph::Access::ColorWrite);
            b.read(m.temporal, graph::Access::StorageRead, kVs);
            b.read(m.depth, graph::Access::StorageRead, kFs);
            if (m.scene.drawCount == 0) return;
            b.read(m.scene.vertices, graph::Access::StorageRead, kVs);
            b.read(m.scene.indices, graph::Access::VertexRead);
            b.read(m.scene.instances, graph::Access::StorageRead, kVs);
            b.read(m.scene.drawCommands, graph::Access::IndirectRead);
            if (m.prevVertices.resource != m.scene.vertices.resource) b.read(m.prevVertices, graph::Access::StorageRead, kVs);
            if (m.prevInstances.resource != m.scene.instances.resource) b.read(m.prevInstances, graph::Access::StorageRead, kVs);
        },
        [&ctx, &shaders, m, out, log](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = pc.view(*out);
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // zero motion; background pixels are told apart by depth
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            beginRendering(cmd, pc.outputExtent(), {&color, 1});
            if (m.scene.drawCount > 0) {
                vk::GraphicsPipelineDesc desc;
                desc.vertex = vk::ShaderId::temporal_motion_vectors_vert;
                desc.fragment = vk::ShaderId::temporal_motion_vectors_frag;
                desc.colorFormats = {VK_FORMAT_R32_UINT};
                desc.cull = VK_CULL_MODE_NONE;  // the G-buffer's depth decides which fragment is kept
                desc.depthTest = desc.depthWrite = false;
                desc.pushBytes = sizeof(gpu::MotionPush);
                vk::bindPipeline(cmd, shaders.graphics(desc));
                ctx.bindless().bind(cmd);
                gpu::MotionPush push{};
                push.temporal = pc.buffer(m.temporal).address;
                push.vertices = pc.buffer(m.scene.vertices).address;
                push.instances = pc.buffer(m.scene.instances).address;
                // Last frame's copies exist once a frame has written them; until then nothing has moved yet.
                const bool havePrevious = m.prevVertices.resource != m.scene.vertices.resource &&
                                          pc.historyValid(m.prevVertices) && pc.historyValid(m.prevInstances);
                push.prevVertices = havePrevious ? pc.buffer(m.prevVertices).address : push.vertices;
                push.prevInstances = havePrevious ? pc.buffer(m.prevInstances).address : push.instances;
                push.depth = pc.texture(m.depth).storageIndex;
                vk::pushConstants(cmd, ctx, push);
                vkCmdBindIndexBuffer(cmd, pc.vkBuffer(m.scene.indices), 0, VK_INDEX_TYPE_UINT32);
                drawAllIndexedIndirect(cmd, pc.vkBuffer(m.scene.drawCommands), m.scene.drawCount);  // indirect_draw.hpp
                if (log) log->record(pc.passName(), m.scene.drawCount);
            }
            vkCmdEndRendering(cmd);
        });
    return *out;
}

void addBufferHistoryPass(graph::RenderGraph& graph, const char* passName, const char* persistentName,
                          graph::BufferHandle source, VkDeviceSize bytes) {
    auto copy = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        passName,
        [&](graph::PassBuilder& b) {
            b.read(source, graph::Access::TransferSrc);
            graph::BufferDesc desc;
            desc.size = bytes;
            desc.persistent = true;
            *copy = b.write(b.create(persistentName, desc), graph::Access::TransferDst);
        },
        [source, copy, bytes](graph::PassContext& pc) {
            VkBufferCopy region{0, 0, bytes};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(source), pc.vkBuffer(*copy), 1, &region);
        });
}

}  // namespace idk::passes
