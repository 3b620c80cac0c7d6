// depth_pyramid_minmax.cpp: the Hi-Z pyramid on the native rung of the ladder "hiz-reduction": each level is one
// dispatch of culling/hiz_reduce.comp.glsl, one MAX-reduction sample per 2 x 2 block (VK_EXT_sampler_filter_minmax)
// of the level below, written to the same pyramid buffer as the compute rung (depth_pyramid.cpp), bit for bit, and
// copied into an R32F image per level (owned by the caller) that the next level samples. The shader does not
// imageStore the level: a store through the bindless storage array counts, for the synchronization validation, as
// writing every storage image in it (the G-buffer's too). A real GPU would store directly (or build several levels
// per dispatch from shared memory) and skip the copies; on lavapipe they are a few hundred KB per frame. Ports IDKEngine's Hi-Z generation
// (MeshCulling/Camera/HiZGenerate), which reads 2 x 2 texels per texel instead of one filtered sample.
#include <stdexcept>

#include "passes/culling.hpp"
#include "shared/depth_pyramid.h"
#include "vk/bindless.hpp"

namespace idk::passes {
namespace {

void levelBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStages, VkAccessFlags2 src, VkPipelineStageFlags2 dstStages,
                  VkAccessFlags2 dst) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStages;
    b.srcAccessMask = src;
    b.dstStageMask = dstStages;
    b.dstAccessMask = dst;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

// The level just written (compute) becomes the copy's source.
void bufferToTransfer(VkCommandBuffer cmd, VkBuffer buffer) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    b.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    b.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.size = VK_WHOLE_SIZE;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.bufferMemoryBarrierCount = 1;
    dep.pBufferMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

void recordDepthPyramidMinmax(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t depthSampled,
                              const HizMinmaxResources& minmax, glm::uvec2 size, VkBuffer pyramidBuffer,
                              VkDeviceAddress pyramid) {
    const std::vector<HizLevelImage>& levels = minmax.levels;
    const uint32_t count = gpu::hizLevelCount(size);
    if (levels.size() != count) throw std::logic_error("recordDepthPyramidMinmax: one image per pyramid level");
    vk::ComputePipelineDesc pipeline;
    pipeline.shader = vk::ShaderId::culling_hiz_reduce_comp;
    pipeline.pushBytes = sizeof(gpu::HizReducePush);
    pipeline.localSize = {gpu::kHizGroupSize, gpu::kHizGroupSize, 1};
    vk::bindPipeline(cmd, shaders.compute(pipeline));
    ctx.bindless().bind(cmd);
    for (uint32_t level = 0; level < count; ++level) {
        const gpu::HizReducePush push{pyramid, size, level == 0 ? depthSampled : levels[level - 1].sampled,
                                      minmax.sampler, level};
        vk::pushConstants(cmd, ctx, push);
        const glm::uvec2 s = gpu::hizLevelSize(size, level);
        vkCmdDispatch(cmd, vk::groupCount(s.x, gpu::kHizGroupSize), vk::groupCount(s.y, gpu::kHizGroupSize), 1);
        if (level + 1 == count) break;
        // The next level samples this one: copy the level from the buffer into its image (the graph does not
        // track these images; the barrier waits for everything before, e.g. the previous frame's pass).
        bufferToTransfer(cmd, pyramidBuffer);
        levelBarrier(cmd, levels[level].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.bufferOffset = VkDeviceSize(gpu::hizLevelOffset(size, level)) * sizeof(float);
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {s.x, s.y, 1};
        vkCmdCopyBufferToImage(cmd, pyramidBuffer, levels[level].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        levelBarrier(cmd, levels[level].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
}

}  // namespace idk::passes
