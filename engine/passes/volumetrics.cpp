// volumetrics.cpp: volumetric lighting as two compute passes: the ray march at 1/scale resolution into a transient
// RGBA16F image (volumetrics/march.comp), then the depth-aware upsample that composites it into the HDR image in
// place (volumetrics/upsample.comp). Ports IDKEngine's VolumetricLighting.Compute (reference 1.5 step 8; there the
// result is added in the tonemap pass and surfaces are not attenuated).
#include <memory>

#include "passes/passes.hpp"
#include "shared/volumetric_types.h"

namespace idk::passes {

graph::TextureHandle addVolumetricPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const VolumetricInputs& in, graph::TextureHandle hdr) {
    graph::TextureDesc lowDesc;
    lowDesc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    lowDesc.sizeMode = graph::SizeMode::Absolute;
    lowDesc.extent = {(in.width + in.push.scale - 1) / in.push.scale, (in.height + in.push.scale - 1) / in.push.scale, 1};
    auto low = std::make_shared<graph::TextureHandle>(graph.createTexture("volumetric light", lowDesc));
    auto written = std::make_shared<graph::TextureHandle>();
    auto inputs = std::make_shared<VolumetricInputs>(in);
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

    auto pushFor = [inputs](graph::PassContext& pc, graph::TextureHandle lowRes, graph::TextureHandle target) {
        gpu::VolumetricPush push = inputs->push;
        push.frame = pc.buffer(inputs->frame).address;
        const bool march = !target.valid();  // only the march reads the shadow table
        push.shadows = march && inputs->shadows.table.valid() ? pc.buffer(inputs->shadows.table).address : 0;
        push.depth = pc.texture(inputs->depth).storageIndex;
        push.lowRes = pc.texture(lowRes).storageIndex;
        push.target = target.valid() ? pc.texture(target).storageIndex : 0;
        return push;
    };
    graph.addPass(
        "volumetrics_march",
        [&](graph::PassBuilder& b) {
            b.read(in.frame, graph::Access::StorageRead, kCs);
            if (in.lights.valid()) b.read(in.lights, graph::Access::StorageRead, kCs);
            b.read(in.depth, graph::Access::StorageRead, kCs);
            if (in.shadows.table.valid()) {
                b.read(in.shadows.table, graph::Access::StorageRead, kCs);
                for (graph::TextureHandle t : in.shadows.cubes) b.read(t, graph::Access::SampledRead, kCs);
            }
            *low = b.write(*low, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, low, pushFor, lowDesc](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::volumetrics_march_comp;
            desc.pushBytes = sizeof(gpu::VolumetricPush);
            desc.localSize = {gpu::kVolumetricGroupSize, gpu::kVolumetricGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            vk::pushConstants(cmd, ctx, pushFor(pc, *low, {}));
            vkCmdDispatch(cmd, vk::groupCount(lowDesc.extent.width, gpu::kVolumetricGroupSize),
                          vk::groupCount(lowDesc.extent.height, gpu::kVolumetricGroupSize), 1);
        });
    graph.addPass(
        "volumetrics_upsample",
        [&](graph::PassBuilder& b) {
            b.read(in.frame, graph::Access::StorageRead, kCs);
            b.read(in.depth, graph::Access::StorageRead, kCs);
            b.read(*low, graph::Access::StorageRead, kCs);
            *written = b.write(hdr, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, low, written, pushFor, inputs](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::volumetrics_upsample_comp;
            desc.pushBytes = sizeof(gpu::VolumetricPush);
            desc.localSize = {gpu::kVolumetricGroupSize, gpu::kVolumetricGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            vk::pushConstants(cmd, ctx, pushFor(pc, *low, *written));
            vkCmdDispatch(cmd, vk::groupCount(inputs->width, gpu::kVolumetricGroupSize),
                          vk::groupCount(inputs->height, gpu::kVolumetricGroupSize), 1);
        });
    return *written;
}

}  // namespace idk::passes
