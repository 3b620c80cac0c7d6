// vrs_camera_motion.cpp: per-pixel camera motion (vrs/camera_motion.comp.glsl) into a transient vec2 buffer: the
// VRS classifier's speed input until issue 12's motion vectors (object and skinned motion too) replace it.
#include <memory>

#include "passes/vrs_passes.hpp"

namespace idk::passes {

graph::BufferHandle addVrsCameraMotionPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                           graph::TextureHandle depth, const glm::mat4& currentToPrevious) {
    auto written = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "vrs_camera_motion",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(depth, graph::Access::StorageRead, kCs);
            const VkExtent2D size = graph.relativeExtent();
            graph::BufferDesc desc;
            desc.size = VkDeviceSize(size.width) * size.height * sizeof(glm::vec2);
            *written = b.write(graph.createBuffer("vrs velocity", desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, depth, written, currentToPrevious](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vrs_camera_motion_comp;
            desc.pushBytes = sizeof(gpu::VrsMotionPush);
            desc.localSize = {8, 8, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            VkExtent3D extent = pc.texture(depth).extent;
            gpu::VrsMotionPush push{};
            push.currentToPrevious = currentToPrevious;
            push.velocity = pc.buffer(*written).address;
            push.depth = pc.texture(depth).storageIndex;
            push.width = extent.width;
            push.height = extent.height;
            vk::pushConstants(cmd, ctx, push);
            vkCmdDispatch(cmd, vk::groupCount(extent.width, 8), vk::groupCount(extent.height, 8), 1);
        });
    return *written;
}

}  // namespace idk::passes
