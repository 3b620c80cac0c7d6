// memory.cpp: memory-type selection, block sub-allocation and dedicated allocations.
#include "vk/memory.hpp"

#include "core/log.hpp"
#include "core/range_allocator.hpp"
#include "vk/check.hpp"

namespace idk::vk {

MemoryAllocator::MemoryAllocator(VkPhysicalDevice physical, VkDevice device, bool forceStaging)
    : device_(device), forceStaging_(forceStaging) {
    vkGetPhysicalDeviceMemoryProperties(physical, &properties_);
    // UMA: every device-local type is also host-visible (lavapipe, integrated GPUs).
    uma_ = true;
    for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
        VkMemoryPropertyFlags f = properties_.memoryTypes[i].propertyFlags;
        if ((f & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) && !(f & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)) uma_ = false;
    }
}

MemoryAllocator::~MemoryAllocator() {
    for (Block& block : blocks_) {
        if (block.ranges && block.ranges->allocationCount() != 0) {
            core::logWarning("memory block of type ", block.memoryType, " still holds ",
                             block.ranges->allocationCount(), " allocations at shutdown");
        }
        vkFreeMemory(device_, block.memory, nullptr);
    }
}

uint32_t MemoryAllocator::findMemoryType(uint32_t typeBits, MemoryUsage usage) const {
    auto score = [&](VkMemoryPropertyFlags f) -> int {
        bool deviceLocal = f & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        bool hostVisible = f & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
        bool coherent = f & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        bool cached = f & VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
        switch (usage) {
            case MemoryUsage::GpuOnly: return deviceLocal ? 10 + (hostVisible ? 0 : 1) : 1;
            case MemoryUsage::Upload: return hostVisible ? 10 + (coherent ? 2 : 0) + (deviceLocal ? 0 : 1) : -1;
            case MemoryUsage::Readback: return hostVisible ? 10 + (cached ? 4 : 0) + (coherent ? 1 : 0) : -1;
        }
        return -1;
    };
    int best = -1;
    uint32_t bestType = UINT32_MAX;
    for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        int s = score(properties_.memoryTypes[i].propertyFlags);
        if (s > best) {
            best = s;
            bestType = i;
        }
    }
    if (best < 0) throw Error(VK_ERROR_FEATURE_NOT_PRESENT, "no Vulkan memory type fits the requested usage");
    return bestType;
}

bool MemoryAllocator::shouldMap(uint32_t memoryType, MemoryUsage usage) const {
    bool hostVisible = properties_.memoryTypes[memoryType].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
    if (!hostVisible) return false;
    // Forced staging keeps GPU-only resources unmapped so uploads take the discrete-GPU path even on UMA.
    return usage != MemoryUsage::GpuOnly || !forceStaging_;
}

VkDeviceMemory MemoryAllocator::allocateDeviceMemory(VkDeviceSize size, uint32_t memoryType, void** mapped, bool map,
                                                     const std::string& category) {
    // Buffer device address is part of the baseline, so every allocation may back an addressable buffer.
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flags};
    info.allocationSize = size;
    info.memoryTypeIndex = memoryType;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkResult result = vkAllocateMemory(device_, &info, nullptr, &memory);
    if (result != VK_SUCCESS) {
        throw Error(result, core::concat("vkAllocateMemory of ", size, " bytes for '", category, "' failed: ",
                                         resultName(result)));
    }
    *mapped = nullptr;
    if (map) check(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, mapped));
    return memory;
}

MemoryAllocation MemoryAllocator::allocate(const VkMemoryRequirements& req, MemoryUsage usage, ResourceTiling tiling,
                                           const std::string& category, bool wantDedicated) {
    std::lock_guard lock(mutex_);
    MemoryAllocation a;
    a.memoryType = findMemoryType(req.memoryTypeBits, usage);
    a.size = req.size;
    a.category = category;
    a.hostCoherent = properties_.memoryTypes[a.memoryType].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    bool map = shouldMap(a.memoryType, usage);

    if (wantDedicated || req.size > kDedicatedThreshold) {
        a.memory = allocateDeviceMemory(req.size, a.memoryType, &a.mapped, map, category);
        dedicatedBytes_ += req.size;
        ++dedicatedCount_;
    } else {
        int32_t found = -1;
        std::optional<uint64_t> offset;
        for (size_t i = 0; i < blocks_.size() && found < 0; ++i) {
            Block& b = blocks_[i];
            if (b.memoryType != a.memoryType || b.tiling != tiling || (map && !b.mapped)) continue;
            offset = b.ranges->allocate(req.size, req.alignment);
            if (offset) found = static_cast<int32_t>(i);
        }
        if (found < 0) {
            Block b;
            b.memoryType = a.memoryType;
            b.tiling = tiling;
            b.memory = allocateDeviceMemory(kBlockSize, a.memoryType, &b.mapped, map, category);
            b.ranges = std::make_unique<core::RangeAllocator>(kBlockSize);
            offset = b.ranges->allocate(req.size, req.alignment);
            blocks_.push_back(std::move(b));
            found = static_cast<int32_t>(blocks_.size() - 1);
        }
        Block& b = blocks_[static_cast<size_t>(found)];
        a.memory = b.memory;
        a.offset = *offset;
        a.block = found;
        if (map) a.mapped = static_cast<uint8_t*>(b.mapped) + a.offset;
    }
    bytesByCategory_[category] += req.size;
    return a;
}

void MemoryAllocator::free(const MemoryAllocation& a) {
    if (a.memory == VK_NULL_HANDLE) return;
    std::lock_guard lock(mutex_);
    if (a.block < 0) {
        vkFreeMemory(device_, a.memory, nullptr);
        dedicatedBytes_ -= a.size;
        --dedicatedCount_;
    } else {
        blocks_[static_cast<size_t>(a.block)].ranges->free(a.offset);
    }
    auto it = bytesByCategory_.find(a.category);
    if (it != bytesByCategory_.end()) {
        it->second -= a.size;
        if (it->second == 0) bytesByCategory_.erase(it);
    }
}

MemoryStats MemoryAllocator::stats() const {
    std::lock_guard lock(mutex_);
    MemoryStats s;
    s.bytesByCategory = bytesByCategory_;
    s.blockBytes = kBlockSize * blocks_.size();
    s.dedicatedBytes = dedicatedBytes_;
    s.deviceMemoryCount = static_cast<uint32_t>(blocks_.size()) + dedicatedCount_;
    return s;
}

}  // namespace idk::vk
