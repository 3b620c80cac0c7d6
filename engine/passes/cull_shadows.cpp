// cull_shadows.cpp: GPU culling of the point-shadow cube faces. "cull_reset_shadows" zeroes one GpuCullCounters per
// face view; "cull_shadows" runs the culling kernel (culling/cull_instances.comp.glsl, frustum phase) once per face
// view, each dispatch writing its own slice of compacted VkDrawIndexedIndirectCommands and its own counters, which
// the point_shadows pass draws with vkCmdDrawIndexedIndirectCount face by face. No Hi-Z: a shadow face has no depth
// of its own before it is drawn. Ports the shadow use of IDKEngine's culling pass (reference 2.12: there culled on
// the CPU per face).
#include <memory>

#include "passes/culling.hpp"

namespace idk::passes {

ShadowCulledDraws addShadowCullPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    const CullInputs& inputs, uint32_t viewCount) {
    const CullInputs in = inputs;
    auto out = std::make_shared<ShadowCulledDraws>();
    out->maxDraws = in.drawCount;
    out->viewCount = viewCount;
    graph::BufferDesc desc;
    desc.size = VkDeviceSize(viewCount) * sizeof(gpu::GpuCullCounters);
    graph::BufferHandle counters = graph.createBuffer("shadow cull counters", desc);
    desc.size = VkDeviceSize(viewCount) * in.drawCount * sizeof(VkDrawIndexedIndirectCommand);
    graph::BufferHandle commands = graph.createBuffer("shadow culled commands", desc);
    auto zeroed = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "cull_reset_shadows", [&](graph::PassBuilder& b) { *zeroed = b.write(counters, graph::Access::TransferDst); },
        [zeroed, viewCount](graph::PassContext& pc) {
            vkCmdFillBuffer(pc.commandBuffer(), pc.vkBuffer(*zeroed), 0, viewCount * sizeof(gpu::GpuCullCounters), 0);
        });
    graph.addPass(
        "cull_shadows",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(in.instances, graph::Access::StorageRead, kCs);
            b.read(in.draws, graph::Access::StorageRead, kCs);
            b.read(in.views, graph::Access::StorageRead, kCs);
            out->counters = b.write(*zeroed, graph::Access::StorageReadWrite, kCs);
            out->commands = b.write(commands, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, in, out](graph::PassContext& pc) {
            gpu::CullPush push{};
            push.instances = pc.buffer(in.instances).address;
            push.draws = pc.buffer(in.draws).address;
            push.views = pc.buffer(in.views).address;
            push.drawCount = in.drawCount;
            push.phase = gpu::kCullFrustum;
            const VkDeviceAddress commands = pc.buffer(out->commands).address;
            const VkDeviceAddress counters = pc.buffer(out->counters).address;
            // One dispatch per view into disjoint slices: no barrier between them.
            for (uint32_t v = 0; v < out->viewCount; ++v) {
                push.view = v;
                push.commands = commands + out->commandOffset(v);
                push.counters = counters + out->countOffset(v);
                recordCull(pc.commandBuffer(), ctx, shaders, push);
            }
        });
    return *out;
}

}  // namespace idk::passes
