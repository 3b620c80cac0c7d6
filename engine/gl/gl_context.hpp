// gl_context.hpp: a headless OpenGL 4.5 core context through EGL (Mesa's surfaceless platform, else the device
// platform), for the GL-interop capability rung: GL runs the steps that need a GL-only extension on memory that
// Vulkan exported (shared_memory.hpp). libEGL is opened with dlopen, so a machine without it still runs: create()
// returns nullptr and says why. IDK_GL_INTEROP=off skips EGL entirely (tests of the "no GL" path use it).
#pragma once
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/gl_api.hpp"

namespace idk::gl {

class GlError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// How Vulkan and GL order their work on shared memory (gl_sync.hpp): GPU-side with exported semaphores where both
// APIs have them, else CPU-side waits. `why` says what decided it (shown by `idk info`).
enum class SyncMode : uint8_t { CpuWait, Semaphores };
struct SyncChoice {
    SyncMode mode = SyncMode::CpuWait;
    std::string why = "not probed";
};

struct EglLibrary;

class GlContext {
public:
    // nullptr when no OpenGL 4.5 context can be created; *whyNot names the cause (no libEGL, no platform, ...).
    static std::unique_ptr<GlContext> create(std::string* whyNot);
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    // GL calls are made only inside a Current scope: it locks the context (EGL contexts are current on one
    // thread at a time) and makes it current on the calling thread, then releases it.
    class Current {
    public:
        explicit Current(const GlContext& ctx);
        ~Current();
        Current(const Current&) = delete;
        Current& operator=(const Current&) = delete;

    private:
        const GlContext& ctx_;
        std::unique_lock<std::mutex> lock_;
    };

    const Api& api() const noexcept { return api_; }
    bool hasExtension(const std::string& name) const;
    const std::string& version() const noexcept { return version_; }    // GL_VERSION
    const std::string& renderer() const noexcept { return renderer_; }  // GL_RENDERER, e.g. "llvmpipe (...)"
    const std::string& platform() const noexcept { return platform_; }  // "surfaceless" or "device N"
    // GL_EXT_memory_object's device and driver UUIDs: Vulkan memory imports only into a context whose UUIDs match
    // the Vulkan device's (VkPhysicalDeviceIDProperties). Empty when the extension is missing.
    const std::vector<uint8_t>& deviceUuid() const noexcept { return deviceUuid_; }
    const std::vector<uint8_t>& driverUuid() const noexcept { return driverUuid_; }
    // The probe's choice (interop_probe.cpp); every hand-off on this context follows it.
    const SyncChoice& sync() const noexcept { return sync_; }
    void setSync(SyncChoice choice) { sync_ = std::move(choice); }
    // Throws GlError naming `what` and the GL error code if the last calls raised one (current context only).
    void check(const std::string& what) const;

private:
    GlContext() = default;
    bool init(std::string* whyNot);
    bool tryDisplay(void* display, const std::string& platform, std::string* whyNot);

    std::shared_ptr<EglLibrary> egl_;
    void* display_ = nullptr;
    void* context_ = nullptr;
    mutable std::mutex mutex_;
    Api api_;
    std::vector<std::string> extensions_;
    std::string version_, renderer_, platform_;
    std::vector<uint8_t> deviceUuid_, driverUuid_;
    SyncChoice sync_;
};

}  // namespace idk::gl
