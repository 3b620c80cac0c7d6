// context.cpp: instance, validation messenger, device choice by required features, device creation with the
// Vulkan 1.3 baseline feature chain (DESIGN.md) plus whatever optional features the device has, submission on
// one timeline semaphore, resource creation and deferred destruction.
#include "vk/context.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>

#include "core/log.hpp"
#include "gl/interop_probe.hpp"
#include "shared/bindings.h"
#include "vk/bindless.hpp"
#include "vk/check.hpp"
#include "vk/fault_injection.hpp"

namespace idk::vk {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* log = static_cast<ValidationLog*>(user);
    const char* text = data && data->pMessage ? data->pMessage : "(no message)";
    // The installed validation layers (1.3.239) treat every element of a bindless runtime array as accessed by
    // every draw or dispatch that statically uses the array, which reports hazards between unrelated images of
    // the global set. Later layer releases skip runtime arrays (Vulkan-ValidationLayers issue 3450); only those
    // synchronization messages about the bindless set are dropped, every other message still counts.
    if (std::strstr(text, "SYNC-HAZARD") && std::strstr(text, "[global bindless set]")) return VK_FALSE;
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        log->errors++;
        core::logError("validation: ", text);
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        log->warnings++;
        core::logWarning("validation: ", text);
    } else {
        return VK_FALSE;
    }
    std::lock_guard lock(log->mutex);
    if (log->messages.size() < 256) log->messages.emplace_back(text);
    return VK_FALSE;
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasInstanceExtension(const char* layer, const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateInstanceExtensionProperties(layer, &count, exts.data());
    return std::any_of(exts.begin(), exts.end(), [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<std::string> deviceExtensions(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, exts.data());
    std::vector<std::string> names;
    for (const auto& e : exts) names.emplace_back(e.extensionName);
    return names;
}

bool contains(const std::vector<std::string>& list, const char* name) {
    return std::find(list.begin(), list.end(), name) != list.end();
}

// Everything the device reports, in one pNext chain.
struct FeatureChain {
    VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceMeshShaderFeaturesEXT mesh{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT};
    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomicFloat{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
    VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT atomicFloat2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_2_FEATURES_EXT};
    VkPhysicalDeviceFragmentShadingRateFeaturesKHR shadingRate{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FRAGMENT_SHADING_RATE_FEATURES_KHR};
    VkPhysicalDeviceShadingRateImageFeaturesNV shadingRateNv{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADING_RATE_IMAGE_FEATURES_NV};
    VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR accel{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};

    // Links the base structs plus the extension structs whose extension is present.
    void link(const std::vector<std::string>& exts) {
        core.pNext = &v11;
        v11.pNext = &v12;
        v12.pNext = &v13;
        void** tail = &v13.pNext;
        auto append = [&](const char* ext, auto& s) {
            if (!contains(exts, ext)) return;
            *tail = &s;
            tail = &s.pNext;
        };
        append(VK_EXT_MESH_SHADER_EXTENSION_NAME, mesh);
        append(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME, atomicFloat);
        append(VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME, atomicFloat2);
        append(VK_KHR_FRAGMENT_SHADING_RATE_EXTENSION_NAME, shadingRate);
        append(VK_NV_SHADING_RATE_IMAGE_EXTENSION_NAME, shadingRateNv);
        if (contains(exts, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
            contains(exts, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME)) {
            append(VK_KHR_RAY_QUERY_EXTENSION_NAME, rayQuery);
            append(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, accel);
        }
        *tail = nullptr;
    }
};

// The device extensions to enable: every optional one present, VRS only for the mechanism the ladder chose.
// The names are the headers' string literals (static storage: Context keeps the pointers).
std::vector<const char*> enabledExtensions(const std::vector<std::string>& exts, const std::vector<Ladder>& ladders,
                                           bool presentation) {
    std::string vrs;
    for (const Ladder& l : ladders)
        if (l.id == "vrs" && l.chosen == Rung::Native) vrs = l.chosenMechanism;
    std::vector<const char*> enabled;
    auto enableIf = [&](const char* name) {
        if (contains(exts, name)) enabled.push_back(name);
    };
    if (presentation) enabled.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    enableIf(VK_EXT_MESH_SHADER_EXTENSION_NAME);
    enableIf(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
    enableIf(VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME);
    if (vrs == VK_KHR_FRAGMENT_SHADING_RATE_EXTENSION_NAME) enableIf(VK_KHR_FRAGMENT_SHADING_RATE_EXTENSION_NAME);
    if (vrs == VK_NV_SHADING_RATE_IMAGE_EXTENSION_NAME) enableIf(VK_NV_SHADING_RATE_IMAGE_EXTENSION_NAME);
    enableIf(VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
    // The single-draw voxelization's native rung (passes/vxgi_voxelize.cpp); neither has a feature struct.
    enableIf(VK_NV_GEOMETRY_SHADER_PASSTHROUGH_EXTENSION_NAME);
    enableIf(VK_NV_VIEWPORT_SWIZZLE_EXTENSION_NAME);
    enableIf(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    enableIf(VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);  // GL-interop hand-offs on the GPU (gl/gl_sync.hpp)
    if (contains(exts, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
        contains(exts, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME)) {
        enableIf(VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
        enableIf(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
        enableIf(VK_KHR_RAY_QUERY_EXTENSION_NAME);
    }
    return enabled;
}

// The Vulkan 1.3 baseline of DESIGN.md. Returns the names of missing features (empty = suitable).
std::vector<std::string> missingBaseline(const FeatureChain& f, uint32_t apiVersion) {
    std::vector<std::string> missing;
    auto need = [&](VkBool32 value, const char* name) {
        if (!value) missing.emplace_back(name);
    };
    if (apiVersion < VK_API_VERSION_1_3) missing.emplace_back("Vulkan 1.3");
    need(f.v13.dynamicRendering, "dynamicRendering");
    need(f.v13.synchronization2, "synchronization2");
    need(f.v13.maintenance4, "maintenance4");
    need(f.v12.bufferDeviceAddress, "bufferDeviceAddress");
    need(f.v12.timelineSemaphore, "timelineSemaphore");
    need(f.v12.scalarBlockLayout, "scalarBlockLayout");
    need(f.v12.drawIndirectCount, "drawIndirectCount");
    need(f.v12.hostQueryReset, "hostQueryReset");
    need(f.v12.descriptorIndexing, "descriptorIndexing");
    need(f.v12.runtimeDescriptorArray, "runtimeDescriptorArray");
    need(f.v12.descriptorBindingPartiallyBound, "descriptorBindingPartiallyBound");
    need(f.v12.descriptorBindingVariableDescriptorCount, "descriptorBindingVariableDescriptorCount");
    need(f.v12.descriptorBindingSampledImageUpdateAfterBind, "descriptorBindingSampledImageUpdateAfterBind");
    need(f.v12.descriptorBindingStorageImageUpdateAfterBind, "descriptorBindingStorageImageUpdateAfterBind");
    need(f.v12.descriptorBindingStorageBufferUpdateAfterBind, "descriptorBindingStorageBufferUpdateAfterBind");
    need(f.v12.descriptorBindingUpdateUnusedWhilePending, "descriptorBindingUpdateUnusedWhilePending");
    need(f.v12.shaderSampledImageArrayNonUniformIndexing, "shaderSampledImageArrayNonUniformIndexing");
    need(f.v12.shaderStorageBufferArrayNonUniformIndexing, "shaderStorageBufferArrayNonUniformIndexing");
    need(f.v11.shaderDrawParameters, "shaderDrawParameters");
    need(f.core.features.multiDrawIndirect, "multiDrawIndirect");
    need(f.core.features.shaderInt64, "shaderInt64");
    need(f.core.features.fragmentStoresAndAtomics, "fragmentStoresAndAtomics");
    need(f.core.features.shaderStorageImageWriteWithoutFormat, "shaderStorageImageWriteWithoutFormat");
    return missing;
}

}  // namespace

Context::Context(const ContextDesc& desc) : desc_(desc), validation_(std::make_unique<ValidationLog>()) {
    if (const char* env = std::getenv("IDK_DEVICE"); env && desc_.deviceNameFilter.empty()) desc_.deviceNameFilter = env;
    if (volkInitialize() != VK_SUCCESS) {
        throw std::runtime_error(
            "no Vulkan loader found (libvulkan.so.1): install the Debian packages libvulkan1 and mesa-vulkan-drivers");
    }
    createInstance();
    pickPhysicalDevice();
    createDevice();
    allocator_ = std::make_unique<MemoryAllocator>(physical_, device_, desc_.forceStaging);
    info_.uma = allocator_->isUma();

    VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &type};
    check(vkCreateSemaphore(device_, &sem, nullptr, &timeline_));
    setName(timeline_, VK_OBJECT_TYPE_SEMAPHORE, "submission timeline");

    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = queueFamily_;
    check(vkCreateCommandPool(device_, &pool, nullptr, &immediatePool_));

    bindless_ = std::make_unique<BindlessTable>(*this);
    VkPushConstantRange push{VK_SHADER_STAGE_ALL, 0, gpu::kPushConstantBytes};
    VkDescriptorSetLayout setLayout = bindless_->layout();
    VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout.setLayoutCount = 1;
    layout.pSetLayouts = &setLayout;
    layout.pushConstantRangeCount = 1;
    layout.pPushConstantRanges = &push;
    check(vkCreatePipelineLayout(device_, &layout, nullptr, &pipelineLayout_));
    setName(pipelineLayout_, VK_OBJECT_TYPE_PIPELINE_LAYOUT, "global pipeline layout");

    if (desc_.probeGlInterop) {
        // The probe needs a working context (it round-trips an image), so the GL rungs are decided last.
        gl::ProbeResult probe;
        try {
            probe = gl::probeGlInterop(*this);
        } catch (...) {
            // The device was lost (or ran out of memory) during the round trip: no destructor runs for a throwing
            // constructor, so everything made so far, the probe's deferred releases included, goes here.
            destroyAll();
            throw;
        }
        caps_.glInterop = probe.context != nullptr;
        caps_.glAtomicFloat = probe.atomicFloat;
        caps_.glAtomicFp16Vector = probe.atomicFp16Vector;
        caps_.glInteropNote = probe.note;
        gl_ = std::move(probe.context);
        forcedRungError_.clear();
        ladders_ = buildLadders(caps_, LadderChoice{desc_.forceFallbackRungs, desc_.forcedRungs}, &forcedRungError_);
    }
}

Context::~Context() { destroyAll(); }

void Context::destroyAll() noexcept {
    if (device_) {
        vkDeviceWaitIdle(device_);
        for (auto& d : deferred_) d.release();
        deferred_.clear();
        releaseLeftovers();
        gl_.reset();
        vkDestroyPipelineLayout(device_, pipelineLayout_, nullptr);
        bindless_.reset();
        vkDestroyCommandPool(device_, immediatePool_, nullptr);
        vkDestroySemaphore(device_, timeline_, nullptr);
        allocator_.reset();
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
    if (instance_) vkDestroyInstance(instance_, nullptr);
    device_ = VK_NULL_HANDLE;
    messenger_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
}

void Context::createInstance() {
    std::vector<const char*> layers;
    std::vector<const char*> extensions(desc_.instanceExtensions.begin(), desc_.instanceExtensions.end());
    bool debugUtils = hasInstanceExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
    bool syncFeatures = false;
    if (desc_.validation) {
        if (!hasLayer(kValidationLayer)) {
            throw std::runtime_error(
                "Vulkan validation was requested but VK_LAYER_KHRONOS_validation is not installed: install the "
                "Debian package vulkan-validationlayers (or run with validation off)");
        }
        if (!debugUtils) throw std::runtime_error("validation needs VK_EXT_debug_utils, which the loader lacks");
        layers.push_back(kValidationLayer);
        if (desc_.syncValidation && hasInstanceExtension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
            extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
            syncFeatures = true;
        }
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "idk-vk";
    app.pEngineName = "idk-vk";
    app.apiVersion = VK_API_VERSION_1_3;

    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger.pfnUserCallback = onValidationMessage;
    messenger.pUserData = validation_.get();

    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    // The messenger in pNext also reports problems inside vkCreateInstance / vkDestroyInstance.
    if (desc_.validation) {
        info.pNext = &messenger;
        if (syncFeatures) messenger.pNext = &features;
    }
    VkResult result = vkCreateInstance(&info, nullptr, &instance_);
    if (result != VK_SUCCESS) {
        throw Error(result, core::concat("vkCreateInstance failed (", resultName(result),
                                         "): is a Vulkan driver installed? (Debian: mesa-vulkan-drivers)"));
    }
    volkLoadInstanceOnly(instance_);
    if (desc_.validation) {
        messenger.pNext = nullptr;
        check(vkCreateDebugUtilsMessengerEXT(instance_, &messenger, nullptr, &messenger_));
    }
}

void Context::pickPhysicalDevice() {
    uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
    if (count == 0) {
        throw std::runtime_error(
            "no Vulkan device found: install a GPU driver, or Mesa's software rasterizer lavapipe (Debian package "
            "mesa-vulkan-drivers, version 24 or newer from bookworm-backports)");
    }
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance_, &count, devices.data()));
    if (desc_.deviceIndex) {
        if (*desc_.deviceIndex >= count) {
            std::string names;
            for (uint32_t i = 0; i < count; ++i) {
                VkPhysicalDeviceProperties props;
                vkGetPhysicalDeviceProperties(devices[i], &props);
                names += core::concat(i ? ", " : "", i, ": ", props.deviceName);
            }
            throw DeviceIndexError(core::concat("device ", *desc_.deviceIndex, " requested but the loader lists only ",
                                                count, " Vulkan device(s): ", names));
        }
        devices = {devices[*desc_.deviceIndex]};  // still checked against the baseline below
    }

    std::string rejected;
    int bestScore = -1;
    for (VkPhysicalDevice device : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(device, &props);
        if (!desc_.deviceNameFilter.empty() &&
            std::string(props.deviceName).find(desc_.deviceNameFilter) == std::string::npos) {
            rejected += core::concat("\n  ", props.deviceName, ": name does not match '", desc_.deviceNameFilter, "'");
            continue;
        }
        FeatureChain chain;
        chain.link(deviceExtensions(device));
        vkGetPhysicalDeviceFeatures2(device, &chain.core);
        std::vector<std::string> missing = missingBaseline(chain, props.apiVersion);
        if (desc_.presentation && !contains(deviceExtensions(device), VK_KHR_SWAPCHAIN_EXTENSION_NAME))
            missing.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        if (!missing.empty()) {
            std::string list;
            for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
            rejected += core::concat("\n  ", props.deviceName, ": lacks ", list);
            continue;
        }
        int score = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 4
                    : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 3
                    : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU    ? 2
                                                                                 : 1;
        if (score > bestScore) {
            bestScore = score;
            physical_ = device;
        }
    }
    if (!physical_) {
        throw std::runtime_error(core::concat(
            "no Vulkan device has the Vulkan 1.3 baseline idk-vk needs:", rejected,
            "\n(on Debian 12, lavapipe from bookworm-backports' mesa-vulkan-drivers 24+ has all of it)"));
    }
}

void Context::createDevice() {
    std::vector<std::string> exts = deviceExtensions(physical_);
    FeatureChain supported;
    supported.link(exts);
    vkGetPhysicalDeviceFeatures2(physical_, &supported.core);

    // Properties: limits, driver, subgroups, descriptor-indexing limits.
    VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
    VkPhysicalDeviceVulkan12Properties p12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES, &p11};
    VkPhysicalDeviceVulkan13Properties p13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES, &p12};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p13};
    // The VRS hardware rungs' texel sizes, chained only where the extension exists (vk/shading_rate.hpp).
    VkPhysicalDeviceFragmentShadingRatePropertiesKHR rateKhr{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FRAGMENT_SHADING_RATE_PROPERTIES_KHR};
    VkPhysicalDeviceShadingRateImagePropertiesNV rateNv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADING_RATE_IMAGE_PROPERTIES_NV};
    if (contains(exts, VK_KHR_FRAGMENT_SHADING_RATE_EXTENSION_NAME)) {
        rateKhr.pNext = p11.pNext;
        p11.pNext = &rateKhr;
    }
    if (contains(exts, VK_NV_SHADING_RATE_IMAGE_EXTENSION_NAME)) {
        rateNv.pNext = p11.pNext;
        p11.pNext = &rateNv;
    }
    vkGetPhysicalDeviceProperties2(physical_, &props);
    info_.name = props.properties.deviceName;
    info_.driverName = p12.driverName;
    info_.driverInfo = p12.driverInfo;
    info_.apiVersion = props.properties.apiVersion;
    info_.driverVersion = props.properties.driverVersion;
    info_.type = props.properties.deviceType;
    info_.limits = props.properties.limits;
    info_.maxBufferSize = p13.maxBufferSize;
    const DeviceLimitOverrides& o = desc_.limitOverrides;
    if (o.maxImageDimension2D) info_.limits.maxImageDimension2D = *o.maxImageDimension2D;
    if (o.maxStorageBufferRange) info_.limits.maxStorageBufferRange = *o.maxStorageBufferRange;
    if (o.maxBufferSize) info_.maxBufferSize = *o.maxBufferSize;
    info_.timestampPeriodNs = props.properties.limits.timestampPeriod;
    info_.maxSampledImagesUpdateAfterBind = std::min(p12.maxDescriptorSetUpdateAfterBindSampledImages,
                                                     p12.maxPerStageDescriptorUpdateAfterBindSampledImages);
    info_.maxStorageImagesUpdateAfterBind = std::min(p12.maxDescriptorSetUpdateAfterBindStorageImages,
                                                     p12.maxPerStageDescriptorUpdateAfterBindStorageImages);
    info_.maxStorageBuffersUpdateAfterBind = std::min(p12.maxDescriptorSetUpdateAfterBindStorageBuffers,
                                                      p12.maxPerStageDescriptorUpdateAfterBindStorageBuffers);
    info_.maxSamplersUpdateAfterBind = std::min(p12.maxDescriptorSetUpdateAfterBindSamplers,
                                                p12.maxPerStageDescriptorUpdateAfterBindSamplers);

    caps_.subgroupSize = p11.subgroupSize;
    caps_.minSubgroupSize = p13.minSubgroupSize;
    caps_.maxSubgroupSize = p13.maxSubgroupSize;
    caps_.subgroupArithmetic = (p11.subgroupSupportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT) &&
                               (p11.subgroupSupportedStages & VK_SHADER_STAGE_COMPUTE_BIT);
    caps_.meshShaderExt = supported.mesh.meshShader && supported.mesh.taskShader;
    {  // the Hi-Z pyramid's reduction sampler reads R32F depth (passes/depth_pyramid.cpp)
        VkFormatProperties r32f{};
        vkGetPhysicalDeviceFormatProperties(physical_, VK_FORMAT_R32_SFLOAT, &r32f);
        caps_.samplerFilterMinmax = supported.v12.samplerFilterMinmax &&
                                    (r32f.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_MINMAX_BIT);
    }
    {  // VXGI's packed directional volumes (frame/voxel_volume.hpp): written by compute, sampled trilinearly
        const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                          VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
        bool packed = supported.core.features.shaderStorageImageExtendedFormats;
        for (VkFormat format : {VK_FORMAT_B10G11R11_UFLOAT_PACK32, VK_FORMAT_R8_UNORM}) {
            VkFormatProperties props{};
            vkGetPhysicalDeviceFormatProperties(physical_, format, &props);
            VkImageFormatProperties image{};
            packed = packed && (props.optimalTilingFeatures & need) == need &&
                     vkGetPhysicalDeviceImageFormatProperties(
                         physical_, format, VK_IMAGE_TYPE_3D, VK_IMAGE_TILING_OPTIMAL,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                             VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0,
                         &image) == VK_SUCCESS;
        }
        caps_.packedVoxelFormats = packed;
    }
    caps_.meshShaderNv = contains(exts, "VK_NV_mesh_shader");
    caps_.fragmentShadingRate = supported.shadingRate.attachmentFragmentShadingRate;
    caps_.shadingRateImageNv = supported.shadingRateNv.shadingRateImage;
    caps_.shadingRateAttachmentTexel = {rateKhr.minFragmentShadingRateAttachmentTexelSize,
                                        rateKhr.maxFragmentShadingRateAttachmentTexelSize,
                                        rateKhr.maxFragmentShadingRateAttachmentTexelSizeAspectRatio};
    caps_.shadingRateTexelNv = rateNv.shadingRateTexelSize;
    caps_.rayQuery = supported.rayQuery.rayQuery && supported.accel.accelerationStructure;
    caps_.imageFloat32AtomicAdd = supported.atomicFloat.shaderImageFloat32AtomicAdd;
    caps_.imageFloat32AtomicMinMax = supported.atomicFloat2.shaderImageFloat32AtomicMinMax;
    caps_.float16VectorAtomicsNv = contains(exts, "VK_NV_shader_atomic_float16_vector");
    caps_.conservativeRasterization = contains(exts, VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
    caps_.geometryShader = supported.core.features.geometryShader;
    caps_.multiViewport = supported.core.features.multiViewport;
    caps_.geometryShaderPassthroughNv = contains(exts, VK_NV_GEOMETRY_SHADER_PASSTHROUGH_EXTENSION_NAME);
    caps_.viewportSwizzleNv = contains(exts, VK_NV_VIEWPORT_SWIZZLE_EXTENSION_NAME);
    caps_.shaderOutputLayer = supported.v12.shaderOutputLayer;
    caps_.externalMemoryFd = contains(exts, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    caps_.bufferFloat32AtomicAdd = supported.atomicFloat.shaderBufferFloat32AtomicAdd;
    caps_.shaderFloat16 = supported.v12.shaderFloat16;
    caps_.storage16Bit = supported.v11.storageBuffer16BitAccess;
    caps_.cpuDevice = info_.type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    ladders_ = buildLadders(caps_, LadderChoice{desc_.forceFallbackRungs, desc_.forcedRungs}, &forcedRungError_);

    // Queue: one family with graphics + compute (every desktop GPU and lavapipe have it), with timestamps.
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, families.data());
    queueFamily_ = UINT32_MAX;
    for (uint32_t i = 0; i < familyCount; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
            queueFamily_ = i;
            info_.timestampsSupported = families[i].timestampValidBits > 0;
            break;
        }
    }
    if (queueFamily_ == UINT32_MAX) throw std::runtime_error(info_.name + " has no graphics+compute queue family");

    // Enable: the baseline, plus every optional feature the device has (all are free to enable), except VRS:
    // only the mechanism the "vrs" ladder chose (the NV shading-rate image and the KHR fragment shading rates must
    // not be enabled together, VUID-VkDeviceCreateInfo-shadingRateImage-04478..04480).
    const std::vector<const char*> enabled = enabledExtensions(exts, ladders_, desc_.presentation);
    FeatureChain enable;
    enable.link(std::vector<std::string>(enabled.begin(), enabled.end()));
    VkPhysicalDeviceFeatures& c = enable.core.features;
    const VkPhysicalDeviceFeatures& s = supported.core.features;
    c.multiDrawIndirect = VK_TRUE;
    c.shaderInt64 = VK_TRUE;
    c.fragmentStoresAndAtomics = VK_TRUE;
    c.shaderStorageImageWriteWithoutFormat = VK_TRUE;
    c.shaderStorageImageReadWithoutFormat = s.shaderStorageImageReadWithoutFormat;
    c.shaderStorageImageExtendedFormats = s.shaderStorageImageExtendedFormats;  // VXGI's packed volumes
    c.vertexPipelineStoresAndAtomics = s.vertexPipelineStoresAndAtomics;
    c.geometryShader = s.geometryShader;
    c.samplerAnisotropy = s.samplerAnisotropy;
    c.independentBlend = s.independentBlend;
    c.imageCubeArray = s.imageCubeArray;
    c.depthClamp = s.depthClamp;
    c.fillModeNonSolid = s.fillModeNonSolid;
    c.shaderInt16 = s.shaderInt16;
    c.multiViewport = s.multiViewport;
    c.drawIndirectFirstInstance = s.drawIndirectFirstInstance;
    c.shaderImageGatherExtended = s.shaderImageGatherExtended;
    enable.v11.shaderDrawParameters = VK_TRUE;
    enable.v11.storageBuffer16BitAccess = supported.v11.storageBuffer16BitAccess;
    VkPhysicalDeviceVulkan12Features& e12 = enable.v12;
    const VkPhysicalDeviceVulkan12Features& s12 = supported.v12;
    e12.bufferDeviceAddress = VK_TRUE;
    e12.timelineSemaphore = VK_TRUE;
    e12.scalarBlockLayout = VK_TRUE;
    e12.drawIndirectCount = VK_TRUE;
    e12.hostQueryReset = VK_TRUE;
    e12.descriptorIndexing = VK_TRUE;
    e12.runtimeDescriptorArray = VK_TRUE;
    e12.descriptorBindingPartiallyBound = VK_TRUE;
    e12.descriptorBindingVariableDescriptorCount = VK_TRUE;
    e12.descriptorBindingSampledImageUpdateAfterBind = VK_TRUE;
    e12.descriptorBindingStorageImageUpdateAfterBind = VK_TRUE;
    e12.descriptorBindingStorageBufferUpdateAfterBind = VK_TRUE;
    e12.descriptorBindingUpdateUnusedWhilePending = VK_TRUE;
    e12.shaderSampledImageArrayNonUniformIndexing = VK_TRUE;
    e12.shaderStorageBufferArrayNonUniformIndexing = VK_TRUE;
    e12.shaderStorageImageArrayNonUniformIndexing = s12.shaderStorageImageArrayNonUniformIndexing;
    e12.shaderFloat16 = s12.shaderFloat16;
    e12.shaderInt8 = s12.shaderInt8;
    e12.storageBuffer8BitAccess = s12.storageBuffer8BitAccess;
    e12.vulkanMemoryModel = s12.vulkanMemoryModel;
    e12.vulkanMemoryModelDeviceScope = s12.vulkanMemoryModelDeviceScope;
    e12.shaderOutputLayer = s12.shaderOutputLayer;
    e12.shaderOutputViewportIndex = s12.shaderOutputViewportIndex;
    e12.samplerFilterMinmax = s12.samplerFilterMinmax;
    e12.shaderBufferInt64Atomics = s12.shaderBufferInt64Atomics;
    enable.v13.dynamicRendering = VK_TRUE;
    enable.v13.synchronization2 = VK_TRUE;
    enable.v13.maintenance4 = VK_TRUE;
    enable.v13.subgroupSizeControl = supported.v13.subgroupSizeControl;
    enable.v13.computeFullSubgroups = supported.v13.computeFullSubgroups;
    enable.mesh.meshShader = supported.mesh.meshShader;
    enable.mesh.taskShader = supported.mesh.taskShader;
    enable.atomicFloat.shaderImageFloat32AtomicAdd = supported.atomicFloat.shaderImageFloat32AtomicAdd;
    enable.atomicFloat.shaderImageFloat32Atomics = supported.atomicFloat.shaderImageFloat32Atomics;
    enable.atomicFloat.shaderBufferFloat32AtomicAdd = supported.atomicFloat.shaderBufferFloat32AtomicAdd;
    enable.atomicFloat.shaderBufferFloat32Atomics = supported.atomicFloat.shaderBufferFloat32Atomics;
    enable.atomicFloat2.shaderImageFloat32AtomicMinMax = supported.atomicFloat2.shaderImageFloat32AtomicMinMax;
    enable.atomicFloat2.shaderBufferFloat32AtomicMinMax = supported.atomicFloat2.shaderBufferFloat32AtomicMinMax;
    enable.shadingRate.attachmentFragmentShadingRate = supported.shadingRate.attachmentFragmentShadingRate;
    enable.shadingRate.pipelineFragmentShadingRate = supported.shadingRate.pipelineFragmentShadingRate;
    enable.shadingRateNv.shadingRateImage = supported.shadingRateNv.shadingRateImage;
    enable.rayQuery.rayQuery = supported.rayQuery.rayQuery;
    enable.accel.accelerationStructure = supported.accel.accelerationStructure;

    enabledDeviceExtensions_ = enabled;

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = queueFamily_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable.core};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.enabledExtensionCount = static_cast<uint32_t>(enabled.size());
    info.ppEnabledExtensionNames = enabled.data();
    VkResult result = vkCreateDevice(physical_, &info, nullptr, &device_);
    if (result != VK_SUCCESS) throw Error(result, "vkCreateDevice failed on " + info_.name + ": " + resultName(result));
    volkLoadDevice(device_);
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
}

const Ladder& Context::ladder(const std::string& feature) const {
    for (size_t i = 0; i < ladders_.size(); ++i) {
        if (ladders_[i].feature != feature && ladders_[i].id != feature) continue;
        std::lock_guard lock(consultedMutex_);
        if (std::find(consulted_.begin(), consulted_.end(), i) == consulted_.end()) consulted_.push_back(i);
        return ladders_[i];
    }
    throw std::logic_error("unknown capability ladder '" + feature + "'");
}

void Context::clearConsultedLadders() {
    std::lock_guard lock(consultedMutex_);
    consulted_.clear();
}

std::vector<Ladder> Context::consultedLadders() const {
    std::lock_guard lock(consultedMutex_);
    std::vector<Ladder> out;
    for (size_t i : consulted_) out.push_back(ladders_[i]);
    return out;
}

std::vector<std::string> Context::validationMessages() const {
    std::lock_guard lock(validation_->mutex);
    return validation_->messages;
}

void Context::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!vkSetDebugUtilsObjectNameEXT || name.empty() || handle == 0) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    vkSetDebugUtilsObjectNameEXT(device_, &info);
}

