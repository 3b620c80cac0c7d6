// transparency_draws.hpp: what every transparency rung (sorted, weighted blended, fixed layers) records the same
// way: the forward shading's push block from the frame's buffers, and the one indirect draw of the BLEND draws.
#pragma once
#include "graph/render_graph.hpp"
#include "passes/passes.hpp"
#include "shared/shadow_types.h"

namespace idk::passes {

inline gpu::TransparencyPush transparencyPush(graph::PassContext& pc, const TransparencyInputs& t) {
    const SceneBuffers& s = t.scene;
    gpu::TransparencyPush push{};
    push.frame = pc.buffer(t.frame).address;
    push.vertices = pc.buffer(s.vertices).address;
    push.instances = pc.buffer(s.instances).address;
    push.meshes = pc.buffer(s.meshes).address;
    push.materials = pc.buffer(s.materials).address;
    push.colors = s.colors.valid() ? pc.buffer(s.colors).address : 0;
    push.uv1 = s.uv1.valid() ? pc.buffer(s.uv1).address : 0;
    push.pointShadows = t.shadows.table.valid() ? pc.buffer(t.shadows.table).address : 0;
    push.depth = pc.texture(t.depth).storageIndex;
    return push;
}

// The BLEND draws in the frame's order (t.sortedDraws), inside a begun rendering with the pipeline bound.
inline void drawTransparent(graph::PassContext& pc, const TransparencyInputs& t, IndirectDrawLog* log) {
    VkCommandBuffer cmd = pc.commandBuffer();
    vkCmdBindIndexBuffer(cmd, pc.vkBuffer(t.scene.indices), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexedIndirect(cmd, pc.vkBuffer(t.sortedDraws), 0, t.drawCount, sizeof(VkDrawIndexedIndirectCommand));
    if (log) log->record(pc.passName(), t.drawCount);
}

}  // namespace idk::passes
