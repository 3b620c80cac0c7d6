// gl_sync.cpp: see gl_sync.hpp. The semaphore path follows VK_KHR_external_semaphore_fd and GL_EXT_semaphore(_fd):
// - the semaphores are binary (GL_EXT_semaphore imports binary payloads), created with VkExportSemaphoreCreateInfo
//   for OPAQUE_FD (reference transference: GL's semaphore object and Vulkan's share one payload for good);
// - vkGetSemaphoreFdKHR makes a new fd per call, and a successful glImportSemaphoreFdEXT takes ownership of it
//   (the application must not use or close it afterwards); on a failed import it is still ours and is closed;
// - each binary semaphore alternates signal, wait: "to GL" is signalled by Vulkan and waited by GL, "to Vulkan"
//   the reverse, once per hand-off;
// - glWaitSemaphoreEXT / glSignalSemaphoreEXT name the buffers and textures whose memory crosses the boundary; a
//   texture's layout is the Vulkan layout it is in (GL_LAYOUT_GENERAL_EXT: releaseToGl and acquireFromGl keep
//   shared images in VK_IMAGE_LAYOUT_GENERAL).
// The validation layers see only Vulkan's half of each pair (GL's signal and wait are invisible to them); this
// machine has no driver with both extensions, so the semaphore path is compiled and reviewed, not run, here.
#include "gl/gl_sync.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::gl {

SyncChoice chooseSyncMode(const SyncCapabilities& caps, const char* override) {
    const std::string value = override ? override : "";
    if (value == "cpu") return {SyncMode::CpuWait, "forced by IDK_GL_SYNC=cpu"};
    if (!value.empty() && value != "auto")
        return {SyncMode::CpuWait, "IDK_GL_SYNC=" + value + " is neither 'cpu' nor 'auto'"};
    if (caps.glSemaphoreFd && caps.vkSemaphoreFd)
        return {SyncMode::Semaphores, "GL_EXT_semaphore_fd + VK_KHR_external_semaphore_fd"};
    if (!caps.glSemaphoreFd && !caps.vkSemaphoreFd)
        return {SyncMode::CpuWait, "GL lacks GL_EXT_semaphore_fd and the device lacks VK_KHR_external_semaphore_fd"};
    if (!caps.glSemaphoreFd) return {SyncMode::CpuWait, "GL lacks GL_EXT_semaphore_fd"};
    return {SyncMode::CpuWait, "the device lacks VK_KHR_external_semaphore_fd with opaque-fd export"};
}

std::string syncText(const SyncChoice& choice) {
    return (choice.mode == SyncMode::Semaphores ? "semaphores (" : "CPU-side waits (") + choice.why + ")";
}

const char* syncModeName(SyncMode mode) { return mode == SyncMode::Semaphores ? "semaphores" : "cpu-wait"; }

SyncCapabilities querySyncCapabilities(const vk::Context& ctx, const GlContext& gl) {
    SyncCapabilities caps;
    caps.glSemaphoreFd = gl.hasExtension("GL_EXT_semaphore") && gl.hasExtension("GL_EXT_semaphore_fd") &&
                         gl.api().hasSemaphoreFunctions();
    // The context enables VK_KHR_external_semaphore_fd wherever the device lists it; vkGetSemaphoreFdKHR is loaded
    // only then.
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(ctx.physicalDevice(), nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateDeviceExtensionProperties(ctx.physicalDevice(), nullptr, &count, exts.data());
    const bool listed = std::any_of(exts.begin(), exts.end(), [](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME) == 0;
    });
    if (listed && vkGetSemaphoreFdKHR) {
        VkPhysicalDeviceExternalSemaphoreInfo query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_SEMAPHORE_INFO};
        query.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;  // binary: no VkSemaphoreTypeCreateInfo
        VkExternalSemaphoreProperties props{VK_STRUCTURE_TYPE_EXTERNAL_SEMAPHORE_PROPERTIES};
        vkGetPhysicalDeviceExternalSemaphoreProperties(ctx.physicalDevice(), &query, &props);
        caps.vkSemaphoreFd = (props.externalSemaphoreFeatures & VK_EXTERNAL_SEMAPHORE_FEATURE_EXPORTABLE_BIT) != 0;
    }
    return caps;
}

