// gbuffer_mesh.cpp: the G-buffer's mesh-shader rung (ladder "mesh-shading", native): the culling pass's
// MeshTaskCommands drawn with vkCmdDrawMeshTasksIndirectCountEXT; the task shader (gbuffer/gbuffer_mesh.task.glsl)
// culls meshlets, the mesh shader (gbuffer_mesh.mesh.glsl) emits them into the unchanged G-buffer fragment shader.
// What the G-buffer pass (gbuffer.cpp) adds on this rung. Ports IDKEngine's MeshPath draw
// (glMultiDrawMeshTasksIndirectCountNV).
#include "passes/culling.hpp"

namespace idk::passes {

void useMeshShaders(vk::GraphicsPipelineDesc& desc) {
    desc.task = vk::ShaderId::gbuffer_gbuffer_mesh_task;
    desc.vertex = vk::ShaderId::gbuffer_gbuffer_mesh_mesh;
    desc.pushBytes = sizeof(gpu::GBufferMeshPush);
    desc.fragmentPushBytes = sizeof(gpu::GBufferPush);  // gbuffer.frag reads the prefix
}

void declareMeshDraws(graph::PassBuilder& b, const CulledDraws& c) {
    b.read(c.meshlets, graph::Access::StorageRead, kTaskMeshStages);
    b.read(c.meshletIndices, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT);
    constexpr VkPipelineStageFlags2 kTs = VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT;
    if (c.phase == gpu::kCullEarly) *c.meshletVisibilityUsed = b.read(c.meshletVisibility, graph::Access::StorageRead, kTs);
    if (c.phase == gpu::kCullLate)
        *c.meshletVisibilityUsed = b.write(c.meshletVisibility, graph::Access::StorageReadWrite, kTs);
    b.read(c.drawInstance, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT);
    b.read(c.draws, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT);
    b.read(c.views, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT);
    if (c.phase == gpu::kCullLate) b.read(c.pyramid, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT);
    *c.meshCountersWritten =
        b.write(c.meshCounters, graph::Access::StorageReadWrite, VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT);
}

void recordMeshDraws(graph::PassContext& pc, vk::Context& ctx, const CulledDraws& c, const gpu::GBufferPush& gbuffer) {
    gpu::GBufferMeshPush push{};
    push.gbuffer = gbuffer;
    push.meshlets = pc.buffer(c.meshlets).address;
    push.meshletIndices = pc.buffer(c.meshletIndices).address;
    push.meshletVisibility = c.phase != gpu::kCullFrustum ? pc.buffer(*c.meshletVisibilityUsed).address : 0;
    push.drawInstance = pc.buffer(c.drawInstance).address;
    push.draws = pc.buffer(c.draws).address;
    push.views = pc.buffer(c.views).address;
    push.pyramid = c.phase == gpu::kCullLate ? pc.buffer(c.pyramid).address : 0;
    push.counters = pc.buffer(*c.meshCountersWritten).address;
    push.view = c.view;
    push.phase = c.phase;
    vk::pushConstants(pc.commandBuffer(), ctx, push);
    vkCmdDrawMeshTasksIndirectCountEXT(pc.commandBuffer(), pc.vkBuffer(c.commands), 0, pc.vkBuffer(c.counters), 0,
                                       c.maxDraws, sizeof(gpu::MeshTaskCommand));
}

}  // namespace idk::passes
