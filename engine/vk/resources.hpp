// resources.hpp: buffers and images as plain structs. Context creates and destroys them; every object gets a
// debug name so validation messages and captures say which resource is involved.
#pragma once
#include <volk.h>

#include <string>

#include "vk/memory.hpp"

namespace idk::vk {

struct BufferDesc {
    VkDeviceSize size = 0;
    VkBufferUsageFlags usage = 0;  // TRANSFER_DST/SRC and SHADER_DEVICE_ADDRESS are added automatically
    MemoryUsage memory = MemoryUsage::GpuOnly;
    std::string name;
    std::string category = "buffers";
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    MemoryAllocation allocation;
    VkDeviceSize size = 0;
    VkDeviceAddress address = 0;
    VkBufferUsageFlags usage = 0;
    std::string name;
    void* mapped() const { return allocation.mapped; }
    explicit operator bool() const { return buffer != VK_NULL_HANDLE; }
};

struct ImageDesc {
    VkImageType type = VK_IMAGE_TYPE_2D;
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkExtent3D extent = {1, 1, 1};
    uint32_t mipLevels = 1;
    uint32_t layers = 1;
    bool cube = false;             // layers must be a multiple of 6
    VkImageUsageFlags usage = 0;   // TRANSFER_SRC/DST are added automatically
    std::string name;
    std::string category = "images";
};

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;  // all mips and layers
    MemoryAllocation allocation;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageType type = VK_IMAGE_TYPE_2D;
    VkExtent3D extent = {};
    uint32_t mipLevels = 1;
    uint32_t layers = 1;
    VkImageUsageFlags usage = 0;
    std::string name;
    explicit operator bool() const { return image != VK_NULL_HANDLE; }
};

bool isDepthFormat(VkFormat format);
VkImageAspectFlags aspectOf(VkFormat format);
uint32_t bytesPerTexel(VkFormat format);  // 0 for block-compressed or unknown formats
VkImageViewType viewTypeOf(const ImageDesc& desc);
// Optimal-tiling image, one sample, UNDEFINED initial layout; usage exactly as given.
VkImageCreateInfo imageCreateInfo(const ImageDesc& desc);

}  // namespace idk::vk
