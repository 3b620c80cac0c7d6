// blit.hpp: a whole-image, same-size blit (nearest filter). A blit, not a copy, because it converts between
// formats: the renderer's and the path-traced viewer's RGBA8 results go to swapchain images, often BGRA8.
// Both images must be in TRANSFER_SRC / TRANSFER_DST_OPTIMAL (the render graph puts them there).
#pragma once
#include <volk.h>

#include <cstdint>

namespace idk::vk {

inline void blitSameSize(VkCommandBuffer cmd, VkImage source, VkImage target, uint32_t width, uint32_t height) {
    VkImageBlit2 region{VK_STRUCTURE_TYPE_IMAGE_BLIT_2};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {int32_t(width), int32_t(height), 1};
    region.dstOffsets[1] = region.srcOffsets[1];
    VkBlitImageInfo2 blit{VK_STRUCTURE_TYPE_BLIT_IMAGE_INFO_2};
    blit.srcImage = source;
    blit.srcImageLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    blit.dstImage = target;
    blit.dstImageLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    blit.regionCount = 1;
    blit.pRegions = &region;
    blit.filter = VK_FILTER_NEAREST;
    vkCmdBlitImage2(cmd, &blit);
}

}  // namespace idk::vk
