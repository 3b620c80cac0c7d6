// shared_memory.cpp: export a dedicated Vulkan allocation as an opaque fd, import it into GL as a memory object
// and place a GL buffer or texture on it; the queue-family ownership transfers around GL's use.
#include "gl/shared_memory.hpp"

#include <unistd.h>

#include "vk/check.hpp"

namespace idk::gl {
namespace {

constexpr VkExternalMemoryHandleTypeFlagBits kHandleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;

uint32_t pickMemoryType(VkPhysicalDevice physical, uint32_t typeBits) {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical, &props);
    uint32_t any = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        if (props.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) return i;
        if (any == UINT32_MAX) any = i;
    }
    if (any == UINT32_MAX) throw std::runtime_error("GL interop: no memory type for an exportable resource");
    return any;
}

// A dedicated, exportable allocation for `image` or `buffer` (one of them), bound by the caller.
VkDeviceMemory allocateExportable(vk::Context& ctx, const VkMemoryRequirements& reqs, VkImage image, VkBuffer buffer) {
    VkMemoryDedicatedAllocateInfo dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
    dedicated.image = image;
    dedicated.buffer = buffer;
    VkExportMemoryAllocateInfo exportInfo{VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO, &dedicated};
    exportInfo.handleTypes = kHandleType;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &exportInfo};
    info.allocationSize = reqs.size;
    info.memoryTypeIndex = pickMemoryType(ctx.physicalDevice(), reqs.memoryTypeBits);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    vk::check(vkAllocateMemory(ctx.device(), &info, nullptr, &memory));
    return memory;
}

// Exports `memory` and imports it into a new GL memory object (GL owns the fd once the import succeeds).
GLuint importIntoGl(vk::Context& ctx, const GlContext& gl, VkDeviceMemory memory, VkDeviceSize size,
                    const std::string& name) {
    VkMemoryGetFdInfoKHR getFd{VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR};
    getFd.memory = memory;
    getFd.handleType = kHandleType;
    int fd = -1;
    vk::check(vkGetMemoryFdKHR(ctx.device(), &getFd, &fd));
    const Api& api = gl.api();
    GLuint object = 0;
    api.glCreateMemoryObjectsEXT(1, &object);
    const GLint dedicated = GL_TRUE;  // the Vulkan allocation is dedicated: GL must be told so (EXT_memory_object)
    api.glMemoryObjectParameterivEXT(object, GL_DEDICATED_MEMORY_OBJECT_EXT, &dedicated);
    api.glImportMemoryFdEXT(object, size, GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);
    if (api.glGetError() != GL_NO_ERROR) {
        close(fd);
        api.glDeleteMemoryObjectsEXT(1, &object);
        throw GlError("OpenGL: glImportMemoryFdEXT refused the memory of '" + name + "'");
    }
    return object;
}

GLenum glFormatOf(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_UNORM: return GL_RGBA8;
        case VK_FORMAT_R32_SFLOAT: return GL_R32F;
        case VK_FORMAT_R32_UINT: return GL_R32UI;
        case VK_FORMAT_R32G32B32A32_SFLOAT: return GL_RGBA32F;
        default: throw std::invalid_argument("GL interop: no GL format for VkFormat " + std::to_string(int(format)));
    }
}

}  // namespace

