// features.hpp: what the device can do beyond the Vulkan 1.3 baseline, and the capability ladders (DESIGN.md)
// that pick, for each optional feature, the best rung the device supports: native Vulkan, GL interop, or a
// portable fallback that computes the same result. Each ladder carries its chosen rung and the reason for it
// (`idk info` and `idk render --json` print both); `--rung LADDER=RUNG` forces one ladder's rung.
#pragma once
#include <volk.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vk/shading_rate.hpp"

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
    bool multiViewport = false;           // gl_ViewportIndex selects among several viewports
    bool geometryShaderPassthroughNv = false;  // VK_NV_geometry_shader_passthrough
    bool viewportSwizzleNv = false;       // VK_NV_viewport_swizzle
    bool shaderOutputLayer = false;       // gl_Layer from the vertex shader (point-shadow cube in one draw)
    bool externalMemoryFd = false;        // VK_KHR_external_memory_fd: share memory with OpenGL
    bool bufferFloat32AtomicAdd = false;  // VK_EXT_shader_atomic_float: shaderBufferFloat32AtomicAdd
    bool samplerFilterMinmax = false;     // VK_EXT_sampler_filter_minmax (core 1.2) with MAX filtering of R32F
    // B10G11R11_UFLOAT_PACK32 and R8_UNORM 3D images with storage, sampling and linear filtering (VXGI's packed
    // directional volumes; storage of both is one of Vulkan's optional "extended" storage formats).
    bool packedVoxelFormats = false;
    // The GL-interop rung (gl/interop_probe.hpp), filled only when the context probed it (ContextDesc).
    bool glInterop = false;               // a GL context imports this device's memory; round trip passed
    bool glAtomicFloat = false;           // ... and has GL_NV_shader_atomic_float
    bool glAtomicFp16Vector = false;      // ... and GL_NV_shader_atomic_fp16_vector
    std::string glInteropNote = "GL interop not probed (this program did not ask for it)";
    bool shaderFloat16 = false;
    bool storage16Bit = false;
    bool subgroupArithmetic = false;      // compute stage supports subgroupAdd & co.
    uint32_t subgroupSize = 0;            // never assume 32: lavapipe reports 8
    uint32_t minSubgroupSize = 0;
    uint32_t maxSubgroupSize = 0;
    bool cpuDevice = false;               // VK_PHYSICAL_DEVICE_TYPE_CPU (lavapipe): "native" runs in software
    // The VRS hardware rungs' texel sizes (vk/shading_rate.hpp picks the classifier's tile from them).
    ShadingRateTexelLimits shadingRateAttachmentTexel;  // VK_KHR_fragment_shading_rate
    VkExtent2D shadingRateTexelNv{0, 0};                // VK_NV_shading_rate_image
};

enum class Rung : uint8_t { Native, GlInterop, Fallback };
const char* rungName(Rung rung);                          // "native", "gl-interop", "fallback"
std::optional<Rung> rungFromName(const std::string& name);  // inverse of rungName

struct RungOption {
    Rung rung;
    std::string mechanism;  // e.g. "VK_EXT_mesh_shader"
    bool available;
    std::string note;       // why it is unavailable, or what it needs
};

// One optional feature and the rung chosen for this device.
struct Ladder {
    std::string id;                   // command-line name, e.g. "mesh-shading" (--rung mesh-shading=fallback)
    std::string feature;              // e.g. "mesh shading"
    std::vector<RungOption> options;  // best first
    Rung chosen;
    std::string chosenMechanism;
    std::string reason;               // why this rung, e.g. "device lacks VK_EXT_mesh_shader"
};

// A rung forced by the user (--rung LADDER=RUNG).
struct RungForce {
    std::string ladder;  // Ladder::id
    Rung rung;
};

struct LadderChoice {
    bool forceFallback = false;     // the last rung everywhere (--fallback; conformance tests compare rungs)
    std::vector<RungForce> forced;  // override forceFallback for the ladders they name
};

// Builds the ladder table for the features known so far: the first available rung, except where a CPU device's
// "native" mechanism is a software emulation slower than our portable rung (the reason says so). A forced rung
// the device cannot run is not taken: the ladder keeps its own choice and *error says why (empty when all
// forcings hold), so a caller can refuse to run.
std::vector<Ladder> buildLadders(const DeviceCapabilities& caps, const LadderChoice& choice, std::string* error);
inline std::vector<Ladder> buildLadders(const DeviceCapabilities& caps, bool forceFallback = false) {
    return buildLadders(caps, LadderChoice{forceFallback, {}}, nullptr);
}

// Every ladder id and the rung names of each ("mesh-shading: native|fallback"), for messages and `idk info`;
// independent of the device. Throws std::invalid_argument for an unknown ladder or rung name in `spec`
// ("LADDER=RUNG"), listing the valid names.
std::vector<std::string> ladderRungList();
std::vector<Rung> ladderRungs(const std::string& ladderId);  // best first; throws std::invalid_argument if unknown
RungForce parseRungForce(const std::string& spec);

}  // namespace idk::vk
