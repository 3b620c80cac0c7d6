// pipeline.hpp: pipeline descriptions and creation on the one global pipeline layout (bindless set 0 plus a
// 128-byte push range). Before a pipeline is built, its SPIR-V is reflected and checked against the C++ side:
// push-constant size, workgroup size, and that only the bindless set is used with the expected kinds.
#pragma once
#include <volk.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "shader/spirv_reflect.hpp"
#include "shader_manifest.hpp"

namespace idk::vk {

class Context;
using shaders::ShaderId;

class PipelineError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct SpecConstant {
    uint32_t id;
    uint32_t value;  // bit pattern; floats through std::bit_cast
};

struct ComputePipelineDesc {
    ShaderId shader;
    std::vector<SpecConstant> spec;
    uint32_t pushBytes = 0;                                 // sizeof the C++ push struct (0 = no push block)
    std::optional<std::array<uint32_t, 3>> localSize;       // expected workgroup size, if the C++ side relies on it
};

enum class BlendMode : uint8_t { Opaque, Alpha, Additive };

// Where a graphics pipeline takes its fragment shading rates from (the VRS hardware rungs, frame/vrs_hardware.cpp).
enum class ShadingRateSource : uint8_t {
    None,
    KhrAttachment,  // VK_KHR_fragment_shading_rate: the rendering's rate attachment, combiner ops set dynamically
    NvImage,        // VK_NV_shading_rate_image: the bound shading-rate image through the vrs palette
};

struct GraphicsPipelineDesc {
    ShaderId vertex;                       // vertex or mesh shader
    std::optional<ShaderId> task;          // with a mesh shader
    std::optional<ShaderId> fragment;      // none for depth-only passes
    std::vector<VkFormat> colorFormats;
    std::vector<BlendMode> blend;          // per colour attachment; empty = all opaque
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkCompareOp depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed Z
    bool depthWrite = true;
    bool depthTest = true;
    VkCullModeFlags cull = VK_CULL_MODE_BACK_BIT;
    VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
    uint32_t viewMask = 0;
    std::vector<SpecConstant> spec;
    uint32_t pushBytes = 0;
    uint32_t fragmentPushBytes = 0;  // the fragment stage's push block when it reads only a prefix (0: pushBytes)
    std::optional<ShaderId> geometry;      // between vertex and fragment (voxelization's triangle dilation)
    bool conservative = false;             // VK_EXT_conservative_rasterization, overestimate (the device must have it)
    // VK_NV_viewport_swizzle (the device must have it and multiViewport): one viewport per entry, each swizzling
    // the clip position (the voxelization's passthrough rung, passes/vxgi_axis_swizzle.hpp); empty: one viewport.
    std::vector<VkViewportSwizzleNV> viewportSwizzles;
    ShadingRateSource shadingRate = ShadingRateSource::None;  // hardware VRS (the device must have the extension)
};

// Checks one module against the engine's conventions; throws PipelineError naming the shader.
void validateShader(const std::string& name, const shader::ShaderInfo& info, uint32_t expectedPushBytes,
                    const std::optional<std::array<uint32_t, 3>>& expectedLocalSize);

VkPipeline createComputePipeline(Context& ctx, std::span<const uint32_t> spirv, const ComputePipelineDesc& desc,
                                 const std::string& name);

struct GraphicsStageCode {
    VkShaderStageFlagBits stage;
    std::span<const uint32_t> spirv;
};
VkPipeline createGraphicsPipeline(Context& ctx, std::span<const GraphicsStageCode> stages,
                                  const GraphicsPipelineDesc& desc, const std::string& name);

}  // namespace idk::vk
