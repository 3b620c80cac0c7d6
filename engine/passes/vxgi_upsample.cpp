// vxgi_upsample.cpp: the edge-aware upsample of the half-resolution VXGI cone trace (shaders_glsl/vxgi/
// upsample.comp.glsl: depth-plane and normal weighted, so indirect light does not cross silhouettes). No IDKEngine
// counterpart: its ConeTracer writes at render resolution (idkengine-internals.md 2.4); issue 11 asks for this.
#include "passes/vxgi_passes.hpp"

#include <memory>

#include "shared/vxgi_types.h"
#include "shared/vxgi_upsample_types.h"

namespace idk::passes {

IndirectLightImages addVxgiUpsamplePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                        const VxgiUpsampleInputs& in) {
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    auto out = std::make_shared<IndirectLightImages>();
    const GBufferOutputs g = in.gbuffer;
    const IndirectLightImages traced = in.traced;
    const graph::BufferHandle frame = in.frame;
    gpu::VxgiUpsamplePush base{};
    base.gridMin = in.box.gridMin;
    base.voxelSize = in.box.voxelSize;
    base.gridSize = in.box.size;
    graph.addPass(
        "vxgi_upsample",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle t : {g.normal, g.depth, traced.diffuse, traced.specular})
                b.read(t, graph::Access::StorageRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            graph::TextureDesc desc;  // render resolution (relative to the G-buffer's extent)
            desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            out->diffuse = b.write(b.create("vxgi diffuse irradiance", desc), graph::Access::StorageWrite, kCs);
            out->specular = b.write(b.create("vxgi specular radiance", desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, g, traced, frame, out, base](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vxgi_upsample_comp;
            desc.pushBytes = sizeof(gpu::VxgiUpsamplePush);
            desc.localSize = {gpu::kConeGroupSize, gpu::kConeGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::VxgiUpsamplePush push = base;
            push.frame = pc.buffer(frame).address;
            push.normal = pc.texture(g.normal).storageIndex;
            push.depth = pc.texture(g.depth).storageIndex;
            push.halfDiffuse = pc.texture(traced.diffuse).storageIndex;
            push.halfSpecular = pc.texture(traced.specular).storageIndex;
            push.diffuse = pc.texture(out->diffuse).storageIndex;
            push.specular = pc.texture(out->specular).storageIndex;
            vk::pushConstants(cmd, ctx, push);
            const VkExtent3D extent = pc.texture(out->diffuse).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kConeGroupSize),
                          vk::groupCount(extent.height, gpu::kConeGroupSize), 1);
        });
    return *out;
}

}  // namespace idk::passes
