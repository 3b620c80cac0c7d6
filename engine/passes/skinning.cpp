// skinning.cpp: animation as graph passes (render/gpu_animation.hpp decides when each runs). pose_upload copies
// this frame's instance transforms from the host-visible pose buffer into the instance buffer (ordered by the graph
// after earlier frames' draws: no stall); skinning is one dispatch, one invocation per deformed vertex (morph, then
// 4-joint skinning) into the vertices' deformed copies. Ports IDKEngine's ModelManager.Update mesh-transform
// upload and Skinning/compute.glsl (reference 1.5 step 5).
#include "passes/passes.hpp"

#include <memory>

namespace idk::passes {
namespace {

graph::BufferHandle importBuffer(graph::RenderGraph& graph, const char* name, const vk::Buffer* buffer) {
    if (!buffer || !*buffer) return {};
    graph::PhysicalBuffer p;
    p.buffer = buffer->buffer;
    p.size = buffer->size;
    p.address = buffer->address;
    // No earlier GPU access to wait for: the static buffers were uploaded at load (that upload ends with a full
    // barrier); the pose slot was written by the host, which this frame's queue submission makes visible.
    return graph.importBuffer(name, p, graph::ResourceState{});
}

// Declared resources: pose (TransferSrc), instances (TransferDst -> new version).
graph::BufferHandle addPoseUploadPass(graph::RenderGraph& graph, graph::BufferHandle pose,
                                      graph::BufferHandle instances, VkDeviceSize bytes) {
    auto written = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "pose_upload",
        [&](graph::PassBuilder& b) {
            b.read(pose, graph::Access::TransferSrc);
            *written = b.write(instances, graph::Access::TransferDst);
        },
        [pose, written, bytes](graph::PassContext& pc) {
            VkBufferCopy region{0, 0, bytes};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(pose), pc.vkBuffer(*written), 1, &region);
        });
    return *written;
}

struct SkinningInputs {
    graph::BufferHandle jobs, influences, deltas, pose;  // influences/deltas invalid when nothing uses them
    VkDeviceSize jointsOffset = AnimationFrame::kAbsent, weightsOffset = AnimationFrame::kAbsent;
    uint32_t jobCount = 0, threadCount = 0;
};

// Declared resources (compute stage): jobs, pose, [influences], [deltas] StorageRead; vertices StorageReadWrite
// (the rest-pose range is read, the deformed copies written) -> new version, which the draws then read.
graph::BufferHandle addSkinningPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    const SkinningInputs& inputs, graph::BufferHandle vertices) {
    auto written = std::make_shared<graph::BufferHandle>();
    const SkinningInputs in = inputs;
    graph.addPass(
        "skinning",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(in.jobs, graph::Access::StorageRead, kCs);
            b.read(in.pose, graph::Access::StorageRead, kCs);
            if (in.influences.valid()) b.read(in.influences, graph::Access::StorageRead, kCs);
            if (in.deltas.valid()) b.read(in.deltas, graph::Access::StorageRead, kCs);
            *written = b.write(vertices, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, in, written](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::skinning_skinning_comp;
            desc.pushBytes = sizeof(gpu::SkinningPush);
            desc.localSize = {gpu::kSkinningGroupSize, 1, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            const VkDeviceAddress pose = pc.buffer(in.pose).address;
            gpu::SkinningPush push{};
            push.vertices = pc.buffer(*written).address;
            push.jobs = pc.buffer(in.jobs).address;
            push.influences = in.influences.valid() ? pc.buffer(in.influences).address : 0;
            push.deltas = in.deltas.valid() ? pc.buffer(in.deltas).address : 0;
            push.jointMatrices = in.jointsOffset != AnimationFrame::kAbsent ? pose + in.jointsOffset : 0;
            push.weights = in.weightsOffset != AnimationFrame::kAbsent ? pose + in.weightsOffset : 0;
            push.jobCount = in.jobCount;
            push.threadCount = in.threadCount;
            vk::pushConstants(cmd, ctx, push);
            vkCmdDispatch(cmd, vk::groupCount(in.threadCount, gpu::kSkinningGroupSize), 1, 1);
        });
    return *written;
}

}  // namespace

void addAnimationPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                        const AnimationFrame& frame, SceneBuffers& scene) {
    const bool upload = frame.instanceBytes > 0 && scene.instances.valid();
    const bool deform = frame.deform && frame.jobCount > 0 && scene.vertices.valid();
    if (!upload && !deform) return;
    graph::BufferHandle pose = importBuffer(graph, "animation pose", frame.pose);
    if (upload) scene.instances = addPoseUploadPass(graph, pose, scene.instances, frame.instanceBytes);
    if (!deform) return;
    SkinningInputs in;
    in.jobs = importBuffer(graph, "skinning jobs", frame.jobs);
    in.influences = importBuffer(graph, "skin influences", frame.influences);
    in.deltas = importBuffer(graph, "morph deltas", frame.deltas);
    in.pose = pose;
    in.jointsOffset = frame.jointsOffset;
    in.weightsOffset = frame.weightsOffset;
    in.jobCount = frame.jobCount;
    in.threadCount = frame.threadCount;
    scene.vertices = addSkinningPass(graph, ctx, shaders, in, scene.vertices);
}

}  // namespace idk::passes
