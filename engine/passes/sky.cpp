// sky.cpp: one compute dispatch that writes the environment's radiance into every background pixel
// (G-buffer depth == 1) of the HDR target, looking up the equirectangular map along each pixel's view ray.
// Ports IDKEngine's skybox step (SkyBox/vertex.glsl + fragment.glsl, a cube drawn with depth LEQUAL there).
// Runs after deferred_lighting, which leaves the background pixels untouched.
#include "passes/passes.hpp"

#include <memory>

#include "shared/deferred_types.h"

namespace idk::passes {

graph::TextureHandle addSkyPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                graph::TextureHandle depth, graph::BufferHandle frame, graph::TextureHandle environment,
                                graph::TextureHandle target, graph::BufferHandle vrsRates) {
    auto written = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "sky",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(depth, graph::Access::StorageRead, kCs);
            b.read(environment, graph::Access::SampledRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            if (vrsRates.valid()) b.read(vrsRates, graph::Access::StorageRead, kCs);
            *written = b.write(target, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, depth, frame, written, vrsRates](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::sky_sky_comp;
            desc.pushBytes = sizeof(gpu::SkyPush);
            desc.localSize = {gpu::kLightingGroupSize, gpu::kLightingGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::SkyPush push{};
            push.frame = pc.buffer(frame).address;
            push.depth = pc.texture(depth).storageIndex;
            push.target = pc.texture(*written).storageIndex;
            push.vrsRates = vrsRates.valid() ? pc.buffer(vrsRates).address : 0;
            vk::pushConstants(cmd, ctx, push);
            VkExtent3D extent = pc.texture(*written).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kLightingGroupSize),
                          vk::groupCount(extent.height, gpu::kLightingGroupSize), 1);
        });
    return *written;
}

}  // namespace idk::passes
