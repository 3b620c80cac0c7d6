// check.hpp: always-on VkResult checking (never compiled out in release builds) and VkResult names.
#pragma once
#include <volk.h>

#include <source_location>
#include <stdexcept>
#include <string>

namespace idk::vk {

// A Vulkan call failed. The message names the call site and the VkResult.
class Error : public std::runtime_error {
public:
    Error(VkResult result, const std::string& what);
    VkResult result() const noexcept { return result_; }

private:
    VkResult result_;
};

const char* resultName(VkResult result);

// Throws vk::Error unless result is VK_SUCCESS (or another non-error code such as VK_SUBOPTIMAL_KHR).
void check(VkResult result, std::source_location where = std::source_location::current());

}  // namespace idk::vk
