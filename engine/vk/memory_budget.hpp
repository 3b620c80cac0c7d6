// memory_budget.hpp: how much device-local memory a new allocation may still take, asked before a large, optional
// allocation (the VXGI grid, frame/vxgi_memory.hpp) so that going over is a clear refusal instead of an
// out-of-memory failure mid-frame or a device loss. From VK_EXT_memory_budget where the device offers it (the
// largest device-local heap's budget minus its usage, which counts every process on that heap), else that heap's
// size minus what this process's allocator holds.
//
// Test hook: the environment variable IDK_TEST_MEMORY_BUDGET_MIB=N replaces the free amount by N MiB (no real
// driver can be made to report a small heap on demand).
#pragma once
#include <volk.h>

#include <cstdint>
#include <string>

namespace idk::vk {

class Context;
struct ImageDesc;

struct DeviceMemoryBudget {
    VkDeviceSize available = 0;  // bytes a new device-local allocation may take
    std::string source;          // "VK_EXT_memory_budget", "device-local heap size" or the test hook's name
};

// Throws std::runtime_error naming IDK_TEST_MEMORY_BUDGET_MIB when its value is not a whole number.
DeviceMemoryBudget deviceLocalBudget(Context& ctx);

// The bytes Context::createImage(desc) allocates (its memory requirements, with the transfer usages it adds),
// asked of the driver without creating the image (Vulkan 1.3 vkGetDeviceImageMemoryRequirements).
VkDeviceSize imageBytes(Context& ctx, const ImageDesc& desc);

// "126.0 MiB (132120576 bytes)": the size in messages that a test can compare exactly.
std::string bytesText(VkDeviceSize bytes);

}  // namespace idk::vk
