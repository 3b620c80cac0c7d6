// acceleration_structure.cpp: BLAS per mesh + TLAS for VK_KHR_ray_query (see acceleration_structure.hpp).
#include "vk/acceleration_structure.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include "vk/check.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::vk {
namespace {

constexpr const char* kCategory = "acceleration structures";

VkDeviceSize scratchAlignment(const Context& ctx) {
    VkPhysicalDeviceAccelerationStructurePropertiesKHR accel{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &accel};
    vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
    return std::max<VkDeviceSize>(accel.minAccelerationStructureScratchOffsetAlignment, 1);
}

Buffer inputBuffer(Context& ctx, const void* data, VkDeviceSize bytes, const std::string& name) {
    BufferDesc desc;
    desc.size = std::max<VkDeviceSize>(bytes, 16);
    desc.usage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    desc.name = name;
    desc.category = kCategory;
    Buffer buffer = ctx.createBuffer(desc);
    if (bytes > 0) uploadBuffer(ctx, buffer, data, bytes);
    return buffer;
}

VkTransformMatrixKHR toTransform(const glm::mat4& m) {
    VkTransformMatrixKHR t{};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 4; ++col) t.matrix[row][col] = m[col][row];  // glm is column-major, Vulkan 3x4 rows
    return t;
}

}  // namespace

bool rayQuerySupported(const Context& ctx) { return ctx.capabilities().rayQuery; }

