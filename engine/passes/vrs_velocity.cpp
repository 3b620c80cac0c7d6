// vrs_velocity.cpp: the VRS classifier's per-pixel velocity (vrs/velocity.comp.glsl) into a transient vec2 buffer:
// the temporal motion vectors (instances, skinning, morphing, camera; passes/motion_vectors.cpp) where the G-buffer
// has a surface, the camera's reprojection on the background.
#include <memory>

#include "passes/vrs_passes.hpp"

namespace idk::passes {

graph::BufferHandle addVrsVelocityPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       graph::BufferHandle temporal, graph::TextureHandle motion,
                                       graph::TextureHandle depth) {
    auto written = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "vrs_velocity",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(temporal, graph::Access::StorageRead, kCs);
            b.read(motion, graph::Access::StorageRead, kCs);
            b.read(depth, graph::Access::StorageRead, kCs);
            const VkExtent2D size = graph.relativeExtent();
            graph::BufferDesc desc;
            desc.size = VkDeviceSize(size.width) * size.height * sizeof(glm::vec2);
            *written = b.write(graph.createBuffer("vrs velocity", desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, temporal, motion, depth, written](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vrs_velocity_comp;
            desc.pushBytes = sizeof(gpu::VrsVelocityPush);
            desc.localSize = {8, 8, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            const VkExtent3D extent = pc.texture(depth).extent;
            gpu::VrsVelocityPush push{};
            push.temporal = pc.buffer(temporal).address;
            push.velocity = pc.buffer(*written).address;
            push.motion = pc.texture(motion).storageIndex;
            push.depth = pc.texture(depth).storageIndex;
            push.width = extent.width;
            push.height = extent.height;
            vk::pushConstants(cmd, ctx, push);
            vkCmdDispatch(cmd, vk::groupCount(extent.width, 8), vk::groupCount(extent.height, 8), 1);
        });
    return *written;
}

}  // namespace idk::passes
