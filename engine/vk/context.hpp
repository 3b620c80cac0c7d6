// context.hpp: the Vulkan device layer's centre. Owns the instance, the debug messenger (which counts
// validation messages so tests can fail on any error), the physical device chosen by required and optional
// features, one graphics+compute queue, the memory allocator, the bindless table, the global pipeline layout,
// one timeline semaphore that orders every submission, and a deferred-destruction queue keyed on it.
#pragma once
#include <volk.h>

#include <atomic>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "vk/features.hpp"
#include "vk/memory.hpp"
#include "vk/resources.hpp"

namespace idk::gl {
class GlContext;
}

namespace idk::vk {

class BindlessTable;

// Test-only: the device pretends to have these smaller limits, so tests of the "too large for the device" errors
// stay small (a 4 KiB buffer instead of a 128 MiB scene).
struct DeviceLimitOverrides {
    std::optional<uint32_t> maxImageDimension2D;
    std::optional<uint32_t> maxStorageBufferRange;
    std::optional<VkDeviceSize> maxBufferSize;
};

// ContextDesc::deviceIndex names no device the loader lists: the message lists those it does ("0: llvmpipe ...").
class DeviceIndexError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A resource larger than a device limit allows: the message names the resource, its size and the limit (instead
// of the validation error or driver failure creating it would give).
class DeviceLimitError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ContextDesc {
    bool validation = IDK_DEFAULT_VALIDATION;          // messenger counts errors; GPU tests assert zero
    bool syncValidation = IDK_DEFAULT_SYNC_VALIDATION;  // VkValidationFeaturesEXT synchronization checks
    bool forceStaging = IDK_DEFAULT_FORCE_STAGING;      // never map GPU-only memory, even on UMA (lavapipe)
    bool forceFallbackRungs = false;                    // choose the portable rung on every ladder
    std::vector<RungForce> forcedRungs;                 // --rung LADDER=RUNG (wins over forceFallbackRungs)
    std::vector<const char*> instanceExtensions;        // window-system extensions; empty = headless
    bool presentation = false;                          // require VK_KHR_swapchain
    std::string deviceNameFilter;                       // substring; also env IDK_DEVICE
    std::optional<uint32_t> deviceIndex;                // that device of vkEnumeratePhysicalDevices (idk --device N)
    // Probe the GL-interop rung at start-up (a headless GL context and a round trip; gl/interop_probe.hpp). The
    // `idk` commands do; tests that need the rung ask for it. Off: the GL rungs say "not probed".
    bool probeGlInterop = false;
    DeviceLimitOverrides limitOverrides;                // tests only
};

// Counts and keeps the validation layer's messages.
struct ValidationLog {
    std::atomic<uint32_t> errors{0};
    std::atomic<uint32_t> warnings{0};
    std::mutex mutex;
    std::vector<std::string> messages;  // errors and warnings, first 256
};

struct DeviceInfo {
    std::string name;
    std::string driverName;
    std::string driverInfo;
    uint32_t apiVersion = 0;
    uint32_t driverVersion = 0;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    VkPhysicalDeviceLimits limits{};
    VkDeviceSize maxBufferSize = 0;  // Vulkan 1.3 (maintenance4): the largest VkBuffer
    uint32_t maxSampledImagesUpdateAfterBind = 0;
    uint32_t maxStorageImagesUpdateAfterBind = 0;
    uint32_t maxStorageBuffersUpdateAfterBind = 0;
    uint32_t maxSamplersUpdateAfterBind = 0;
    float timestampPeriodNs = 1.0f;
    bool timestampsSupported = false;
    bool uma = false;
};

class Context {
public:
    explicit Context(const ContextDesc& desc = {});  // throws vk::Error / std::runtime_error naming what is missing
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const noexcept { return instance_; }
    VkPhysicalDevice physicalDevice() const noexcept { return physical_; }
    VkDevice device() const noexcept { return device_; }
    VkQueue queue() const noexcept { return queue_; }
    uint32_t queueFamily() const noexcept { return queueFamily_; }
    const DeviceInfo& info() const noexcept { return info_; }
    const DeviceCapabilities& capabilities() const noexcept { return caps_; }
    const std::vector<Ladder>& ladders() const noexcept { return ladders_; }
    // By feature name or id; throws if unknown. Records the ladder as consulted: the code asking is about to run
    // its chosen rung, so consultedLadders() lists the rungs that ran (`idk render --json`, benchmark labels).
    const Ladder& ladder(const std::string& feature) const;
    std::vector<Ladder> consultedLadders() const;  // in first-use order
    void clearConsultedLadders();                  // a benchmark sharing the context starts its own list
    // Why a desc.forcedRungs entry could not be taken (the device lacks it); empty when all were. Callers that
    // forced rungs check it and refuse to run (the CLI exits 2).
    const std::string& forcedRungError() const noexcept { return forcedRungError_; }
    const ContextDesc& desc() const noexcept { return desc_; }
    // The probed OpenGL context of the GL-interop rung; nullptr when not probed or unavailable
    // (capabilities().glInteropNote says why).
    const gl::GlContext* glContext() const noexcept { return gl_.get(); }
    MemoryAllocator& allocator() noexcept { return *allocator_; }
    BindlessTable& bindless() noexcept { return *bindless_; }
    VkPipelineLayout pipelineLayout() const noexcept { return pipelineLayout_; }

    // Validation messages seen so far (errors fail tests).
    uint32_t validationErrors() const noexcept { return validation_->errors.load(); }
    uint32_t validationWarnings() const noexcept { return validation_->warnings.load(); }
    std::vector<std::string> validationMessages() const;

    // Resources. Names become debug names. destroy() is immediate (caller guarantees the GPU is done);
    // destroyDeferred() waits until every submission made so far has completed. The context keeps a list of the
    // live buffers and images: whatever an exception unwound past (a staging buffer whose copy failed to submit,
    // say) is destroyed with the device, silently after a failed submission, else with a warning naming it.
    Buffer createBuffer(const BufferDesc& desc);
    Image createImage(const ImageDesc& desc);
    void destroy(Buffer& buffer);
    void destroy(Image& image);
    void destroyDeferred(Buffer& buffer);
    void destroyDeferred(Image& image);
    void destroyDeferred(std::function<void()> release);  // any other object
    void collectGarbage();                                // runs deferred releases whose submissions completed

    // Submission. All submissions signal the one timeline semaphore with increasing values.
    uint64_t submit(VkCommandBuffer cmd, std::span<const VkSemaphoreSubmitInfo> waits = {},
                    std::span<const VkSemaphoreSubmitInfo> signals = {});
    void waitFor(uint64_t timelineValue);
    uint64_t completedValue() const;
    uint64_t lastSubmittedValue() const noexcept { return lastSubmitted_; }
    VkSemaphore timeline() const noexcept { return timeline_; }
    // Records with fn into a one-time command buffer, submits and waits (uploads, readbacks, tests).
    void runImmediate(const std::function<void(VkCommandBuffer)>& fn);
    void waitIdle();

    // Device loss. The first VK_ERROR_DEVICE_LOST seen by submit/waitFor/waitIdle (or reported through markLost()
    // by a caller that saw it elsewhere, e.g. at present) throws vk::DeviceLostError and marks the context lost:
    // later submissions throw again, while waits return at once and treat everything as complete, so unwinding can
    // destroy every object (what the spec asks after a loss) without waiting for work that never finishes. The test
    // hook IDK_TEST_FAIL_SUBMIT (fault_injection.hpp) makes a chosen submission fail this way.
    bool deviceLost() const noexcept { return lost_.load(); }
    void markLost() noexcept { lost_ = failed_ = true; }

    void setName(VkObjectType type, uint64_t handle, const std::string& name) const;
    template <class T>
    void setName(T handle, VkObjectType type, const std::string& name) const {
        setName(type, reinterpret_cast<uint64_t>(handle), name);
    }

private:
    void createInstance();
    void pickPhysicalDevice();
    void createDevice();

    ContextDesc desc_;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    DeviceInfo info_;
    DeviceCapabilities caps_;
    std::vector<Ladder> ladders_;
    std::string forcedRungError_;
    std::unique_ptr<gl::GlContext> gl_;
    mutable std::mutex consultedMutex_;
    mutable std::vector<size_t> consulted_;  // indices into ladders_
    std::vector<const char*> enabledDeviceExtensions_;
    std::unique_ptr<ValidationLog> validation_;
    std::unique_ptr<MemoryAllocator> allocator_;
    std::unique_ptr<BindlessTable> bindless_;
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;

    VkSemaphore timeline_ = VK_NULL_HANDLE;
    uint64_t lastSubmitted_ = 0;
    std::atomic<bool> lost_{false};
    std::atomic<bool> failed_{false};  // a submission threw: leftovers at destruction are expected
    std::mutex liveMutex_;
    std::unordered_map<VkBuffer, Buffer> liveBuffers_;
    std::unordered_map<VkImage, Image> liveImages_;
    void destroyAll() noexcept;  // the destructor's body (also for a constructor that throws late)
    void releaseLeftovers();
    std::mutex submitMutex_;
    std::mutex immediateMutex_;  // command pools are externally synchronized
    VkCommandPool immediatePool_ = VK_NULL_HANDLE;

    struct Deferred {
        uint64_t afterValue;
        std::function<void()> release;
    };
    std::mutex deferredMutex_;
    std::deque<Deferred> deferred_;
};

}  // namespace idk::vk
