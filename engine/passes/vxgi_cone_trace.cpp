// vxgi_cone_trace.cpp: the voxel grid's anisotropic mip chain (six directional volumes) and the cone-tracing pass (shaders_glsl/vxgi/mip.comp.glsl,
// cone_trace.comp.glsl). Ports IDKEngine's Voxelizer mipmap step and ConeTracer.cs, at render resolution (the
// original's resolution too; a half-resolution trace with an edge-aware upsample is not done here).
#include "passes/vxgi_passes.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "shared/vxgi_types.h"

namespace idk::passes {

IndirectLightImages addConeTracePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const ConeTraceInputs& in) {
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    graph::TextureHandle grid = in.grid;
    std::array<graph::TextureHandle, 6> dirs = in.directions;
    for (uint32_t level = 1; level < in.directionLevels.size(); ++level) {
        gpu::VoxelMipPush push{};
        for (uint32_t d = 0; d < 6; ++d) {
            push.src[d] = in.directionLevels[level - 1][d];
            push.dst[d] = in.directionLevels[level][d];
        }
        push.dstSize = std::max(1u, in.box.size >> level);
        graph.addPass(
            "vxgi_mip " + std::to_string(level),
            // Levels are read and written through views the graph does not see: each directional volume is one
            // read-write resource, so consecutive levels get a full barrier between them.
            [&](graph::PassBuilder& b) {
                for (graph::TextureHandle& d : dirs) d = b.write(d, graph::Access::StorageReadWrite, kCs);
            },
            [&ctx, &shaders, push](graph::PassContext& pc) {
                VkCommandBuffer cmd = pc.commandBuffer();
                vk::ComputePipelineDesc desc;
                desc.shader = vk::ShaderId::vxgi_mip_comp;
                desc.pushBytes = sizeof(gpu::VoxelMipPush);
                desc.localSize = {gpu::kVoxelGroupSize, gpu::kVoxelGroupSize, gpu::kVoxelGroupSize};
                vk::bindPipeline(cmd, shaders.compute(desc));
                ctx.bindless().bind(cmd);
                vk::pushConstants(cmd, ctx, push);
                const uint32_t groups = vk::groupCount(push.dstSize, gpu::kVoxelGroupSize);
                vkCmdDispatch(cmd, groups, groups, groups);
            });
    }

    auto out = std::make_shared<IndirectLightImages>();
    const GBufferOutputs g = in.gbuffer;
    gpu::ConeTracePush base{};
    base.gridSampler = in.gridSampler;
    base.ringCones = in.ringCones;
    base.gridMin = in.box.gridMin;
    base.voxelSize = in.box.voxelSize;
    base.gridSize = in.box.size;
    base.maxLod = float(in.directionLevels.size() - 1);
    for (uint32_t d = 0; d < 6; ++d) base.directions[d] = in.directionSampled[d];
    base.grid = in.gridSampled;
    base.stepFactor = in.stepFactor;
    const graph::BufferHandle frame = in.frame;
    graph.addPass(
        "vxgi_cone_trace",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle t : {g.normal, g.material, g.depth}) b.read(t, graph::Access::StorageRead, kCs);
            b.read(grid, graph::Access::SampledRead, kCs);
            for (graph::TextureHandle d : dirs) b.read(d, graph::Access::SampledRead, kCs);
            b.read(in.environment, graph::Access::SampledRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            graph::TextureDesc desc;
            desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            out->diffuse = b.write(b.create("vxgi diffuse irradiance", desc), graph::Access::StorageWrite, kCs);
            out->specular = b.write(b.create("vxgi specular radiance", desc), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, g, frame, out, base](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::vxgi_cone_trace_comp;
            desc.pushBytes = sizeof(gpu::ConeTracePush);
            desc.localSize = {gpu::kConeGroupSize, gpu::kConeGroupSize, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::ConeTracePush push = base;
            push.frame = pc.buffer(frame).address;
            push.normal = pc.texture(g.normal).storageIndex;
            push.material = pc.texture(g.material).storageIndex;
            push.depth = pc.texture(g.depth).storageIndex;
            push.diffuse = pc.texture(out->diffuse).storageIndex;
            push.specular = pc.texture(out->specular).storageIndex;
            vk::pushConstants(cmd, ctx, push);
            VkExtent3D extent = pc.texture(out->diffuse).extent;
            vkCmdDispatch(cmd, vk::groupCount(extent.width, gpu::kConeGroupSize),
                          vk::groupCount(extent.height, gpu::kConeGroupSize), 1);
        });
    return *out;
}

}  // namespace idk::passes
