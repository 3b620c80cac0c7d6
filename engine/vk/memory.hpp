// memory.hpp: the Vulkan memory sub-allocator (Debian has no VMA package). Small resources share 64 MiB
// VkDeviceMemory blocks, each managed by a core::RangeAllocator; big resources get dedicated allocations.
// Linear (buffers) and optimal-tiling (images) resources live in separate blocks, which satisfies
// bufferImageGranularity without tracking neighbours.
#pragma once
#include <volk.h>

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace idk::core { class RangeAllocator; }

namespace idk::vk {

enum class MemoryUsage : uint8_t {
    GpuOnly,   // device-local; mapped only when the device is UMA and staging is not forced
    Upload,    // host-visible, written by the CPU (staging, per-frame constants)
    Readback,  // host-visible and cached if possible, read by the CPU
};

enum class ResourceTiling : uint8_t { Linear, Optimal };

struct MemoryAllocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr;       // host pointer to offset, when the memory is mapped
    uint32_t memoryType = 0;
    int32_t block = -1;           // -1 = dedicated allocation
    bool hostCoherent = true;
    std::string category;         // for `idk render --stats`: "geometry", "textures", "render targets"...
};

struct MemoryStats {
    std::map<std::string, VkDeviceSize> bytesByCategory;
    VkDeviceSize blockBytes = 0;      // VkDeviceMemory reserved for sub-allocation
    VkDeviceSize dedicatedBytes = 0;
    uint32_t deviceMemoryCount = 0;   // live vkAllocateMemory objects
};

class MemoryAllocator {
public:
    static constexpr VkDeviceSize kBlockSize = 64ull << 20;
    static constexpr VkDeviceSize kDedicatedThreshold = kBlockSize / 2;

    MemoryAllocator(VkPhysicalDevice physical, VkDevice device, bool forceStaging);
    ~MemoryAllocator();
    MemoryAllocator(const MemoryAllocator&) = delete;
    MemoryAllocator& operator=(const MemoryAllocator&) = delete;

    // Throws vk::Error (VK_ERROR_OUT_OF_DEVICE_MEMORY) when nothing fits, naming the category and size.
    MemoryAllocation allocate(const VkMemoryRequirements& requirements, MemoryUsage usage, ResourceTiling tiling,
                              const std::string& category, bool wantDedicated = false);
    void free(const MemoryAllocation& allocation);

    MemoryStats stats() const;
    bool isUma() const noexcept { return uma_; }
    bool forceStaging() const noexcept { return forceStaging_; }

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        uint32_t memoryType = 0;
        ResourceTiling tiling = ResourceTiling::Linear;
        void* mapped = nullptr;
        std::unique_ptr<core::RangeAllocator> ranges;
    };

    uint32_t findMemoryType(uint32_t typeBits, MemoryUsage usage) const;
    bool shouldMap(uint32_t memoryType, MemoryUsage usage) const;
    VkDeviceMemory allocateDeviceMemory(VkDeviceSize size, uint32_t memoryType, void** mapped, bool map,
                                        const std::string& category);

    VkDevice device_;
    VkPhysicalDeviceMemoryProperties properties_{};
    bool forceStaging_;
    bool uma_ = false;
    mutable std::mutex mutex_;
    std::vector<Block> blocks_;
    std::map<std::string, VkDeviceSize> bytesByCategory_;
    VkDeviceSize dedicatedBytes_ = 0;
    uint32_t dedicatedCount_ = 0;
};

}  // namespace idk::vk
