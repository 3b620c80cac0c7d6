// check.cpp: VkResult to text (Debian's headers have no vk_enum_string_helper.h) and the check() helper.
#include "vk/check.hpp"

#include "core/log.hpp"

namespace idk::vk {

Error::Error(VkResult result, const std::string& what) : std::runtime_error(what), result_(result) {}

const char* resultName(VkResult result) {
    switch (result) {
#define IDK_CASE(x) \
    case x: return #x;
        IDK_CASE(VK_SUCCESS)
        IDK_CASE(VK_NOT_READY)
        IDK_CASE(VK_TIMEOUT)
        IDK_CASE(VK_EVENT_SET)
        IDK_CASE(VK_EVENT_RESET)
        IDK_CASE(VK_INCOMPLETE)
        IDK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        IDK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        IDK_CASE(VK_ERROR_INITIALIZATION_FAILED)
        IDK_CASE(VK_ERROR_DEVICE_LOST)
        IDK_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        IDK_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        IDK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        IDK_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        IDK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        IDK_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        IDK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        IDK_CASE(VK_ERROR_FRAGMENTED_POOL)
        IDK_CASE(VK_ERROR_UNKNOWN)
        IDK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        IDK_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        IDK_CASE(VK_ERROR_FRAGMENTATION)
        IDK_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        IDK_CASE(VK_PIPELINE_COMPILE_REQUIRED)
        IDK_CASE(VK_ERROR_SURFACE_LOST_KHR)
        IDK_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        IDK_CASE(VK_SUBOPTIMAL_KHR)
        IDK_CASE(VK_ERROR_OUT_OF_DATE_KHR)
        IDK_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef IDK_CASE
        default: return "VK_RESULT_UNKNOWN";
    }
}

void throwResult(VkResult result, const std::string& what) {
    if (result == VK_ERROR_DEVICE_LOST) throw DeviceLostError(result, what);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY) throw OutOfDeviceMemoryError(result, what);
    throw Error(result, what);
}

void check(VkResult result, std::source_location where) {
    if (result >= 0) return;  // SPEC: negative codes are errors, positive ones are status codes
    std::string what = core::concat(where.file_name(), ":", where.line(), ": Vulkan call failed with ",
                                    resultName(result), " in ", where.function_name());
    if (result == VK_ERROR_DEVICE_LOST) what += " (device lost: the GPU reset or the driver crashed)";
    throwResult(result, what);
}

}  // namespace idk::vk