namespace {

// A binary semaphore exportable as an opaque fd, exported and imported into a new GL semaphore object.
void makeSharedSemaphore(vk::Context& ctx, const GlContext& gl, const std::string& name, VkSemaphore* vkOut,
                         GLuint* glOut) {
    VkExportSemaphoreCreateInfo exportInfo{VK_STRUCTURE_TYPE_EXPORT_SEMAPHORE_CREATE_INFO};
    exportInfo.handleTypes = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &exportInfo};
    vk::check(vkCreateSemaphore(ctx.device(), &info, nullptr, vkOut));
    ctx.setName(*vkOut, VK_OBJECT_TYPE_SEMAPHORE, name);
    VkSemaphoreGetFdInfoKHR getFd{VK_STRUCTURE_TYPE_SEMAPHORE_GET_FD_INFO_KHR};
    getFd.semaphore = *vkOut;
    getFd.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    int fd = -1;
    vk::check(vkGetSemaphoreFdKHR(ctx.device(), &getFd, &fd));
    const Api& api = gl.api();
    api.glGenSemaphoresEXT(1, glOut);
    api.glImportSemaphoreFdEXT(*glOut, GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);
    if (const GLenum error = api.glGetError(); error != GL_NO_ERROR) {
        close(fd);  // a failed import leaves the fd with us
        api.glDeleteSemaphoresEXT(1, glOut);
        *glOut = 0;
        throw GlError("OpenGL: glImportSemaphoreFdEXT refused semaphore '" + name + "' (GL error " +
                      std::to_string(error) + ")");
    }
}

// GL_LAYOUT_GENERAL_EXT for each texture (shared images stay in VK_IMAGE_LAYOUT_GENERAL).
std::vector<GLenum> generalLayouts(std::span<const GLuint> textures) {
    return std::vector<GLenum>(textures.size(), GL_LAYOUT_GENERAL_EXT);
}

}  // namespace

HandOff::HandOff(vk::Context& ctx, const GlContext& gl, const std::string& name)
    : ctx_(ctx), gl_(gl), name_(name), semaphores_(gl.sync().mode == SyncMode::Semaphores) {
    if (!semaphores_) return;
    try {
        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        poolInfo.queueFamilyIndex = ctx.queueFamily();
        vk::check(vkCreateCommandPool(ctx.device(), &poolInfo, nullptr, &pool_));
        GlContext::Current current(gl);
        makeSharedSemaphore(ctx, gl, name + ": to GL", &toGl_, &glToGl_);
        makeSharedSemaphore(ctx, gl, name + ": to Vulkan", &toVulkan_, &glToVulkan_);
    } catch (...) {
        release();
        throw;
    }
}

HandOff::~HandOff() { release(); }

void HandOff::release() noexcept {
    if (glToGl_ || glToVulkan_) {
        try {
            GlContext::Current current(gl_);
            // GL may still have the last wait or signal queued: finish before the objects go.
            gl_.api().glFinish();
            if (glToGl_) gl_.api().glDeleteSemaphoresEXT(1, &glToGl_);
            if (glToVulkan_) gl_.api().glDeleteSemaphoresEXT(1, &glToVulkan_);
        } catch (const GlError&) {
            // The context cannot be made current: GL frees its objects with it.
        }
        glToGl_ = glToVulkan_ = 0;
    }
    // The Vulkan objects go once every submission made so far (the last hand-off's included) has completed.
    const VkDevice device = ctx_.device();
    if (toGl_ || toVulkan_ || pool_) {
        ctx_.destroyDeferred([device, toGl = toGl_, toVulkan = toVulkan_, pool = pool_] {
            if (toGl) vkDestroySemaphore(device, toGl, nullptr);
            if (toVulkan) vkDestroySemaphore(device, toVulkan, nullptr);
            if (pool) vkDestroyCommandPool(device, pool, nullptr);  // frees its command buffers
        });
    }
    toGl_ = toVulkan_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
    commandBuffers_.clear();
}

void HandOff::expect(Step step, const char* call) const {
    if (step_ == Step::Broken)
        throw GlError(name_ + ": an earlier GL step failed between glBegin and glEnd; the semaphore hand-off is out "
                              "of step and cannot be used again");
    if (step_ != step) throw std::logic_error(name_ + ": HandOff::" + call + " called out of order");
}

VkCommandBuffer HandOff::ownCommandBuffer() {
    const uint64_t completed = ctx_.completedValue();
    for (Recorded& r : commandBuffers_) {
        if (r.value > completed) continue;
        vk::check(vkResetCommandBuffer(r.cmd, 0));
        r.value = UINT64_MAX;  // in use until submitted
        return r.cmd;
    }
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vk::check(vkAllocateCommandBuffers(ctx_.device(), &alloc, &cmd));
    commandBuffers_.push_back({cmd, UINT64_MAX});
    return cmd;
}

