// transfer.cpp: staging uploads and readbacks on the immediate path (submit and wait). The per-frame
// streaming ring for asynchronous texture loading builds on the same copies.
#include "vk/transfer.hpp"

#include <cstring>
#include <stdexcept>

#include "core/log.hpp"
#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::vk {
namespace {

void checkRange(const Buffer& b, VkDeviceSize size, VkDeviceSize offset, const char* what) {
    if (offset + size > b.size || offset + size < offset) {
        throw std::out_of_range(core::concat(what, " of ", size, " bytes at offset ", offset, " overruns buffer '",
                                             b.name, "' of ", b.size, " bytes"));
    }
}

void flushIfNeeded(Context& ctx, const MemoryAllocation& a, VkDeviceSize offset, VkDeviceSize size) {
    if (a.hostCoherent) return;
    VkDeviceSize atom = ctx.info().limits.nonCoherentAtomSize;
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = a.memory;
    range.offset = (a.offset + offset) / atom * atom;
    range.size = VK_WHOLE_SIZE;
    (void)size;
    check(vkFlushMappedMemoryRanges(ctx.device(), 1, &range));
}

void invalidateIfNeeded(Context& ctx, const MemoryAllocation& a) {
    if (a.hostCoherent) return;
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = a.memory;
    range.offset = 0;
    range.size = VK_WHOLE_SIZE;
    check(vkInvalidateMappedMemoryRanges(ctx.device(), 1, &range));
}

Buffer makeStaging(Context& ctx, VkDeviceSize size, MemoryUsage usage, const char* name) {
    BufferDesc desc;
    desc.size = size;
    desc.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    desc.memory = usage;
    desc.name = name;
    desc.category = "staging";
    return ctx.createBuffer(desc);
}

// The staging buffer of one transfer, destroyed however the transfer ends (a failed submission throws).
struct Staging {
    Context& ctx;
    Buffer buffer;
    Staging(Context& c, Buffer b) : ctx(c), buffer(b) {}
    Staging(const Staging&) = delete;
    Staging& operator=(const Staging&) = delete;
    ~Staging() { ctx.destroy(buffer); }
};

// SYNC: transfers here run in their own submission; make their writes visible to any later use.
void barrierAfterTransfer(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

}  // namespace

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStages;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStages;
    barrier.dstAccessMask = dstAccess;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void computeToComputeBarrier(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void uploadBuffer(Context& ctx, const Buffer& dst, const void* data, VkDeviceSize size, VkDeviceSize offset) {
    checkRange(dst, size, offset, "upload");
    if (size == 0) return;
    if (dst.mapped()) {
        std::memcpy(static_cast<uint8_t*>(dst.mapped()) + offset, data, size);
        flushIfNeeded(ctx, dst.allocation, offset, size);
        return;
    }
    Staging scoped(ctx, makeStaging(ctx, size, MemoryUsage::Upload, "upload staging"));
    Buffer& staging = scoped.buffer;
    std::memcpy(staging.mapped(), data, size);
    flushIfNeeded(ctx, staging.allocation, 0, size);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        barrierAfterTransfer(cmd);  // earlier GPU work on dst must finish before it is overwritten
        VkBufferCopy copy{0, offset, size};
        vkCmdCopyBuffer(cmd, staging.buffer, dst.buffer, 1, &copy);
        barrierAfterTransfer(cmd);
    });
}

void downloadBuffer(Context& ctx, const Buffer& src, void* out, VkDeviceSize size, VkDeviceSize offset) {
    checkRange(src, size, offset, "download");
    if (size == 0) return;
    if (src.mapped() && !ctx.allocator().forceStaging()) {
        ctx.waitIdle();  // the CPU reads what the GPU wrote: everything submitted must be complete
        invalidateIfNeeded(ctx, src.allocation);
        std::memcpy(out, static_cast<const uint8_t*>(src.mapped()) + offset, size);
        return;
    }
    Staging scoped(ctx, makeStaging(ctx, size, MemoryUsage::Readback, "readback staging"));
    Buffer& staging = scoped.buffer;
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        barrierAfterTransfer(cmd);
        VkBufferCopy copy{offset, 0, size};
        vkCmdCopyBuffer(cmd, src.buffer, staging.buffer, 1, &copy);
        barrierAfterTransfer(cmd);
    });
    invalidateIfNeeded(ctx, staging.allocation);
    std::memcpy(out, staging.mapped(), size);
}

Buffer createBufferWithData(Context& ctx, const BufferDesc& desc, const void* data, VkDeviceSize size) {
    Buffer b = ctx.createBuffer(desc);
    uploadBuffer(ctx, b, data, size, 0);
    return b;
}

void transitionImage(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image.image;
    barrier.subresourceRange = {aspectOf(image.format), 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

static VkDeviceSize mip0Bytes(const Image& image) {
    uint32_t texel = bytesPerTexel(image.format);
    if (texel == 0) throw std::invalid_argument("image '" + image.name + "' has a format without a fixed texel size");
    return VkDeviceSize(texel) * image.extent.width * image.extent.height * image.extent.depth;
}

void uploadImage(Context& ctx, const Image& image, const void* texels, VkDeviceSize size, VkImageLayout finalLayout) {
    VkDeviceSize expected = mip0Bytes(image);
    if (size != expected) {
        throw std::invalid_argument(core::concat("uploadImage '", image.name, "': ", size, " bytes given, ", expected,
                                                 " expected"));
    }
    Staging scoped(ctx, makeStaging(ctx, size, MemoryUsage::Upload, "image upload staging"));
    Buffer& staging = scoped.buffer;
    std::memcpy(staging.mapped(), texels, size);
    flushIfNeeded(ctx, staging.allocation, 0, size);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {aspectOf(image.format), 0, 0, 1};
        copy.imageExtent = image.extent;
        vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, finalLayout);
    });
}

std::vector<uint8_t> readbackImage(Context& ctx, const Image& image, VkImageLayout currentLayout) {
    VkDeviceSize size = mip0Bytes(image);
    Staging scoped(ctx, makeStaging(ctx, size, MemoryUsage::Readback, "image readback staging"));
    Buffer& staging = scoped.buffer;
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        transitionImage(cmd, image, currentLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {aspectOf(image.format), 0, 0, 1};
        copy.imageExtent = image.extent;
        vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &copy);
        if (currentLayout != VK_IMAGE_LAYOUT_UNDEFINED)
            transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, currentLayout);
        barrierAfterTransfer(cmd);
    });
    invalidateIfNeeded(ctx, staging.allocation);
    std::vector<uint8_t> out(size);
    std::memcpy(out.data(), staging.mapped(), size);
    return out;
}

}  // namespace idk::vk
