// transparency_draws.hpp: what every transparency rung (sorted, weighted blended, fixed layers) records the same
// way: the forward shading's reads and push block from the frame's buffers, and the one indirect draw of the BLEND draws.
#pragma once
#include "graph/render_graph.hpp"
#include "passes/indirect_draw.hpp"
#include "passes/passes.hpp"
#include "shared/shadow_types.h"
#include "shared/vxgi_types.h"

namespace idk::passes {

// The forward shading's reads (every rung declares the same).
inline void readTransparencyInputs(graph::PassBuilder& b, const TransparencyInputs& t) {
    constexpr VkPipelineStageFlags2 kVs = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    const SceneBuffers& s = t.scene;
    b.read(t.sortedDraws, graph::Access::IndirectRead);
    b.read(t.depth, graph::Access::StorageRead, kFs);
    b.read(t.environment, graph::Access::SampledRead, kFs);
    b.read(t.frame, graph::Access::StorageRead, kVs | kFs);
    readSceneMeshes(b, s);
    if (s.lights.valid()) b.read(s.lights, graph::Access::StorageRead, kFs);
    if (t.shadows.table.valid()) {
        b.read(t.shadows.table, graph::Access::StorageRead, kFs);
        for (graph::TextureHandle cube : t.shadows.cubes) b.read(cube, graph::Access::SampledRead, kFs);
    }
    if (t.vxgi.params.valid()) {  // --gi vxgi: the fragments trace cones through the directional volumes
        b.read(t.vxgi.params, graph::Access::StorageRead, kFs);
        for (graph::TextureHandle v : t.vxgi.volumes)
            if (v.valid()) b.read(v, graph::Access::SampledRead, kFs);
        b.read(t.vxgi.grid, graph::Access::SampledRead, kFs);
    }
}

inline gpu::TransparencyPush transparencyPush(graph::PassContext& pc, const TransparencyInputs& t) {
    const SceneBuffers& s = t.scene;
    gpu::TransparencyPush push{};
    push.frame = pc.buffer(t.frame).address;
    setSceneAddresses(push, pc, s);
    push.pointShadows = t.shadows.table.valid() ? pc.buffer(t.shadows.table).address : 0;
    push.depth = pc.texture(t.depth).storageIndex;
    push.vxgiCones = t.vxgi.params.valid() ? t.vxgi.paramsIndex : gpu::kNoVxgi;
    return push;
}

// The BLEND draws in the frame's order (t.sortedDraws), inside a begun rendering with the pipeline bound.
inline void drawTransparent(graph::PassContext& pc, const TransparencyInputs& t, IndirectDrawLog* log) {
    VkCommandBuffer cmd = pc.commandBuffer();
    vkCmdBindIndexBuffer(cmd, pc.vkBuffer(t.scene.indices), 0, VK_INDEX_TYPE_UINT32);
    drawAllIndexedIndirect(cmd, pc.vkBuffer(t.sortedDraws), t.drawCount);  // see passes/indirect_draw.hpp
    if (log) log->record(pc.passName(), t.drawCount);
}

}  // namespace idk::passes
