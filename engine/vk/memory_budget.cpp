// memory_budget.cpp: see memory_budget.hpp.
#include "vk/memory_budget.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "vk/context.hpp"
#include "vk/memory.hpp"
#include "vk/resources.hpp"

namespace idk::vk {
namespace {

bool hasMemoryBudget(VkPhysicalDevice physical) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME) == 0;
    });
}

}  // namespace

VkDeviceSize imageBytes(Context& ctx, const ImageDesc& desc) {
    ImageDesc withTransfers = desc;  // as Context::createImage
    withTransfers.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const VkImageCreateInfo info = imageCreateInfo(withTransfers);
    VkDeviceImageMemoryRequirements query{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
    query.pCreateInfo = &info;
    VkMemoryRequirements2 req{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    vkGetDeviceImageMemoryRequirements(ctx.device(), &query, &req);
    return req.memoryRequirements.size;
}

std::string bytesText(VkDeviceSize bytes) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.1f MiB (%llu bytes)", double(bytes) / double(1u << 20),
                  static_cast<unsigned long long>(bytes));
    return text;
}

DeviceMemoryBudget deviceLocalBudget(Context& ctx) {
    if (const char* env = std::getenv("IDK_TEST_MEMORY_BUDGET_MIB"); env && *env) {
        char* end = nullptr;
        const unsigned long long mib = std::strtoull(env, &end, 10);
        if (*end != '\0' || env[0] == '-')
            throw std::runtime_error(std::string("IDK_TEST_MEMORY_BUDGET_MIB='") + env + "': expected a whole number of MiB");
        return {VkDeviceSize(mib) << 20, "IDK_TEST_MEMORY_BUDGET_MIB"};
    }
    // Physical-device queries may use a device extension's structures when the device supports it (Vulkan 1.1+),
    // enabled or not.
    const bool budgetExt = hasMemoryBudget(ctx.physicalDevice());
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    VkPhysicalDeviceMemoryProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
    if (budgetExt) properties.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(ctx.physicalDevice(), &properties);
    const VkPhysicalDeviceMemoryProperties& p = properties.memoryProperties;
    // The largest device-local heap is where GpuOnly resources go (on a discrete GPU the small device-local heap
    // is the host-visible BAR window).
    uint32_t heap = 0;
    for (uint32_t h = 0; h < p.memoryHeapCount; ++h)
        if ((p.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) &&
            (!(p.memoryHeaps[heap].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) || p.memoryHeaps[h].size > p.memoryHeaps[heap].size))
            heap = h;
    if (budgetExt) {
        const VkDeviceSize limit = budget.heapBudget[heap], used = std::min(budget.heapUsage[heap], limit);
        return {limit - used, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME};
    }
    const MemoryStats stats = ctx.allocator().stats();
    const VkDeviceSize held = stats.blockBytes + stats.dedicatedBytes, size = p.memoryHeaps[heap].size;
    return {size - std::min(held, size), "device-local heap size"};
}

}  // namespace idk::vk
