// rendering.hpp: the start of a dynamic-rendering pass shared by the raster passes: vkCmdBeginRendering over the
// whole extent plus a full-extent viewport and scissor (both are dynamic state in every pipeline, see
// vk/pipeline.cpp). The attachments' layouts are the ones the render graph put them in.
#pragma once
#include <volk.h>

#include <span>

namespace idk::passes {

inline void beginRendering(VkCommandBuffer cmd, VkExtent2D extent, std::span<const VkRenderingAttachmentInfo> colors,
                           const VkRenderingAttachmentInfo* depth = nullptr, uint32_t layers = 1) {
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, extent};
    rendering.layerCount = layers;
    rendering.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    rendering.pColorAttachments = colors.data();
    rendering.pDepthAttachment = depth;
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0, 1};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace idk::passes
