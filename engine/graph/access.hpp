// access.hpp: the kinds of access a render-graph pass declares on a resource, and THE ONE table that maps
// (Access, resource kind) to synchronization2 stage/access masks, the image layout and whether it writes.
// No other file in the engine spells these masks: passes name an Access and their shader stages only.
#pragma once
#include <volk.h>

#include <cstdint>
#include <string_view>

namespace idk::graph {

enum class Access : uint8_t {
    SampledRead,       // texture()/texelFetch through a sampled descriptor (or a uniform texel buffer)
    StorageRead,       // imageLoad / storage buffer read
    StorageWrite,      // imageStore / storage buffer write (previous contents may be kept: partial writes are fine)
    StorageReadWrite,  // both in one pass (atomics, in-place updates)
    ColorWrite,        // colour attachment written with loadOp CLEAR or DONT_CARE and no blending
    ColorReadWrite,    // colour attachment with blending or loadOp LOAD
    DepthWrite,        // depth attachment, test + write (the test reads: the access mask includes READ)
    DepthRead,         // depth attachment, test only (read-only layout, can also be sampled in the same pass)
    IndirectRead,      // vkCmdDraw*/Dispatch*Indirect arguments (and indirect counts)
    VertexRead,        // vertex and index buffers
    UniformRead,       // uniform buffer
    TransferSrc,       // copy/blit source
    TransferDst,       // copy/blit/clear/fill destination
    Present,           // handed to the presentation engine (images only; final state of a swapchain image)
    HostRead,          // read by the CPU after the frame's fence (buffers only)
    ShadingRateRead,   // fragment shading-rate attachment (KHR) or shading-rate image (NV; same stage/access/layout values)
};
inline constexpr uint32_t kAccessCount = static_cast<uint32_t>(Access::ShadingRateRead) + 1;

enum class ResourceKind : uint8_t { Image, Buffer };

struct AccessInfo {
    bool valid = false;                                   // false: this access makes no sense for this kind
    VkPipelineStageFlags2 defaultStages = VK_PIPELINE_STAGE_2_NONE;  // used when a pass gives no stages
    VkPipelineStageFlags2 allowedStages = VK_PIPELINE_STAGE_2_NONE;  // stages a pass may name with this access
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;    // images only (UNDEFINED for buffers)
    bool isWrite = false;
};

// The table lookup. Total: returns {valid = false} for combinations such as ColorWrite on a buffer.
AccessInfo accessInfo(Access access, ResourceKind kind) noexcept;

// Usage flags a resource needs for an access (derived, so passes never spell usage by hand).
VkImageUsageFlags imageUsageFor(Access access) noexcept;
VkBufferUsageFlags bufferUsageFor(Access access) noexcept;

std::string_view toString(Access access) noexcept;
std::string_view toString(ResourceKind kind) noexcept;

// Every access bit that is a write. SYNC: only writes need an availability operation (srcAccessMask);
// naming read bits in srcAccessMask is meaningless, so the planner filters with this mask.
inline constexpr VkAccessFlags2 kWriteAccessMask =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
    VK_ACCESS_2_MEMORY_WRITE_BIT;

// Default stages of shader accesses when a pass names none: the core stages every Vulkan 1.3 device
// supports. SYNC: naming TASK/MESH/GEOMETRY stages in a barrier requires the feature to be enabled, so
// passes that run in those stages must name them explicitly.
inline constexpr VkPipelineStageFlags2 kDefaultShaderStages =
    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

// Aspect mask for whole-image barriers and clears of a format (colour, depth, depth+stencil, stencil).
VkImageAspectFlags aspectMaskFor(VkFormat format) noexcept;
bool isDepthOrStencilFormat(VkFormat format) noexcept;

}  // namespace idk::graph