SharedBuffer::SharedBuffer(vk::Context& vkCtx, const GlContext& glCtx, VkDeviceSize size, VkBufferUsageFlags usage,
                           const std::string& name)
    : vkCtx_(vkCtx), glCtx_(glCtx) {
    usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkPhysicalDeviceExternalBufferInfo query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_BUFFER_INFO};
    query.usage = usage;
    query.handleType = kHandleType;
    VkExternalBufferProperties props{VK_STRUCTURE_TYPE_EXTERNAL_BUFFER_PROPERTIES};
    vkGetPhysicalDeviceExternalBufferProperties(vkCtx.physicalDevice(), &query, &props);
    if (!(props.externalMemoryProperties.externalMemoryFeatures & VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT))
        throw std::runtime_error("GL interop: the device cannot export buffer '" + name + "' as an opaque fd");

    VkExternalMemoryBufferCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
    external.handleTypes = kHandleType;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, &external};
    // llvmpipe places a GL buffer only on memory a little larger than the buffer (it pads buffers for its
    // rasterizer's block reads, and refuses a memory object smaller than buffer + pad with GL_OUT_OF_MEMORY);
    // the Vulkan buffer is made kGlPad bytes longer so its dedicated memory has room, and GL sees `size` bytes.
    constexpr VkDeviceSize kGlPad = 256;
    info.size = size + kGlPad;
    info.usage = usage;
    vk::check(vkCreateBuffer(vkCtx.device(), &info, nullptr, &buffer_.buffer));
    buffer_.size = size;
    buffer_.usage = usage;
    buffer_.name = name;
    vkCtx.setName(buffer_.buffer, VK_OBJECT_TYPE_BUFFER, name);
    try {
        VkMemoryRequirements reqs;
        vkGetBufferMemoryRequirements(vkCtx.device(), buffer_.buffer, &reqs);
        memory_ = allocateExportable(vkCtx, reqs, VK_NULL_HANDLE, buffer_.buffer);
        vk::check(vkBindBufferMemory(vkCtx.device(), buffer_.buffer, memory_, 0));
        buffer_.allocation = {memory_, 0, reqs.size, nullptr, 0, -1, true, "gl interop"};
        GlContext::Current current(glCtx);
        glMemory_ = importIntoGl(vkCtx, glCtx, memory_, reqs.size, name);
        glCtx.api().glCreateBuffers(1, &glBuffer_);
        glCtx.api().glNamedBufferStorageMemEXT(glBuffer_, GLsizeiptr(size), glMemory_, 0);
        glCtx.check("glNamedBufferStorageMemEXT for '" + name + "'");
    } catch (...) {
        release();
        throw;
    }
}

SharedBuffer::~SharedBuffer() { release(); }

void SharedBuffer::release() noexcept {
    if (glBuffer_ || glMemory_) {
        try {
            GlContext::Current current(glCtx_);
            if (glBuffer_) glCtx_.api().glDeleteBuffers(1, &glBuffer_);
            if (glMemory_) glCtx_.api().glDeleteMemoryObjectsEXT(1, &glMemory_);
        } catch (const GlError&) {  // the context cannot be made current: GL frees its objects with it
        }
        glBuffer_ = glMemory_ = 0;
    }
    // Vulkan may still read it: released once every submission made so far has completed.
    if (!buffer_.buffer) return;
    VkDevice device = vkCtx_.device();
    vkCtx_.destroyDeferred([device, buffer = buffer_.buffer, memory = memory_] {
        vkDestroyBuffer(device, buffer, nullptr);
        vkFreeMemory(device, memory, nullptr);
    });
    buffer_.buffer = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

SharedImage::SharedImage(vk::Context& vkCtx, const GlContext& glCtx, VkFormat format, uint32_t width, uint32_t height,
                         VkImageUsageFlags usage, const std::string& name)
    : vkCtx_(vkCtx), glCtx_(glCtx), glFormat_(glFormatOf(format)) {
    vk::ImageDesc desc;
    desc.format = format;
    desc.extent = {width, height, 1};
    desc.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.name = name;
    VkImageCreateInfo info = vk::imageCreateInfo(desc);

    VkPhysicalDeviceExternalImageFormatInfo externalQuery{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_IMAGE_FORMAT_INFO};
    externalQuery.handleType = kHandleType;
    VkPhysicalDeviceImageFormatInfo2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGE_FORMAT_INFO_2, &externalQuery};
    query.format = info.format;
    query.type = info.imageType;
    query.tiling = info.tiling;
    query.usage = info.usage;
    query.flags = info.flags;
    VkExternalImageFormatProperties externalProps{VK_STRUCTURE_TYPE_EXTERNAL_IMAGE_FORMAT_PROPERTIES};
    VkImageFormatProperties2 props{VK_STRUCTURE_TYPE_IMAGE_FORMAT_PROPERTIES_2, &externalProps};
    if (vkGetPhysicalDeviceImageFormatProperties2(vkCtx.physicalDevice(), &query, &props) != VK_SUCCESS ||
        !(externalProps.externalMemoryProperties.externalMemoryFeatures & VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT))
        throw std::runtime_error("GL interop: the device cannot export image '" + name + "' as an opaque fd");

    VkExternalMemoryImageCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_IMAGE_CREATE_INFO};
    external.handleTypes = kHandleType;
    info.pNext = &external;
    vk::check(vkCreateImage(vkCtx.device(), &info, nullptr, &image_.image));
    image_.format = format;
    image_.extent = desc.extent;
    image_.usage = desc.usage;
    image_.name = name;
    vkCtx.setName(image_.image, VK_OBJECT_TYPE_IMAGE, name);
    try {
        VkMemoryRequirements reqs;
        vkGetImageMemoryRequirements(vkCtx.device(), image_.image, &reqs);
        memory_ = allocateExportable(vkCtx, reqs, image_.image, VK_NULL_HANDLE);
        vk::check(vkBindImageMemory(vkCtx.device(), image_.image, memory_, 0));
        image_.allocation = {memory_, 0, reqs.size, nullptr, 0, -1, true, "gl interop"};
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = image_.image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vk::check(vkCreateImageView(vkCtx.device(), &view, nullptr, &image_.view));
        GlContext::Current current(glCtx);
        glMemory_ = importIntoGl(vkCtx, glCtx, memory_, reqs.size, name);
        glCtx.api().glCreateTextures(GL_TEXTURE_2D, 1, &glTexture_);
        // Default GL_TEXTURE_TILING_EXT is GL_OPTIMAL_TILING_EXT, matching VK_IMAGE_TILING_OPTIMAL.
        glCtx.api().glTextureStorageMem2DEXT(glTexture_, 1, glFormat_, GLsizei(width), GLsizei(height), glMemory_, 0);
        glCtx.check("glTextureStorageMem2DEXT for '" + name + "'");
    } catch (...) {
        release();
        throw;
    }
}

