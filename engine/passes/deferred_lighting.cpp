// deferred_lighting.cpp: one compute dispatch (8x8 tiles) that shades every G-buffer pixel with geometry:
// glTF metallic-roughness BRDF per punctual light, environment ambient times occlusion, plus emission, written
// as linear radiance into an RGBA16F storage image. Ports IDKEngine's DeferredLighting pass (a fullscreen
// fragment shader there, ToScreen/vertex.glsl + DeferredLighting/fragment.glsl) with point-light cube shadows
// (passes/point_shadows.cpp); GI comes later.
#include "passes/passes.hpp"

#include <memory>

#include "shared/deferred_types.h"

namespace idk::passes {

graph::TextureHandle addDeferredLightingPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                             const GBufferOutputs& gbuffer, graph::BufferHandle frame,
                                             graph::BufferHandle lights, graph::TextureHandle environment,
                                             graph::TextureHandle target, const PointShadowOutputs& shadows) {
    auto written = std::make_shared<graph::TextureHandle>();
    const GBufferOutputs g = gbuffer;
    graph.addPass(
        "deferred_lighting",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            for (graph::TextureHandle t : {g.albedo, g.normal, g.material, g.emissive, g.depth})
                b.read(t, graph::Access::StorageRead, kCs);
            b.read(environment, graph::Access::SampledRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            if (lights.valid()) b.read(lights, graph::Access::StorageRead, kCs);
            if (shadows.table.valid()) {
                b.read(shadows.table, graph::Access::StorageRead, kCs);
                for (graph::TextureHandle cube : shadows.cubes) b.read(cube, graph::Access::SampledRead, kCs);
                if (shadows.mask.valid()) b.read(shadows.mask, graph::Access::StorageRead, kCs);
            }
            *written = b.write(target, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, g, frame, written, table = shadows.table](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::deferred_lighting_lighting_comp;
            desc.pushBytes = sizeof(gpu::LightingPush);
            desc.localSize = {gpu::kLightingGroupSize, gpu::kLightingGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::LightingPush push{};
            push.frame = pc.buffer(frame).address;
            push.albedo = pc.texture(g.albedo).storageIndex;
            push.normal = pc.texture(g.normal).storageIndex;
            push.material = pc.texture(g.material).storageIndex;
            push.emissive = pc.texture(g.emissive).storageIndex;
            push.depth = pc.texture(g.depth).storageIndex;
            push.target = pc.texture(*written).storageIndex;
            push.pointShadows = table.valid() ? pc.buffer(table).address : 0;
            vk::pushConstants(cmd, ctx, push);
            VkExtent3D extent = pc.texture(*written).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kLightingGroupSize),
                          vk::groupCount(extent.height, gpu::kLightingGroupSize), 1);
        });
    return *written;
}

}  // namespace idk::passes
