// transfer.hpp: moving bytes between the CPU and GPU resources. Uploads write mapped memory directly when
// the buffer is mapped (UMA without forced staging) and otherwise go through a staging buffer and a copy on
// the queue, the path a discrete GPU always takes. Readbacks always copy into a host-visible buffer.
#pragma once
#include <volk.h>

#include <cstdint>
#include <span>
#include <vector>

#include "vk/resources.hpp"

namespace idk::vk {

class Context;

void uploadBuffer(Context& ctx, const Buffer& dst, const void* data, VkDeviceSize size, VkDeviceSize offset = 0);
void downloadBuffer(Context& ctx, const Buffer& src, void* out, VkDeviceSize size, VkDeviceSize offset = 0);

template <class T>
void uploadBuffer(Context& ctx, const Buffer& dst, std::span<const T> values, VkDeviceSize offsetBytes = 0) {
    uploadBuffer(ctx, dst, values.data(), values.size_bytes(), offsetBytes);
}
template <class T>
std::vector<T> downloadBuffer(Context& ctx, const Buffer& src, size_t count, VkDeviceSize offsetBytes = 0) {
    std::vector<T> out(count);
    downloadBuffer(ctx, src, out.data(), count * sizeof(T), offsetBytes);
    return out;
}

// Creates a buffer with the given usage and fills it (through staging when needed).
Buffer createBufferWithData(Context& ctx, const BufferDesc& desc, const void* data, VkDeviceSize size);

// Uploads tightly packed texels of mip 0, layer 0 and leaves the image in finalLayout.
void uploadImage(Context& ctx, const Image& image, const void* texels, VkDeviceSize size, VkImageLayout finalLayout);
// Reads mip 0 of layer 0 (tightly packed) from an image currently in currentLayout; the layout is restored.
std::vector<uint8_t> readbackImage(Context& ctx, const Image& image, VkImageLayout currentLayout);

// One global memory barrier (synchronization2), for GPU work recorded outside the render graph (uploads,
// readbacks, the standalone compute primitives and BVH refit). Passes in the graph never call these.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess);
// A dispatch's storage writes made visible to the next dispatch's storage reads and writes.
void computeToComputeBarrier(VkCommandBuffer cmd);

// Records a full-image layout transition (used outside the render graph: uploads, readbacks, tests).
void transitionImage(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to);

}  // namespace idk::vk