void HandOff::submitToGl(VkCommandBuffer cmd) {
    expect(Step::Vulkan, "submitToGl");
    if (!semaphores_) {
        ctx_.waitFor(ctx_.submit(cmd));  // the CPU-side wait: GL may touch the memory once this returns
    } else {
        VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        signal.semaphore = toGl_;
        signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;  // after every command of the batch
        ctx_.submit(cmd, {}, std::span<const VkSemaphoreSubmitInfo>(&signal, 1));
    }
    step_ = Step::GlReady;
}

void HandOff::submitToGl(const std::function<void(VkCommandBuffer)>& release) {
    if (!semaphores_) {
        expect(Step::Vulkan, "submitToGl");
        ctx_.runImmediate(release);  // submits and waits
        step_ = Step::GlReady;
        return;
    }
    expect(Step::Vulkan, "submitToGl");
    VkCommandBuffer cmd = ownCommandBuffer();
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk::check(vkBeginCommandBuffer(cmd, &begin));
    release(cmd);
    vk::check(vkEndCommandBuffer(cmd));
    submitToGl(cmd);
    for (Recorded& r : commandBuffers_)
        if (r.cmd == cmd) r.value = ctx_.lastSubmittedValue();
}

void HandOff::glBegin(std::span<const GLuint> buffers, std::span<const GLuint> textures) {
    expect(Step::GlReady, "glBegin");
    step_ = Step::GlRunning;
    if (!semaphores_) return;
    const std::vector<GLenum> layouts = generalLayouts(textures);
    gl_.api().glWaitSemaphoreEXT(glToGl_, GLuint(buffers.size()), buffers.data(), GLuint(textures.size()),
                                 textures.data(), layouts.data());
    gl_.check(name_ + ": glWaitSemaphoreEXT");
}

void HandOff::glEnd(std::span<const GLuint> buffers, std::span<const GLuint> textures) {
    expect(Step::GlRunning, "glEnd");
    if (!semaphores_) {
        gl_.api().glFinish();
        gl_.check(name_ + ": glFinish");
    } else {
        const std::vector<GLenum> layouts = generalLayouts(textures);
        gl_.api().glSignalSemaphoreEXT(glToVulkan_, GLuint(buffers.size()), buffers.data(), GLuint(textures.size()),
                                       textures.data(), layouts.data());
        // The signal is queued in GL's command stream: without a flush Vulkan's wait could wait forever.
        gl_.api().glFlush();
        gl_.check(name_ + ": glSignalSemaphoreEXT");
    }
    step_ = Step::GlDone;
}

uint64_t HandOff::resumeVulkan(VkCommandBuffer next, const std::function<void(VkCommandBuffer)>& acquire) {
    if (!semaphores_ || step_ != Step::GlDone) {
        // CPU-wait mode (GL finished: the barriers only transfer ownership), or GL failed part-way: the caller
        // still gets its buffers back in a command buffer it can end and submit.
        if (semaphores_ && step_ != Step::Vulkan) step_ = Step::Broken;
        if (step_ != Step::Broken) step_ = Step::Vulkan;
        acquire(next);
        return 0;
    }
    VkCommandBuffer cmd = ownCommandBuffer();
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk::check(vkBeginCommandBuffer(cmd, &begin));
    acquire(cmd);
    // An acquire barrier's source scope is empty (its source is outside Vulkan), so by itself it does not chain the
    // semaphore wait to the later submissions. This barrier does: its source scope (all stages) meets the wait's
    // destination scope (all stages, below), and its destination scope is every later command on the queue, in
    // this batch or the caller's next. On a GPU this drains the queue at the hand-off, like a semaphore wait would.
    VkMemoryBarrier2 chain{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    chain.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    chain.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    chain.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    chain.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &chain;
    vkCmdPipelineBarrier2(cmd, &dep);
    vk::check(vkEndCommandBuffer(cmd));
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = toVulkan_;
    wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;  // every command of the batch waits for GL's signal
    const uint64_t value = ctx_.submit(cmd, std::span<const VkSemaphoreSubmitInfo>(&wait, 1));
    for (Recorded& r : commandBuffers_)
        if (r.cmd == cmd) r.value = value;
    step_ = Step::Vulkan;
    return value;
}

}  // namespace idk::gl
