// cull.cpp: GPU culling for one view: "cull_reset" zeroes the counters, "cull" (culling/cull_instances.comp.glsl,
// one dispatch, one invocation per scene draw) writes the compacted VkDrawIndexedIndirectCommands (firstInstance =
// instance) and the counters whose first word vkCmdDrawIndexedIndirectCount reads. Ports IDKEngine's culling dispatch
// in RasterPipeline (MeshCulling/Camera/Cull/compute.glsl) without its per-pass CPU re-upload of the commands.
#include "passes/culling.hpp"

#include <array>
#include <memory>

#include "vk/bindless.hpp"

namespace idk::passes {

void recordCull(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, const gpu::CullPush& push) {
    vk::ComputePipelineDesc pipeline;
    pipeline.shader = vk::ShaderId::culling_cull_instances_comp;
    pipeline.pushBytes = sizeof(gpu::CullPush);
    pipeline.localSize = {gpu::kCullGroupSize, 1, 1};
    vk::bindPipeline(cmd, shaders.compute(pipeline));
    ctx.bindless().bind(cmd);
    vk::pushConstants(cmd, ctx, push);
    vkCmdDispatch(cmd, vk::groupCount(push.drawCount, gpu::kCullGroupSize), 1, 1);
}

CulledDraws addCullPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                        const CullInputs& inputs, const std::string& viewName) {
    const CullInputs in = inputs;
    auto out = std::make_shared<CulledDraws>();
    out->maxDraws = in.drawCount;
    out->meshTasks = in.meshTasks;
    out->draws = in.draws;
    out->views = in.views;
    out->view = in.view;
    out->phase = in.phase;
    out->pyramid = in.pyramid;
    graph::BufferDesc desc;
    desc.size = sizeof(gpu::GpuCullCounters);
    graph::BufferHandle counters = graph.createBuffer(viewName + " cull counters", desc);
    desc.size = VkDeviceSize(in.drawCount) *
                (in.meshTasks ? sizeof(gpu::MeshTaskCommand) : sizeof(VkDrawIndexedIndirectCommand));
    graph::BufferHandle commands = graph.createBuffer(viewName + " culled commands", desc);

    graph::BufferHandle meshCounters, drawInstance;
    if (in.meshTasks) {
        desc.size = sizeof(gpu::GpuCullCounters);
        meshCounters = graph.createBuffer(viewName + " task counters", desc);
        desc.size = VkDeviceSize(in.drawCount) * sizeof(uint32_t);
        drawInstance = graph.createBuffer(viewName + " culled instances", desc);
    }
    auto zeroed = std::make_shared<std::array<graph::BufferHandle, 2>>();
    const std::string phase = in.phase == gpu::kCullEarly ? "_early" : in.phase == gpu::kCullLate ? "_late" : "";
    graph.addPass(
        "cull_reset" + phase,
        [&](graph::PassBuilder& b) {
            (*zeroed)[0] = b.write(counters, graph::Access::TransferDst);
            if (meshCounters.valid()) (*zeroed)[1] = b.write(meshCounters, graph::Access::TransferDst);
        },
        [zeroed](graph::PassContext& pc) {
            for (graph::BufferHandle h : *zeroed)
                if (h.valid()) vkCmdFillBuffer(pc.commandBuffer(), pc.vkBuffer(h), 0, sizeof(gpu::GpuCullCounters), 0);
        });
    out->meshCounters = (*zeroed)[1];
    graph.addPass(
        "cull" + phase,
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(in.instances, graph::Access::StorageRead, kCs);
            b.read(in.draws, graph::Access::StorageRead, kCs);
            b.read(in.views, graph::Access::StorageRead, kCs);
            if (in.phase == gpu::kCullEarly) b.read(in.visibility, graph::Access::StorageRead, kCs);
            if (in.phase == gpu::kCullLate) {
                out->visibility = b.write(in.visibility, graph::Access::StorageReadWrite, kCs);
                b.read(in.pyramid, graph::Access::StorageRead, kCs);
            }
            out->counters = b.write((*zeroed)[0], graph::Access::StorageReadWrite, kCs);
            out->commands = b.write(commands, graph::Access::StorageWrite, kCs);
            if (drawInstance.valid()) out->drawInstance = b.write(drawInstance, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, in, out](graph::PassContext& pc) {
            gpu::CullPush push{};
            push.instances = pc.buffer(in.instances).address;
            push.draws = pc.buffer(in.draws).address;
            push.views = pc.buffer(in.views).address;
            push.commands = pc.buffer(out->commands).address;
            push.counters = pc.buffer(out->counters).address;
            push.drawCount = in.drawCount;
            push.view = in.view;
            push.phase = in.phase;
            push.meshTasks = in.meshTasks ? 1u : 0u;
            if (in.meshTasks) push.drawInstance = pc.buffer(out->drawInstance).address;
            if (in.phase == gpu::kCullEarly) push.visibility = pc.buffer(in.visibility).address;
            if (in.phase == gpu::kCullLate) {
                push.visibility = pc.buffer(out->visibility).address;
                push.pyramid = pc.buffer(in.pyramid).address;
            }
            recordCull(pc.commandBuffer(), ctx, shaders, push);
        });
    return *out;
}

void addCullStatsCopyPass(graph::RenderGraph& graph, const std::vector<graph::BufferHandle>& counters,
                          graph::BufferHandle hostBuffer) {
    auto written = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "cull_stats",
        [&](graph::PassBuilder& b) {
            for (graph::BufferHandle c : counters) b.read(c, graph::Access::TransferSrc);
            *written = b.write(hostBuffer, graph::Access::TransferDst);
            b.sideEffect();  // read by the CPU after the frame's fence
        },
        [counters, written](graph::PassContext& pc) {
            for (size_t i = 0; i < counters.size(); ++i) {
                VkBufferCopy region{0, i * sizeof(gpu::GpuCullCounters), sizeof(gpu::GpuCullCounters)};
                vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(counters[i]), pc.vkBuffer(*written), 1, &region);
            }
        });
}

}  // namespace idk::passes
