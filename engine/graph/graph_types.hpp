// graph_types.hpp: the value types shared by the render graph, its resource pool and its backend: typed
// versioned handles, resource descriptions (as declared, and resolved for the backend), the physical
// objects a backend hands back, and GraphError.
#pragma once
#include "graph/access.hpp"

#include <compare>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace idk::graph {

// Thrown by RenderGraph::compile() (malformed graph) and by programmer errors during execution.
class GraphError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

inline constexpr uint32_t kInvalidId = ~0u;
inline constexpr uint32_t kNoBindlessIndex = ~0u;

// A resource plus the version of its contents. write() returns version + 1; reading or writing a version
// that a later write already replaced is an error, which is what orders passes without explicit edges.
struct TextureHandle {
    uint32_t resource = kInvalidId;
    uint32_t version = 0;
    bool valid() const noexcept { return resource != kInvalidId; }
    auto operator<=>(const TextureHandle&) const = default;
};
struct BufferHandle {
    uint32_t resource = kInvalidId;
    uint32_t version = 0;
    bool valid() const noexcept { return resource != kInvalidId; }
    auto operator<=>(const BufferHandle&) const = default;
};

enum class SizeMode : uint8_t { Absolute, OutputRelative };

// A texture as a pass declares it. Usage is NOT declared: it is derived from the accesses of all passes.
struct TextureDesc {
    VkFormat format = VK_FORMAT_UNDEFINED;
    SizeMode sizeMode = SizeMode::OutputRelative;
    float scaleX = 1.0f, scaleY = 1.0f;   // OutputRelative: extent = max(1, round(output * scale))
    VkExtent3D extent{1, 1, 1};           // Absolute: depth > 1 makes a 3D image
    uint32_t mips = 1;                    // 0 = full chain down to 1x1
    uint32_t layers = 1;
    bool cube = false;                    // layers must be a multiple of 6
    bool persistent = false;              // kept for next frame's history(name): two copies, ping-pong
    VkImageUsageFlags extraUsage = 0;     // on top of the derived usage (e.g. for views the graph can't see)
};

struct BufferDesc {
    VkDeviceSize size = 0;
    bool persistent = false;
    VkBufferUsageFlags extraUsage = 0;
};

// Resolved descriptions handed to the backend (absolute extent, final mip count, derived usage). Equality
// is what the resource pool keys physical objects on.
struct TextureInfo {
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageType type = VK_IMAGE_TYPE_2D;
    VkExtent3D extent{1, 1, 1};
    uint32_t mips = 1;
    uint32_t layers = 1;
    bool cube = false;
    VkImageUsageFlags usage = 0;
    bool operator==(const TextureInfo& o) const noexcept {
        return format == o.format && type == o.type && extent.width == o.extent.width &&
               extent.height == o.extent.height && extent.depth == o.extent.depth && mips == o.mips &&
               layers == o.layers && cube == o.cube && usage == o.usage;
    }
};

struct BufferInfo {
    VkDeviceSize size = 0;
    VkBufferUsageFlags usage = 0;
    bool hostVisible = false;   // some pass declares HostRead: the memory must be host-visible
    bool operator==(const BufferInfo&) const noexcept = default;
};

// Physical objects as the backend creates them (or as the caller imports them).
struct PhysicalTexture {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;   // all mips and layers
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent3D extent{1, 1, 1};
    uint32_t mips = 1;
    uint32_t layers = 1;
    uint32_t sampledIndex = kNoBindlessIndex;   // bindless slots (kNoBindlessIndex when not registered)
    uint32_t storageIndex = kNoBindlessIndex;
    uint64_t backendData = 0;                   // opaque to the graph (e.g. the backend's allocation id)
};

struct PhysicalBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    VkDeviceAddress address = 0;
    uint32_t storageIndex = kNoBindlessIndex;
    uint64_t backendData = 0;
};

// How an imported resource is left after the graph (e.g. {Access::Present} for a swapchain image, or
// {Access::SampledRead, FRAGMENT} for an image the UI samples next). Stages NONE: the table default.
struct FinalUse {
    Access access = Access::SampledRead;
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
};

}  // namespace idk::graph
