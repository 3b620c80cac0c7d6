// deferred_lighting.cpp: one compute dispatch (8x8 tiles) that shades every G-buffer pixel with geometry:
// glTF metallic-roughness BRDF per punctual light, environment ambient times occlusion, plus emission, written
// as linear radiance into an RGBA16F storage image. Ports IDKEngine's DeferredLighting pass (a fullscreen
// fragment shader there, ToScreen/vertex.glsl + DeferredLighting/fragment.glsl) with point-light cube shadows
// (passes/point_shadows.cpp); inside the VXGI grid the cone-traced light replaces the ambient (vxgi_ambient.glsl).
#include "passes/passes.hpp"

#include <memory>

#include "shared/deferred_types.h"
#include "shared/ssr_types.h"
#include "shared/vxgi_types.h"

namespace idk::passes {

graph::TextureHandle addDeferredLightingPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                             const GBufferOutputs& gbuffer, graph::BufferHandle frame,
                                             graph::BufferHandle lights, graph::TextureHandle environment,
                                             graph::TextureHandle target, const LightingInputs& in) {
    auto written = std::make_shared<graph::TextureHandle>();
    const GBufferOutputs g = gbuffer;
    graph.addPass(
        "deferred_lighting",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            for (graph::TextureHandle t : {g.albedo, g.normal, g.material, g.emissive, g.depth})
                b.read(t, graph::Access::StorageRead, kCs);
            if (g.layers.valid()) b.read(g.layers, graph::Access::StorageRead, kCs);
            if (g.layerSpill.valid()) b.read(g.layerSpill, graph::Access::StorageRead, kCs);
            b.read(environment, graph::Access::SampledRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            if (lights.valid()) b.read(lights, graph::Access::StorageRead, kCs);
            if (in.materials.valid()) b.read(in.materials, graph::Access::StorageRead, kCs);
            if (in.shadows.table.valid()) {
                b.read(in.shadows.table, graph::Access::StorageRead, kCs);
                for (graph::TextureHandle cube : in.shadows.cubes) b.read(cube, graph::Access::SampledRead, kCs);
                if (in.shadows.mask.valid()) b.read(in.shadows.mask, graph::Access::StorageRead, kCs);
            }
            if (in.vrsRates.valid()) b.read(in.vrsRates, graph::Access::StorageRead, kCs);
            if (in.ambientOcclusion.valid()) b.read(in.ambientOcclusion, graph::Access::StorageRead, kCs);
            if (in.indirect.diffuse.valid()) {
                b.read(in.indirect.diffuse, graph::Access::StorageRead, kCs);
                b.read(in.indirect.specular, graph::Access::StorageRead, kCs);
            }
            if (in.reflections.valid()) b.read(in.reflections, graph::Access::StorageRead, kCs);
            *written = b.write(target, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, g, frame, written, in](graph::PassContext& pc) {
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
            push.pointShadows = in.shadows.table.valid() ? pc.buffer(in.shadows.table).address : 0;
            push.materials = in.materials.valid() ? pc.buffer(in.materials).address : 0;
            push.vrsRates = in.vrsRates.valid() ? pc.buffer(in.vrsRates).address : 0;
            push.ambientOcclusion =
                in.ambientOcclusion.valid() ? pc.texture(in.ambientOcclusion).storageIndex : gpu::kLightingNoAo;
            push.vxgiDiffuse = in.indirect.diffuse.valid() ? pc.texture(in.indirect.diffuse).storageIndex : gpu::kNoVxgi;
            push.vxgiSpecular =
                in.indirect.specular.valid() ? pc.texture(in.indirect.specular).storageIndex : gpu::kNoVxgi;
            push.ssr = in.reflections.valid() ? pc.texture(in.reflections).storageIndex : gpu::kSsrNoImage;
            push.layers = g.layers.valid() ? pc.texture(g.layers).storageIndex : gpu::kLightingNoLayers;
            push.layerSpill = g.layerSpill.valid() ? pc.texture(g.layerSpill).storageIndex : gpu::kLightingNoLayers;
            vk::pushConstants(cmd, ctx, push);
            VkExtent3D extent = pc.texture(*written).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kLightingGroupSize),
                          vk::groupCount(extent.height, gpu::kLightingGroupSize), 1);
        });
    return *written;
}

}  // namespace idk::passes
