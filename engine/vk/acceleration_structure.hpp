// acceleration_structure.hpp: driver acceleration structures for VK_KHR_ray_query (the native rung of the
// "ray traversal" capability ladder): one bottom-level structure per triangle mesh and one top-level structure
// over placed instances, built once on the device and compacted by nothing (static scenes). The portable rung is
// our own BVH (engine/bvh + include/bvh_traverse.glsl); both must return the same hits (conformance tests).
#pragma once
#include <volk.h>

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "vk/resources.hpp"

namespace idk::vk {

class Context;

// An indexed triangle mesh in object space (primitive index in shaders = triangle index in `indices`).
struct AccelMesh {
    std::span<const glm::vec3> positions;
    std::span<const glm::uvec3> indices;
};

struct AccelInstance {
    glm::mat4 objectToWorld{1.0f};  // affine
    uint32_t mesh = 0;              // into the mesh span
    uint32_t customIndex = 0;       // gl_InstanceCustomIndex / rayQueryGetIntersectionInstanceCustomIndexEXT (24 bits)
};

// True when the device exposes VK_KHR_acceleration_structure + VK_KHR_ray_query (enabled by Context).
bool rayQuerySupported(const Context& ctx);

class AccelerationStructures {
public:
    // Builds every BLAS and the TLAS (one immediate submission, waits). Meshes without triangles get no BLAS and
    // their instances are skipped. Throws std::runtime_error when ray query is unsupported or a count is out of
    // range (custom index >= 2^24).
    AccelerationStructures(Context& ctx, std::span<const AccelMesh> meshes, std::span<const AccelInstance> instances);
    ~AccelerationStructures();
    AccelerationStructures(const AccelerationStructures&) = delete;
    AccelerationStructures& operator=(const AccelerationStructures&) = delete;

    VkDeviceAddress tlasAddress() const noexcept { return tlasAddress_; }
    uint64_t gpuBytes() const noexcept;

private:
    struct Built {
        VkAccelerationStructureKHR handle = VK_NULL_HANDLE;
        Buffer storage;
    };
    Built build(VkCommandBuffer cmd, const VkAccelerationStructureGeometryKHR& geometry, uint32_t primitiveCount,
                VkAccelerationStructureTypeKHR type, Buffer& scratch, const char* name);

    Context& ctx_;
    std::vector<Built> blases_;
    Built tlas_;
    std::vector<Buffer> inputs_;  // vertex, index and instance buffers (kept until destruction)
    std::vector<Buffer> scratch_;
    VkDeviceAddress tlasAddress_ = 0;
};

}  // namespace idk::vk
