// depth_pyramid.cpp: "depth_pyramid": the Hi-Z pyramid of an R32F depth image (shared/depth_pyramid.h) in one pass:
// culling/hiz_build.comp.glsl reduces kHizTileLevels levels per dispatch from 32 x 32 tiles in shared memory (two
// dispatches at 1280x720, eleven levels), with a buffer barrier between dispatches (each reads the one before's
// last level); the SSR's closest-depth pyramid is one dispatch of ssr/hiz_min.comp.glsl per level. The portable
// compute rung (fallback of the ladder "hiz-reduction"; the sampler rung is depth_pyramid_minmax.cpp): any size,
// odd and non-power-of-two included. Ports IDKEngine's Hi-Z generation (MeshCulling/Camera/HiZGenerate, a
// fullscreen draw per mip).
#include "passes/culling.hpp"
#include "passes/depth_pyramid_levels.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "shared/depth_pyramid.h"
#include "vk/bindless.hpp"

namespace idk::passes {

void recordDepthPyramidLevels(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders,
                              uint32_t depthStorage, glm::uvec2 size, VkDeviceAddress pyramid, HizReduction reduction,
                              uint32_t levelsPerDispatch) {
    const bool tiled = reduction == HizReduction::Farthest;  // hiz_build (tiles); the SSR minimum: hiz_level.glsl
    if (tiled && (levelsPerDispatch < 1 || levelsPerDispatch > gpu::kHizTileLevels))
        throw std::invalid_argument("recordDepthPyramidLevels: 1 to kHizTileLevels levels per dispatch");
    const uint32_t step = tiled ? levelsPerDispatch : 1;
    const uint32_t group = tiled ? gpu::kHizTile / 2 : gpu::kHizGroupSize;  // invocations per side
    const uint32_t texels = tiled ? gpu::kHizTile : gpu::kHizGroupSize;     // first-level texels per group side
    vk::ComputePipelineDesc pipeline;
    pipeline.shader = tiled ? vk::ShaderId::culling_hiz_build_comp : vk::ShaderId::ssr_hiz_min_comp;
    pipeline.pushBytes = sizeof(gpu::HizBuildPush);
    pipeline.localSize = {group, group, 1};
    vk::bindPipeline(cmd, shaders.compute(pipeline));
    ctx.bindless().bind(cmd);
    const uint32_t levels = gpu::hizLevelCount(size);
    for (uint32_t level = 0; level < levels; level += step) {
        if (level > 0) {
            // These levels read the last dispatch's writes (storage buffer, compute to compute).
            VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
            barrier.srcStageMask = barrier.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            barrier.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
            barrier.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dep.memoryBarrierCount = 1;
            dep.pMemoryBarriers = &barrier;
            vkCmdPipelineBarrier2(cmd, &dep);
        }
        const uint32_t count = std::min(step, levels - level);
        const gpu::HizBuildPush push{pyramid, size, depthStorage, level | (tiled ? count << 16 : 0u)};
        vk::pushConstants(cmd, ctx, push);
        const glm::uvec2 s = gpu::hizLevelSize(size, level);
        vkCmdDispatch(cmd, vk::groupCount(s.x, texels), vk::groupCount(s.y, texels), 1);
    }
}

void recordDepthPyramid(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t depthStorage,
                        glm::uvec2 size, VkDeviceAddress pyramid, HizReduction reduction) {
    recordDepthPyramidLevels(cmd, ctx, shaders, depthStorage, size, pyramid, reduction, gpu::kHizTileLevels);
}

graph::BufferHandle addDepthPyramidPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                        graph::TextureHandle depth, glm::uvec2 size, const std::string& name,
                                        const HizMinmaxResources* minmax) {
    graph::BufferDesc desc;
    desc.size = VkDeviceSize(gpu::hizLevelOffset(size, gpu::hizLevelCount(size))) * sizeof(float);
    if (minmax) desc.extraUsage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;  // the sampler rung copies levels out of it
    graph::BufferHandle created = graph.createBuffer(name, desc);
    auto out = std::make_shared<graph::BufferHandle>();
    if (minmax) {  // the sampler rung: the depth image is sampled
        graph.addPass(
            name,
            [&](graph::PassBuilder& b) {
                constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
                b.read(depth, graph::Access::SampledRead, kCs);
                *out = b.write(created, graph::Access::StorageReadWrite, kCs);
            },
            [&ctx, &shaders, depth, out, size, minmax](graph::PassContext& pc) {
                recordDepthPyramidMinmax(pc.commandBuffer(), ctx, shaders, pc.texture(depth).sampledIndex, *minmax,
                                         size, pc.vkBuffer(*out), pc.buffer(*out).address);
            });
        return *out;
    }
    graph.addPass(
        name,
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(depth, graph::Access::StorageRead, kCs);
            *out = b.write(created, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, depth, out, size](graph::PassContext& pc) {
            recordDepthPyramid(pc.commandBuffer(), ctx, shaders, pc.texture(depth).storageIndex, size,
                               pc.buffer(*out).address);
        });
    return *out;
}

}  // namespace idk::passes
