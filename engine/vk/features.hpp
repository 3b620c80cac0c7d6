// features.hpp: what the device can do beyond the Vulkan 1.3 baseline, and the capability ladders (DESIGN.md)
// that pick, for each optional feature, the best rung the device supports: native Vulkan, GL interop, or a
// portable fallback that computes the same result.
#pragma once
#include <volk.h>

#include <cstdint>
#include <string>
#include <vector>

namespace idk::vk {

// Optional device capabilities detected at start-up (the baseline ones are required and not listed).
struct DeviceCapabilities {
    bool meshShaderExt = false;           // VK_EXT_mesh_shader (task + mesh)
    bool meshShaderNv = false;            // VK_NV_mesh_shader
    bool fragmentShadingRate = false;     // VK_KHR_fragment_shading_rate with attachment rates
    bool shadingRateImageNv = false;      // VK_NV_shading_rate_image
    bool rayQuery = false;                // VK_KHR_ray_query + VK_KHR_acceleration_structure
    bool imageFloat32AtomicAdd = false;   // VK_EXT_shader_atomic_float: shaderImageFloat32AtomicAdd
    bool imageFloat32AtomicMinMax = false;// VK_EXT_shader_atomic_float2
    bool float16VectorAtomicsNv = false;  // VK_NV_shader_atomic_float16_vector
    bool conservativeRasterization = false;
    bool geometryShader = false;
    bool shaderOutputLayer = false;       // gl_Layer from the vertex shader (point-shadow cube in one draw)
    bool externalMemoryFd = false;        // VK_KHR_external_memory_fd: share memory with OpenGL
    bool shaderFloat16 = false;
    bool storage16Bit = false;
    bool subgroupArithmetic = false;      // compute stage supports subgroupAdd & co.
    uint32_t subgroupSize = 0;            // never assume 32: lavapipe reports 8
    uint32_t minSubgroupSize = 0;
    uint32_t maxSubgroupSize = 0;
};

enum class Rung : uint8_t { Native, GlInterop, Fallback };
const char* rungName(Rung rung);

struct RungOption {
    Rung rung;
    std::string mechanism;  // e.g. "VK_EXT_mesh_shader"
    bool available;
    std::string note;       // why it is unavailable, or what it needs
};

// One optional feature and the rung chosen for this device.
struct Ladder {
    std::string feature;              // e.g. "mesh shading"
    std::vector<RungOption> options;  // best first
    Rung chosen;
    std::string chosenMechanism;
};

// Builds the ladder table for the features known so far. forceFallback picks the last rung everywhere
// (conformance tests use it to check that rungs agree on the same input).
std::vector<Ladder> buildLadders(const DeviceCapabilities& caps, bool forceFallback = false);

}  // namespace idk::vk
