// vxgi_cone_trace.cpp: the voxel grid's anisotropic mip chain (six directional volumes) and the cone-tracing pass (shaders_glsl/vxgi/mip.comp.glsl,
// cone_trace.comp.glsl). Ports IDKEngine's Voxelizer mipmap step and ConeTracer.cs, at render resolution or at half
// of it (one G-buffer pixel per 2x2 block; passes/vxgi_upsample.cpp brings it back to render resolution).
#include "passes/vxgi_passes.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <string>

#include "shared/vxgi_types.h"

namespace idk::passes {

namespace {

// "vxgi_cone_trace": traces into new images (`fix` null; half or render resolution per in.halfResolution) or, as
// "vxgi_cone_trace_fixup", the pixels of `fix` (render resolution) whose diffuse alpha the upsample set to -1.
IndirectLightImages addTracePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                 const ConeTraceInputs& in, const gpu::ConeTracePush& base,
                                 const std::vector<graph::TextureHandle>& volumes, const IndirectLightImages* fix) {
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    auto out = std::make_shared<IndirectLightImages>();
    const GBufferOutputs g = in.gbuffer;
    const graph::BufferHandle frame = in.frame;
    graph.addPass(
        fix ? "vxgi_cone_trace_fixup" : "vxgi_cone_trace",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle t : {g.normal, g.material, g.depth}) b.read(t, graph::Access::StorageRead, kCs);
            for (graph::TextureHandle v : volumes) b.read(v, graph::Access::SampledRead, kCs);
            b.read(in.environment, graph::Access::SampledRead, kCs);
            b.read(frame, graph::Access::StorageRead, kCs);
            if (fix) {
                out->diffuse = b.write(fix->diffuse, graph::Access::StorageReadWrite, kCs);
                out->specular = b.write(fix->specular, graph::Access::StorageReadWrite, kCs);
                return;
            }
            graph::TextureDesc desc;
            desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            std::string suffix;
            if (in.halfResolution) {  // the shader reads the resolution from its outputs' size
                const VkExtent2D e = graph.relativeExtent();
                desc.sizeMode = graph::SizeMode::Absolute;
                desc.extent = {(e.width + 1) / 2, (e.height + 1) / 2, 1};
                suffix = " (half resolution)";
            }
            out->diffuse =
                b.write(b.create("vxgi diffuse irradiance" + suffix, desc), graph::Access::StorageWrite, kCs);
            out->specular =
                b.write(b.create("vxgi specular radiance" + suffix, desc), graph::Access::StorageWrite, kCs);
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

}  // namespace

IndirectLightImages addConeTracePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const ConeTraceInputs& in) {
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    graph::TextureHandle grid = in.grid;
    VxgiDirectionHandles dirs = in.directions;
    for (uint32_t level = 1; level < in.directionLevels.size(); ++level) {
        gpu::VoxelMipPush push{};
        for (uint32_t d = 0; d < 6; ++d) {
            push.src[d] = in.directionLevels[level - 1][d];
            push.dst[d] = in.directionLevels[level][d];
            push.srcOpacity[d] = in.directionLevels[level - 1][6 + d];
            push.dstOpacity[d] = in.directionLevels[level][6 + d];
        }
        push.dstSize = std::max(1u, in.box.size >> level);
        push.cells = gpu::kVoxelNoCells;  // level 1: the mask's index, known when the pass runs
        const graph::TextureHandle cells = level == 1 ? in.cells : graph::TextureHandle{};
        graph.addPass(
            "vxgi_mip " + std::to_string(level),
            // Levels are read and written through views the graph does not see: each directional volume is one
            // read-write resource, so consecutive levels get a full barrier between them.
            [&](graph::PassBuilder& b) {
                if (cells.valid()) b.read(cells, graph::Access::StorageRead, kCs);
                for (graph::TextureHandle& d : dirs)
                    if (d.valid()) d = b.write(d, graph::Access::StorageReadWrite, kCs);
            },
            [&ctx, &shaders, push, cells](graph::PassContext& pc) mutable {
                VkCommandBuffer cmd = pc.commandBuffer();
                if (cells.valid()) push.cells = pc.texture(cells).storageIndex;
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

    if (in.mipped) *in.mipped = dirs;
    gpu::ConeTracePush base{};
    base.gridSampler = in.gridSampler;
    base.ringCones = in.ringCones;
    base.footprintCones = in.footprintCones;
    base.gridMin = in.box.gridMin;
    base.voxelSize = in.box.voxelSize;
    base.gridSize = in.box.size;
    base.maxLod = float(in.directionLevels.size() - 1);
    for (uint32_t d = 0; d < 6; ++d) {
        base.directions[d] = in.directionSampled[d];
        base.opacity[d] = in.directionSampled[6 + d];
    }
    base.grid = in.gridSampled;
    base.stepFactor = in.stepFactor;
    std::vector<graph::TextureHandle> volumes = {grid};
    for (graph::TextureHandle d : dirs)
        if (d.valid()) volumes.push_back(d);
    IndirectLightImages traced = addTracePass(graph, ctx, shaders, in, base, volumes, nullptr);
    if (!in.halfResolution) return traced;
    // Half resolution: the edge-aware upsample, then full-resolution traces of the pixels it found no sample of
    // their own surface for (alpha -1: features thinner than the sample spacing, silhouettes the quincunx missed).
    IndirectLightImages full = addVxgiUpsamplePass(graph, ctx, shaders, {in.gbuffer, in.frame, traced, in.box});
    base.unmatchedOnly = 1;
    return addTracePass(graph, ctx, shaders, in, base, volumes, &full);
}

}  // namespace idk::passes