AccelerationStructures::Built AccelerationStructures::build(VkCommandBuffer cmd,
                                                            const VkAccelerationStructureGeometryKHR& geometry,
                                                            uint32_t primitiveCount, VkAccelerationStructureTypeKHR type,
                                                            Buffer& scratch, const char* name) {
    VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    info.type = type;
    info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    info.geometryCount = 1;
    info.pGeometries = &geometry;
    VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    vkGetAccelerationStructureBuildSizesKHR(ctx_.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                                            &primitiveCount, &sizes);
    Built built;
    BufferDesc desc;
    desc.size = sizes.accelerationStructureSize;
    desc.usage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR;
    desc.name = name;
    desc.category = kCategory;
    built.storage = ctx_.createBuffer(desc);
    VkAccelerationStructureCreateInfoKHR create{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
    create.buffer = built.storage.buffer;
    create.size = sizes.accelerationStructureSize;
    create.type = type;
    check(vkCreateAccelerationStructureKHR(ctx_.device(), &create, nullptr, &built.handle));

    // Scratch: each build gets its own (builds in one command buffer are not ordered against each other's scratch
    // use without barriers), aligned as the driver asks.
    const VkDeviceSize align = scratchAlignment(ctx_);
    BufferDesc scratchDesc;
    scratchDesc.size = sizes.buildScratchSize + align;
    scratchDesc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    scratchDesc.name = std::string(name) + " scratch";
    scratchDesc.category = kCategory;
    scratch = ctx_.createBuffer(scratchDesc);
    info.dstAccelerationStructure = built.handle;
    info.scratchData.deviceAddress = (scratch.address + align - 1) / align * align;
    VkAccelerationStructureBuildRangeInfoKHR range{primitiveCount, 0, 0, 0};
    const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
    vkCmdBuildAccelerationStructuresKHR(cmd, 1, &info, &ranges);
    return built;
}

AccelerationStructures::AccelerationStructures(Context& ctx, std::span<const AccelMesh> meshes,
                                               std::span<const AccelInstance> instances)
    : ctx_(ctx) {
    if (!rayQuerySupported(ctx)) throw std::runtime_error(ctx.info().name + " lacks VK_KHR_ray_query");
    std::vector<VkAccelerationStructureGeometryKHR> geometries(meshes.size());
    std::vector<int32_t> blasOf(meshes.size(), -1);
    for (size_t m = 0; m < meshes.size(); ++m) {
        if (meshes[m].indices.empty()) continue;
        // Addresses are taken at once: a later emplace_back may move the vector's elements.
        const VkDeviceAddress vertices = inputs_.emplace_back(inputBuffer(ctx, meshes[m].positions.data(),
                                                                          meshes[m].positions.size_bytes(), "as vertices")).address;
        const VkDeviceAddress indices = inputs_.emplace_back(inputBuffer(ctx, meshes[m].indices.data(),
                                                                         meshes[m].indices.size_bytes(), "as indices")).address;
        VkAccelerationStructureGeometryKHR& g = geometries[m];
        g = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
        g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
        g.geometry.triangles = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR};
        g.geometry.triangles.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
        g.geometry.triangles.vertexData.deviceAddress = vertices;
        g.geometry.triangles.vertexStride = sizeof(glm::vec3);
        g.geometry.triangles.maxVertex = uint32_t(meshes[m].positions.size() - 1);
        g.geometry.triangles.indexType = VK_INDEX_TYPE_UINT32;
        g.geometry.triangles.indexData.deviceAddress = indices;
        // Not OPAQUE: the shaders test alpha on candidates (or force opaque with a ray flag when nothing is masked).
        g.flags = 0;
        blasOf[m] = int32_t(m);
    }
    std::vector<VkAccelerationStructureInstanceKHR> records;
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        blases_.resize(meshes.size());
        for (size_t m = 0; m < meshes.size(); ++m) {
            if (blasOf[m] < 0) continue;
            blases_[m] = build(cmd, geometries[m], uint32_t(meshes[m].indices.size()),
                               VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, scratch_.emplace_back(), "blas");
        }
    });
    for (const AccelInstance& inst : instances) {
        if (inst.mesh >= meshes.size()) throw std::runtime_error("acceleration structures: instance mesh out of range");
        if (inst.customIndex >= (1u << 24)) throw std::runtime_error("acceleration structures: custom index >= 2^24");
        if (blasOf[inst.mesh] < 0) continue;
        VkAccelerationStructureDeviceAddressInfoKHR addr{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
        addr.accelerationStructure = blases_[inst.mesh].handle;
        VkAccelerationStructureInstanceKHR r{};
        r.transform = toTransform(inst.objectToWorld);
        r.instanceCustomIndex = inst.customIndex;
        r.mask = 0xFF;
        // Both faces are hit, as by our BVH's two-sided triangle test; no culling flags.
        r.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
        r.accelerationStructureReference = vkGetAccelerationStructureDeviceAddressKHR(ctx.device(), &addr);
        records.push_back(r);
    }
    const VkDeviceAddress instanceAddress = inputs_.emplace_back(
        inputBuffer(ctx, records.data(), records.size() * sizeof(VkAccelerationStructureInstanceKHR), "as instances")).address;
    VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    g.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
    g.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
    g.geometry.instances.data.deviceAddress = instanceAddress;
    // The BLAS builds above were a separate submission that the context waited for: they are complete.
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        tlas_ = build(cmd, g, uint32_t(records.size()), VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                      scratch_.emplace_back(), "tlas");
        // Make the build visible to the ray queries of later submissions.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                      VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
    });
    VkAccelerationStructureDeviceAddressInfoKHR addr{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    addr.accelerationStructure = tlas_.handle;
    tlasAddress_ = vkGetAccelerationStructureDeviceAddressKHR(ctx.device(), &addr);
    for (Buffer& s : scratch_) ctx.destroy(s);  // the builds finished (runImmediate waits)
    scratch_.clear();
}

AccelerationStructures::~AccelerationStructures() {
    ctx_.waitIdle();  // a structure may be referenced by submitted ray queries
    for (Built& b : blases_) {
        if (b.handle) vkDestroyAccelerationStructureKHR(ctx_.device(), b.handle, nullptr);
        if (b.storage.buffer) ctx_.destroy(b.storage);
    }
    if (tlas_.handle) vkDestroyAccelerationStructureKHR(ctx_.device(), tlas_.handle, nullptr);
    if (tlas_.storage.buffer) ctx_.destroy(tlas_.storage);
    for (Buffer& b : inputs_) ctx_.destroy(b);
}

uint64_t AccelerationStructures::gpuBytes() const noexcept {
    uint64_t bytes = tlas_.storage.size;
    for (const Built& b : blases_) bytes += b.storage.size;
    for (const Buffer& b : inputs_) bytes += b.size;
    return bytes;
}

}  // namespace idk::vk