SharedImage::~SharedImage() { release(); }

void SharedImage::release() noexcept {
    if (glTexture_ || glMemory_) {
        try {
            GlContext::Current current(glCtx_);
            if (glTexture_) glCtx_.api().glDeleteTextures(1, &glTexture_);
            if (glMemory_) glCtx_.api().glDeleteMemoryObjectsEXT(1, &glMemory_);
        } catch (const GlError&) {  // the context cannot be made current: GL frees its objects with it
        }
        glTexture_ = glMemory_ = 0;
    }
    if (!image_.image) return;
    VkDevice device = vkCtx_.device();
    vkCtx_.destroyDeferred([device, image = image_.image, view = image_.view, memory = memory_] {
        vkDestroyImageView(device, view, nullptr);
        vkDestroyImage(device, image, nullptr);
        vkFreeMemory(device, memory, nullptr);
    });
    image_.image = VK_NULL_HANDLE;
    image_.view = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

namespace {

void bufferBarrier(VkCommandBuffer cmd, VkBufferMemoryBarrier2 barrier) {
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.bufferMemoryBarrierCount = 1;
    dep.pBufferMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void imageBarrier(VkCommandBuffer cmd, VkImageMemoryBarrier2 barrier) {
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

void releaseToGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedBuffer& buffer, VkPipelineStageFlags2 srcStages,
                 VkAccessFlags2 srcAccess) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    b.srcStageMask = srcStages;
    b.srcAccessMask = srcAccess;
    b.srcQueueFamilyIndex = ctx.queueFamily();
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_EXTERNAL;
    b.buffer = buffer.vk().buffer;
    b.size = VK_WHOLE_SIZE;
    bufferBarrier(cmd, b);
}

void releaseToGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedImage& image, VkImageLayout layout,
                 VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStages;
    b.srcAccessMask = srcAccess;
    b.oldLayout = layout;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.srcQueueFamilyIndex = ctx.queueFamily();
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_EXTERNAL;
    b.image = image.vk().image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    imageBarrier(cmd, b);
}

void acquireFromGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedBuffer& buffer, VkPipelineStageFlags2 dstStages,
                   VkAccessFlags2 dstAccess) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    b.dstStageMask = dstStages;
    b.dstAccessMask = dstAccess;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_EXTERNAL;
    b.dstQueueFamilyIndex = ctx.queueFamily();
    b.buffer = buffer.vk().buffer;
    b.size = VK_WHOLE_SIZE;
    bufferBarrier(cmd, b);
}

void acquireFromGl(VkCommandBuffer cmd, const vk::Context& ctx, const SharedImage& image, VkPipelineStageFlags2 dstStages,
                   VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.dstStageMask = dstStages;
    b.dstAccessMask = dstAccess;
    b.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_EXTERNAL;
    b.dstQueueFamilyIndex = ctx.queueFamily();
    b.image = image.vk().image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    imageBarrier(cmd, b);
}

void finishGl(const GlContext& glCtx) {
    glCtx.api().glFinish();
    glCtx.check("glFinish");
}

}  // namespace idk::gl
