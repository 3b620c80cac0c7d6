// shared_memory.hpp: Vulkan buffers and images whose memory is exported (VK_KHR_external_memory_fd, opaque fd)
// and imported into OpenGL (GL_EXT_memory_object_fd): one allocation seen by both APIs, no copies. Plus the
// ownership transfers and the CPU-side wait that order Vulkan and GL work on them.
//
// Synchronisation. GL_EXT_semaphore_fd would let GL wait on and signal Vulkan semaphores on the GPU; llvmpipe
// (and so this machine) lacks it, so the rung orders the two APIs on the CPU: Vulkan work before a GL step is
// waited for on the context's timeline, GL work is finished with glFinish before Vulkan work that reads it is
// submitted. On a GPU driver this stalls the queue once per hand-over; there the semaphore path is the one to use
// (not implemented: no driver here exposes it to test it on). Vulkan's side of each hand-over is a queue-family
// ownership transfer to/from VK_QUEUE_FAMILY_EXTERNAL (the spec's rule for memory another API touches), with the
// image in GENERAL layout: GL has no layout of its own, and GENERAL is valid for every access Vulkan makes here.
#pragma once
#include <volk.h>

#include <string>

#include "gl/gl_context.hpp"
#include "vk/context.hpp"

namespace idk::gl {

class SharedBuffer {
public:
    // usage: STORAGE/TRANSFER bits as needed (TRANSFER_SRC|DST are added). Throws vk::Error / GlError.
    SharedBuffer(vk::Context& vkCtx, const GlContext& glCtx, VkDeviceSize size, VkBufferUsageFlags usage,
                 const std::string& name);
    ~SharedBuffer();
    SharedBuffer(const SharedBuffer&) = delete;
    SharedBuffer& operator=(const SharedBuffer&) = delete;

    const vk::Buffer& vk() const noexcept { return buffer_; }  // no device address; memory not host-mapped
    GLuint gl() const noexcept { return glBuffer_; }
    VkDeviceSize size() const noexcept { return buffer_.size; }

private:
    void release() noexcept;  // the destructor, and the constructor's unwinding
    vk::Context& vkCtx_;
    const GlContext& glCtx_;
    vk::Buffer buffer_;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    GLuint glMemory_ = 0, glBuffer_ = 0;
};

class SharedImage {
public:
    // 2D, one mip, one layer; format: R8G8B8A8_UNORM, R32_SFLOAT, R32_UINT or R32G32B32A32_SFLOAT.
    SharedImage(vk::Context& vkCtx, const GlContext& glCtx, VkFormat format, uint32_t width, uint32_t height,
                VkImageUsageFlags usage, const std::string& name);
    ~SharedImage();
    SharedImage(const SharedImage&) = delete;
    SharedImage& operator=(const SharedImage&) = delete;

    const vk::Image& vk() const noexcept { return image_; }
    GLuint gl() const noexcept { return glTexture_; }
    GLenum glFormat() const noexcept { return glFormat_; }  // sized internal format, e.g. GL_RGBA8

private:
    void release() noexcept;
    vk::Context& vkCtx_;
    const GlContext& glCtx_;
    vk::Image image_;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    GLuint glMemory_ = 0, glTexture_ = 0;
    GLenum glFormat_ = 0;
};

// Vulkan gives the resource to GL: a release barrier to VK_QUEUE_FAMILY_EXTERNAL after `srcStages`/`srcAccess`
// (images: from `layout` to GENERAL). The submission holding it must complete before GL touches the memory
// (Context::waitFor / runImmediate: the CPU-side wait).
void releaseToGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedBuffer& buffer, VkPipelineStageFlags2 srcStages,
                 VkAccessFlags2 srcAccess);
void releaseToGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedImage& image, VkImageLayout layout,
                 VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess);
// Vulkan takes the resource back after GL finished (finishGl): an acquire barrier from VK_QUEUE_FAMILY_EXTERNAL
// before `dstStages`/`dstAccess` (images stay in GENERAL).
void acquireFromGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedBuffer& buffer, VkPipelineStageFlags2 dstStages,
                   VkAccessFlags2 dstAccess);
void acquireFromGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedImage& image, VkPipelineStageFlags2 dstStages,
                   VkAccessFlags2 dstAccess);
// The CPU-side wait on GL's side: every GL command issued so far has completed (call inside GlContext::Current).
void finishGl(const GlContext& glCtx);

}  // namespace idk::gl
