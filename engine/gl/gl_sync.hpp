// gl_sync.hpp: how Vulkan and OpenGL take turns on shared memory (shared_memory.hpp), in one place for every GL pass
// (render/float_splat.cpp, passes/vxgi_gl_accumulate.cpp). Two modes, chosen once by the start-up probe:
//
// - Semaphores, where GL has GL_EXT_semaphore_fd and the device VK_KHR_external_semaphore_fd: two binary Vulkan
//   semaphores exported as opaque fds and imported into GL. Vulkan's submission holding the release barriers
//   signals "to GL"; GL waits for it (glWaitSemaphoreEXT, naming the buffers and textures), runs, signals "to
//   Vulkan" (glSignalSemaphoreEXT) and flushes; a Vulkan submission holding the acquire barriers waits for it. No
//   thread waits for either API.
// - CPU-side waits, elsewhere (llvmpipe, this machine: it has neither extension) or with IDK_GL_SYNC=cpu: Vulkan's
//   release submission is waited for on the context's timeline, GL ends with glFinish, and the acquire barriers go
//   into the caller's next command buffer.
//
// The four steps are the same in both modes (submitToGl, glBegin, glEnd, resumeVulkan): the passes do not branch.
#pragma once
#include <volk.h>

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "gl/gl_context.hpp"

namespace idk::vk {
class Context;
}

namespace idk::gl {

struct SyncCapabilities {
    bool vkSemaphoreFd = false;  // VK_KHR_external_semaphore_fd enabled, binary semaphores exportable as opaque fds
    bool glSemaphoreFd = false;  // GL_EXT_semaphore + GL_EXT_semaphore_fd, their entry points loaded
};

// The mode for `caps`. `override` is IDK_GL_SYNC's value (nullptr when unset): "cpu" forces CPU-side waits, "auto"
// or unset takes semaphores where both sides have them; any other value is refused (CPU-side waits, and `why`
// names the value). Pure: the unit test passes fake capability sets.
SyncChoice chooseSyncMode(const SyncCapabilities& caps, const char* override);
// What `idk info` prints after "sync: ", e.g. "semaphores (GL_EXT_semaphore_fd + VK_KHR_external_semaphore_fd)".
std::string syncText(const SyncChoice& choice);
const char* syncModeName(SyncMode mode);  // "semaphores" / "cpu-wait" (--json)
// What this device and GL context offer (the probe passes it to chooseSyncMode with getenv("IDK_GL_SYNC")).
SyncCapabilities querySyncCapabilities(const vk::Context& ctx, const GlContext& gl);

// One pass's hand-offs, in the mode of gl.sync(). Use from one thread at a time (it records into a command pool of
// its own). The steps must come in order, once each per hand-off; out of order they throw std::logic_error.
class HandOff {
public:
    // Semaphore mode: creates, exports and imports the two semaphores (throws vk::Error / GlError).
    HandOff(vk::Context& ctx, const GlContext& gl, const std::string& name);
    // Semaphore mode: makes the context current itself (glFinish, then the GL semaphores go), so destroy it outside
    // a GlContext::Current scope (the context's lock is not recursive).
    ~HandOff();
    HandOff(const HandOff&) = delete;
    HandOff& operator=(const HandOff&) = delete;

    bool usesSemaphores() const noexcept { return semaphores_; }

    // 1. Vulkan -> GL. `cmd` is ended and holds the release barriers (releaseToGl) after the work GL consumes.
    //    CPU-wait mode: submits it and waits until it completed. Semaphore mode: submits it signalling "to GL".
    void submitToGl(VkCommandBuffer cmd);
    //    The same, recording `release` into a command buffer of the hand-off's own.
    void submitToGl(const std::function<void(VkCommandBuffer)>& release);
    // 2. Inside GlContext::Current, before GL touches the shared objects. Semaphore mode: glWaitSemaphoreEXT on
    //    "to GL" with them; textures come from GENERAL (the layout releaseToGl leaves). CPU-wait mode: nothing.
    void glBegin(std::span<const GLuint> buffers, std::span<const GLuint> textures = {});
    // 3. Inside GlContext::Current, after GL's last command on them. Semaphore mode: glSignalSemaphoreEXT on "to
    //    Vulkan" (textures left in GENERAL, what acquireFromGl expects) and glFlush, so the signal reaches the GPU.
    //    CPU-wait mode: glFinish.
    void glEnd(std::span<const GLuint> buffers, std::span<const GLuint> textures = {});
    // 4. GL -> Vulkan. `acquire` records the acquire barriers (acquireFromGl). CPU-wait mode: into `next`, the
    //    caller's command buffer, submitted later. Semaphore mode: into a command buffer of the hand-off's own,
    //    submitted now waiting for "to Vulkan"; its barriers order every later command on the queue (`next`
    //    included: a pipeline barrier's scopes follow submission order across submissions) after GL's work.
    //    When GL threw between glBegin and glEnd, the barriers go into `next` unwaited and the hand-off refuses
    //    further use (its semaphores are out of step). Returns the submission's timeline value (0: none).
    uint64_t resumeVulkan(VkCommandBuffer next, const std::function<void(VkCommandBuffer)>& acquire);

private:
    enum class Step { Vulkan, GlReady, GlRunning, GlDone, Broken };
    VkCommandBuffer ownCommandBuffer();  // reuses one whose submission completed
    void expect(Step step, const char* call) const;
    void release() noexcept;

    vk::Context& ctx_;
    const GlContext& gl_;
    std::string name_;
    bool semaphores_ = false;
    Step step_ = Step::Vulkan;
    VkSemaphore toGl_ = VK_NULL_HANDLE, toVulkan_ = VK_NULL_HANDLE;
    GLuint glToGl_ = 0, glToVulkan_ = 0;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    struct Recorded {
        VkCommandBuffer cmd;
        uint64_t value;  // timeline value of its submission
    };
    std::vector<Recorded> commandBuffers_;
};

}  // namespace idk::gl
