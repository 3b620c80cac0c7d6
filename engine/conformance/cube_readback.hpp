// cube_readback.hpp: the six faces of a D32 shadow cube that a frame left in SHADER_READ_ONLY_OPTIMAL, read back as
// float depths, face-major (the shadow tests compare cubes texel for texel): shared by the shadow tests and the
// registered check "shadows/point faces rungs agree". Test and conformance support.
#pragma once
#include <vector>

#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {

inline std::vector<float> readCube(vk::Context& ctx, const vk::Image& cube) {
    const VkDeviceSize faceBytes = VkDeviceSize(cube.extent.width) * cube.extent.height * sizeof(float);
    vk::BufferDesc desc;
    desc.size = faceBytes * 6;
    desc.memory = vk::MemoryUsage::Readback;
    desc.name = "cube readback";
    vk::Buffer staging = ctx.createBuffer(desc);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, cube, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 6};
        copy.imageExtent = cube.extent;
        vkCmdCopyImageToBuffer(cmd, cube.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &copy);
        vk::transitionImage(cmd, cube, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    std::vector<float> out(size_t(desc.size / sizeof(float)));
    vk::downloadBuffer(ctx, staging, out.data(), desc.size);
    ctx.destroy(staging);
    return out;
}

}  // namespace idk::conformance