Buffer Context::createBuffer(const BufferDesc& desc) {
    if (desc.size == 0) throw std::invalid_argument("createBuffer '" + desc.name + "': size is zero");
    if (desc.size > info_.maxBufferSize)
        throw DeviceLimitError("buffer '" + desc.name + "' needs " + std::to_string(desc.size) +
                               " bytes, more than the device's maxBufferSize (" + std::to_string(info_.maxBufferSize) +
                               "); the scene or the settings are too large for this device");
    Buffer b;
    b.size = desc.size;
    b.name = desc.name;
    b.usage = desc.usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
              VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = desc.size;
    info.usage = b.usage;
    check(vkCreateBuffer(device_, &info, nullptr, &b.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, b.buffer, &req);
    try {  // out of device memory is an exception a caller may survive: leave nothing behind
        b.allocation = allocator_->allocate(req, desc.memory, ResourceTiling::Linear, desc.category);
    } catch (...) {
        vkDestroyBuffer(device_, b.buffer, nullptr);
        throw;
    }
    {
        std::lock_guard lock(liveMutex_);
        liveBuffers_[b.buffer] = b;
    }
    check(vkBindBufferMemory(device_, b.buffer, b.allocation.memory, b.allocation.offset));
    VkBufferDeviceAddressInfo address{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    address.buffer = b.buffer;
    b.address = vkGetBufferDeviceAddress(device_, &address);
    setName(b.buffer, VK_OBJECT_TYPE_BUFFER, desc.name);
    return b;
}

Image Context::createImage(const ImageDesc& desc) {
    const bool volume = desc.type == VK_IMAGE_TYPE_3D;
    const uint32_t maxSize = volume ? info_.limits.maxImageDimension3D : info_.limits.maxImageDimension2D;
    if (std::max({desc.extent.width, desc.extent.height, volume ? desc.extent.depth : 1u}) > maxSize)
        throw DeviceLimitError("image '" + desc.name + "' (" + std::to_string(desc.extent.width) + "x" +
                               std::to_string(desc.extent.height) + (volume ? "x" + std::to_string(desc.extent.depth) : "") +
                               ") exceeds the device's " + (volume ? "maxImageDimension3D" : "maxImageDimension2D") + " (" +
                               std::to_string(maxSize) + ")");
    Image img;
    img.format = desc.format;
    img.type = desc.type;
    img.extent = desc.extent;
    img.mipLevels = desc.mipLevels;
    img.layers = desc.layers;
    img.name = desc.name;
    img.usage = desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ImageDesc withTransfers = desc;
    withTransfers.usage = img.usage;
    VkImageCreateInfo info = imageCreateInfo(withTransfers);
    check(vkCreateImage(device_, &info, nullptr, &img.image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, img.image, &req);
    try {
        img.allocation = allocator_->allocate(req, MemoryUsage::GpuOnly, ResourceTiling::Optimal, desc.category);
    } catch (...) {
        vkDestroyImage(device_, img.image, nullptr);
        throw;
    }
    {
        std::lock_guard lock(liveMutex_);
        liveImages_[img.image] = img;
    }
    check(vkBindImageMemory(device_, img.image, img.allocation.memory, img.allocation.offset));

    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = img.image;
    view.viewType = viewTypeOf(desc);
    view.format = desc.format;
    view.subresourceRange = {aspectOf(desc.format), 0, desc.mipLevels, 0, desc.layers};
    check(vkCreateImageView(device_, &view, nullptr, &img.view));
    {
        std::lock_guard lock(liveMutex_);
        liveImages_[img.image].view = img.view;
    }
    setName(img.image, VK_OBJECT_TYPE_IMAGE, desc.name);
    setName(img.view, VK_OBJECT_TYPE_IMAGE_VIEW, desc.name + " view");
    return img;
}

void Context::destroy(Buffer& b) {
    if (!b.buffer) return;
    {
        std::lock_guard lock(liveMutex_);
        liveBuffers_.erase(b.buffer);
    }
    vkDestroyBuffer(device_, b.buffer, nullptr);
    allocator_->free(b.allocation);
    b = {};
}

void Context::destroy(Image& img) {
    if (!img.image) return;
    {
        std::lock_guard lock(liveMutex_);
        liveImages_.erase(img.image);
    }
    vkDestroyImageView(device_, img.view, nullptr);
    vkDestroyImage(device_, img.image, nullptr);
    allocator_->free(img.allocation);
    img = {};
}

void Context::releaseLeftovers() {
    std::vector<Buffer> buffers;
    std::vector<Image> images;
    for (auto& [handle, b] : liveBuffers_) buffers.push_back(b);
    for (auto& [handle, img] : liveImages_) images.push_back(img);
    if ((!buffers.empty() || !images.empty()) && !failed_ && std::uncaught_exceptions() == 0) {
        std::string names;
        for (const Buffer& b : buffers) names += (names.empty() ? "" : ", ") + b.name;
        for (const Image& img : images) names += (names.empty() ? "" : ", ") + img.name;
        core::logWarning(buffers.size(), " buffer(s) and ", images.size(),
                         " image(s) were never destroyed; released with the device: ", names);
    }
    for (Buffer& b : buffers) destroy(b);
    for (Image& img : images) destroy(img);
}

void Context::destroyDeferred(Buffer& b) {
    if (!b.buffer) return;
    destroyDeferred([this, moved = b]() mutable { destroy(moved); });
    b = {};
}

void Context::destroyDeferred(Image& img) {
    if (!img.image) return;
    destroyDeferred([this, moved = img]() mutable { destroy(moved); });
    img = {};
}

void Context::destroyDeferred(std::function<void()> release) {
    std::lock_guard lock(deferredMutex_);
    deferred_.push_back({lastSubmitted_, std::move(release)});
}

void Context::collectGarbage() {
    uint64_t done = completedValue();
    std::vector<std::function<void()>> ready;
    {
        std::lock_guard lock(deferredMutex_);
        while (!deferred_.empty() && deferred_.front().afterValue <= done) {
            ready.push_back(std::move(deferred_.front().release));
            deferred_.pop_front();
        }
    }
    for (auto& release : ready) release();
}

uint64_t Context::submit(VkCommandBuffer cmd, std::span<const VkSemaphoreSubmitInfo> waits,
                         std::span<const VkSemaphoreSubmitInfo> signals) {
    std::lock_guard lock(submitMutex_);
    uint64_t value = lastSubmitted_ + 1;
    std::vector<VkSemaphoreSubmitInfo> allSignals(signals.begin(), signals.end());
    VkSemaphoreSubmitInfo timelineSignal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    timelineSignal.semaphore = timeline_;
    timelineSignal.value = value;
    timelineSignal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    allSignals.push_back(timelineSignal);

    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.waitSemaphoreInfoCount = static_cast<uint32_t>(waits.size());
    submit.pWaitSemaphoreInfos = waits.data();
    submit.commandBufferInfoCount = cmd ? 1 : 0;
    submit.pCommandBufferInfos = &cmdInfo;
    submit.signalSemaphoreInfoCount = static_cast<uint32_t>(allSignals.size());
    submit.pSignalSemaphoreInfos = allSignals.data();
    if (lost_) throwResult(VK_ERROR_DEVICE_LOST, "queue submission after the device was lost (VK_ERROR_DEVICE_LOST)");
    const InjectedFailure injected = nextSubmission();
    if (injected.result != VK_SUCCESS) {
        failed_ = true;
        if (injected.result == VK_ERROR_DEVICE_LOST) lost_ = true;
        throwResult(injected.result, core::concat("vkQueueSubmit2 failed with ", resultName(injected.result),
                                                  " (submission ", injected.submission,
                                                  ", simulated by IDK_TEST_FAIL_SUBMIT)"));
    }
    const VkResult result = vkQueueSubmit2(queue_, 1, &submit, VK_NULL_HANDLE);
    if (result < 0) failed_ = true;
    if (result == VK_ERROR_DEVICE_LOST) lost_ = true;
    check(result);
    lastSubmitted_ = value;
    return value;
}

void Context::waitFor(uint64_t value) {
    if (lost_) return;  // nothing will ever complete; see deviceLost()
    VkSemaphoreWaitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
    wait.semaphoreCount = 1;
    wait.pSemaphores = &timeline_;
    wait.pValues = &value;
    const VkResult result = vkWaitSemaphores(device_, &wait, UINT64_MAX);
    if (result == VK_ERROR_DEVICE_LOST) lost_ = failed_ = true;
    check(result);
}

uint64_t Context::completedValue() const {
    if (lost_) return lastSubmitted_;  // treated as complete so deferred releases run during teardown
    uint64_t value = 0;
    check(vkGetSemaphoreCounterValue(device_, timeline_, &value));
    return value;
}

void Context::runImmediate(const std::function<void(VkCommandBuffer)>& fn) {
    std::lock_guard lock(immediateMutex_);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = immediatePool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(device_, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin));
    try {
        fn(cmd);
    } catch (...) {
        vkEndCommandBuffer(cmd);
        vkFreeCommandBuffers(device_, immediatePool_, 1, &cmd);
        throw;
    }
    check(vkEndCommandBuffer(cmd));
    uint64_t value = submit(cmd);
    waitFor(value);
    vkFreeCommandBuffers(device_, immediatePool_, 1, &cmd);
    collectGarbage();
}

void Context::waitIdle() {
    if (!lost_) {
        const VkResult result = vkDeviceWaitIdle(device_);
        if (result == VK_ERROR_DEVICE_LOST) lost_ = failed_ = true;
        check(result);
    }
    collectGarbage();
}

}  // namespace idk::vk
