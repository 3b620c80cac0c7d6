// rt_shadows.cpp: ray-traced shadows after the G-buffer: one compute dispatch (8x8 pixels x shadowed lights)
// tracing one shadow ray per pixel and light along the "ray traversal" ladder (rt_shadows/mask_rq: VK_KHR_ray_query;
// rt_shadows/mask_bvh: our BVH), into a float mask per light (with a light radius: several rays per pixel over the
// sphere, then an edge-aware spatial filter, rt_shadows/denoise); then the shadow table whose entries point the
// lighting at the mask (include/rt_shadows.glsl). Ports IDKEngine's ShadowsRayTraced pass (reference 2.12; there
// R8 images per light: a real GPU would want 8 bits per light here too, lavapipe does not care).
#include <algorithm>
#include <cstring>
#include <memory>

#include "passes/passes.hpp"
#include "shared/deferred_types.h"
#include "shared/pt_wavefront.h"
#include "shared/rt_shadow_types.h"
#include "shared/shadow_types.h"

namespace idk::passes {

PointShadowOutputs addRtShadowPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                     const RtShadowInputs& in, uint32_t width, uint32_t height) {
    const uint32_t slots = uint32_t(in.casters.size());
    graph::BufferDesc maskDesc;
    maskDesc.size = size_t(slots) * width * height * sizeof(float);
    auto out = std::make_shared<PointShadowOutputs>();
    out->mask = graph.createBuffer("rt shadow mask", maskDesc);
    auto inputs = std::make_shared<RtShadowInputs>(in);
    auto traced = std::make_shared<graph::BufferHandle>();  // this pass's mask (out->mask moves on when filtered)
    graph.addPass(
        "rt_shadows",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(in.frame, graph::Access::StorageRead, kCs);
            if (in.lights.valid()) b.read(in.lights, graph::Access::StorageRead, kCs);
            b.read(in.depth, graph::Access::StorageRead, kCs);
            b.read(in.normal, graph::Access::StorageRead, kCs);
            out->mask = b.write(out->mask, graph::Access::StorageWrite, kCs);
            *traced = out->mask;
        },
        [&ctx, &shaders, inputs, traced, width, height, slots](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            const RtShadowInputs& s = *inputs;
            vk::ComputePipelineDesc desc;
            desc.shader = s.rayQuery ? vk::ShaderId::rt_shadows_mask_rq_comp : vk::ShaderId::rt_shadows_mask_bvh_comp;
            desc.pushBytes = sizeof(gpu::RtShadowPush);
            desc.localSize = {gpu::kRtShadowGroupSize, gpu::kRtShadowGroupSize, 1};
            desc.spec = {{gpu::kSpecPtHasAlpha, s.hasAlpha ? 1u : 0u},
                         {gpu::kSpecPtStackSize, std::max(s.blasStack, 1u)},
                         {gpu::kSpecPtTlasStackSize, std::max(s.tlasStack, 1u)}};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            gpu::RtShadowPush push{};
            push.frame = pc.buffer(s.frame).address;
            push.scene = s.sceneDesc;
            push.mask = pc.buffer(*traced).address;
            push.depth = pc.texture(s.depth).storageIndex;
            push.normal = pc.texture(s.normal).storageIndex;
            push.casterCount = slots;
            for (uint32_t i = 0; i < slots; ++i) push.casters[i] = s.casters[i];
            push.lightRadius = s.lightRadius;
            push.softRays = s.softRays;
            vk::pushConstants(cmd, ctx, push);
            vkCmdDispatch(cmd, vk::groupCount(width, gpu::kRtShadowGroupSize),
                          vk::groupCount(height, gpu::kRtShadowGroupSize), slots);
        });

    // Soft shadows (a light radius): the stochastic estimate filtered along the surfaces (rt_shadows/denoise).
    if (in.lightRadius > 0.0f) {
        auto noisy = traced;
        out->mask = graph.createBuffer("rt shadow mask filtered", maskDesc);
        graph.addPass(
            "rt_shadow_denoise",
            [&](graph::PassBuilder& b) {
                constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
                b.read(in.frame, graph::Access::StorageRead, kCs);
                b.read(in.depth, graph::Access::StorageRead, kCs);
                b.read(in.normal, graph::Access::StorageRead, kCs);
                b.read(*noisy, graph::Access::StorageRead, kCs);
                out->mask = b.write(out->mask, graph::Access::StorageWrite, kCs);
            },
            [&ctx, &shaders, inputs, out, noisy, width, height, slots](graph::PassContext& pc) {
                VkCommandBuffer cmd = pc.commandBuffer();
                vk::ComputePipelineDesc desc;
                desc.shader = vk::ShaderId::rt_shadows_denoise_comp;
                desc.pushBytes = sizeof(gpu::RtShadowDenoisePush);
                desc.localSize = {gpu::kRtShadowGroupSize, gpu::kRtShadowGroupSize, 1};
                vk::bindPipeline(cmd, shaders.compute(desc));
                ctx.bindless().bind(cmd);
                gpu::RtShadowDenoisePush push{};
                push.frame = pc.buffer(inputs->frame).address;
                push.noisy = pc.buffer(*noisy).address;
                push.filtered = pc.buffer(out->mask).address;
                push.depth = pc.texture(inputs->depth).storageIndex;
                push.normal = pc.texture(inputs->normal).storageIndex;
                push.slots = slots;
                push.rays = inputs->softRays;
                vk::pushConstants(cmd, ctx, push);
                vkCmdDispatch(cmd, vk::groupCount(width, gpu::kRtShadowGroupSize),
                              vk::groupCount(height, gpu::kRtShadowGroupSize), slots);
            });
    }

    // The table: kNoShadow for every light, kRayTracedShadow + a GpuRtShadowMask record for each shadowed one. The
    // mask's address exists only once the graph has placed it, so the records are completed when the pass runs.
    graph::BufferDesc tableDesc;
    tableDesc.size = size_t(in.lightCount) * sizeof(gpu::GpuPointShadow) + slots * sizeof(gpu::GpuRtShadowMask);
    out->table = graph.createBuffer("shadow table", tableDesc);
    graph.addPass(
        "rt_shadow_table",
        [&](graph::PassBuilder& b) {
            b.read(out->mask, graph::Access::StorageRead, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);  // its address
            out->table = b.write(out->table, graph::Access::TransferDst);
        },
        [inputs, out, width, height, slots](graph::PassContext& pc) {
            const RtShadowInputs& s = *inputs;
            std::vector<gpu::GpuPointShadow> entries(s.lightCount);
            for (gpu::GpuPointShadow& e : entries) e.cube = gpu::kNoShadow;
            std::vector<gpu::GpuRtShadowMask> records(slots);
            for (uint32_t i = 0; i < slots; ++i) {
                gpu::GpuPointShadow& e = entries[s.casters[i]];
                e.cube = gpu::kRayTracedShadow;
                e.mapOffset = uint32_t(entries.size() * sizeof(gpu::GpuPointShadow) + i * sizeof(gpu::GpuRtShadowMask));
                records[i] = {pc.buffer(out->mask).address, width, height, i, 0};
            }
            std::vector<uint8_t> bytes(entries.size() * sizeof(gpu::GpuPointShadow) +
                                       records.size() * sizeof(gpu::GpuRtShadowMask));
            std::memcpy(bytes.data(), entries.data(), entries.size() * sizeof(gpu::GpuPointShadow));
            std::memcpy(bytes.data() + entries.size() * sizeof(gpu::GpuPointShadow), records.data(),
                        records.size() * sizeof(gpu::GpuRtShadowMask));
            for (size_t offset = 0; offset < bytes.size(); offset += 65536)  // vkCmdUpdateBuffer's limit per call
                vkCmdUpdateBuffer(pc.commandBuffer(), pc.vkBuffer(out->table), offset,
                                  std::min<size_t>(65536, bytes.size() - offset), bytes.data() + offset);
        });
    return *out;
}

}  // namespace idk::passes
