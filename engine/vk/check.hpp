// check.hpp: always-on VkResult checking (never compiled out in release builds) and VkResult names. The two
// failures a caller can act on have their own types: device loss (recreate the device) and device memory
// exhaustion (retry with less); `idk render` maps them to exit codes 3 and 4, the viewer offers a retry.
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

// VK_ERROR_DEVICE_LOST: the device (driver, GPU) failed; every object of the VkDevice must be destroyed and the
// device recreated before anything renders again.
class DeviceLostError : public Error {
public:
    using Error::Error;
};

// VK_ERROR_OUT_OF_DEVICE_MEMORY: an allocation or a submission needed more device memory than there is.
class OutOfDeviceMemoryError : public Error {
public:
    using Error::Error;
};

const char* resultName(VkResult result);

// Throws the typed error for `result` (DeviceLostError, OutOfDeviceMemoryError, else Error) with message `what`.
[[noreturn]] void throwResult(VkResult result, const std::string& what);

// Throws vk::Error (or a subclass above) unless result is VK_SUCCESS (or another non-error code such as VK_SUBOPTIMAL_KHR).
void check(VkResult result, std::source_location where = std::source_location::current());

}  // namespace idk::vk
