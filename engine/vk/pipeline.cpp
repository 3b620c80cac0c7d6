// pipeline.cpp: shader checks and Vulkan pipeline objects (dynamic rendering: no render passes; dynamic
// viewport and scissor; no vertex input: every vertex shader pulls its data through bindless buffers).
#include "vk/pipeline.hpp"

#include <algorithm>
#include <array>

#include "core/log.hpp"
#include "shared/bindings.h"
#include "shared/vrs_types.h"
#include "vk/check.hpp"
#include "vk/context.hpp"
#include "vk/shading_rate.hpp"

namespace idk::vk {
namespace {

shader::DescriptorKind expectedKind(uint32_t binding) {
    switch (binding) {
        case gpu::kBindingSampledImages: return shader::DescriptorKind::SampledImage;
        case gpu::kBindingStorageImages: return shader::DescriptorKind::StorageImage;
        case gpu::kBindingSamplers: return shader::DescriptorKind::Sampler;
        default: return shader::DescriptorKind::StorageBuffer;
    }
}

struct SpecData {
    std::vector<VkSpecializationMapEntry> entries;
    std::vector<uint32_t> values;
    VkSpecializationInfo info{};
    explicit SpecData(const std::vector<SpecConstant>& spec) {
        for (uint32_t i = 0; i < spec.size(); ++i) {
            entries.push_back({spec[i].id, i * 4u, 4});
            values.push_back(spec[i].value);
        }
        info.mapEntryCount = static_cast<uint32_t>(entries.size());
        info.pMapEntries = entries.data();
        info.dataSize = values.size() * 4;
        info.pData = values.data();
    }
    const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

VkShaderModule createModule(Context& ctx, std::span<const uint32_t> spirv, const std::string& name) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
    ctx.setName(module, VK_OBJECT_TYPE_SHADER_MODULE, name);
    return module;
}

}  // namespace

void validateShader(const std::string& name, const shader::ShaderInfo& info, uint32_t expectedPushBytes,
                    const std::optional<std::array<uint32_t, 3>>& expectedLocalSize) {
    if (info.pushConstantBytes > gpu::kPushConstantBytes) {
        throw PipelineError(core::concat(name, ": push constants use ", info.pushConstantBytes,
                                         " bytes, more than the portable ", gpu::kPushConstantBytes));
    }
    if (info.pushConstantBytes != 0 && info.pushConstantBytes != expectedPushBytes) {
        throw PipelineError(core::concat(name, ": the shader's push block is ", info.pushConstantBytes,
                                         " bytes but the C++ push struct is ", expectedPushBytes,
                                         " bytes (layouts differ)"));
    }
    if (info.descriptorSetMask & ~1u) {
        throw PipelineError(name + ": uses a descriptor set other than the global bindless set 0");
    }
    for (const shader::DescriptorBinding& b : info.bindings) {
        if (b.binding > gpu::kBindingStorageBuffers || b.kind != expectedKind(b.binding)) {
            throw PipelineError(core::concat(name, ": set 0 binding ", b.binding, " is declared as ",
                                             shader::toString(b.kind), ", which the bindless set does not have there"));
        }
    }
    if (expectedLocalSize && shader::hasWorkgroup(info.stage) && info.localSize != *expectedLocalSize) {
        const auto& e = *expectedLocalSize;
        throw PipelineError(core::concat(name, ": workgroup size is ", info.localSize[0], "x", info.localSize[1], "x",
                                         info.localSize[2], " but the C++ side dispatches for ", e[0], "x", e[1],
                                         "x", e[2]));
    }
}

VkPipeline createComputePipeline(Context& ctx, std::span<const uint32_t> spirv, const ComputePipelineDesc& desc,
                                 const std::string& name) {
    VkShaderModule module = createModule(ctx, spirv, name);
    SpecData spec(desc.spec);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = spec.get();
    info.layout = ctx.pipelineLayout();
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkResult result = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(ctx.device(), module, nullptr);
    check(result);
    ctx.setName(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
    return pipeline;
}

VkPipeline createGraphicsPipeline(Context& ctx, std::span<const GraphicsStageCode> stages,
                                  const GraphicsPipelineDesc& desc, const std::string& name) {
    SpecData spec(desc.spec);
    std::vector<VkPipelineShaderStageCreateInfo> stageInfos;
    std::vector<VkShaderModule> modules;
    for (const GraphicsStageCode& s : stages) {
        modules.push_back(createModule(ctx, s.spirv, name));
        VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage = s.stage;
        info.module = modules.back();
        info.pName = "main";
        info.pSpecializationInfo = spec.get();
        stageInfos.push_back(info);
    }
    bool meshPipeline = stages.size() > 0 && (stages[0].stage == VK_SHADER_STAGE_MESH_BIT_EXT ||
                                              stages[0].stage == VK_SHADER_STAGE_TASK_BIT_EXT);

    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = desc.topology;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = std::max<uint32_t>(1, uint32_t(desc.viewportSwizzles.size()));
    viewport.scissorCount = viewport.viewportCount;
    // Per-viewport swizzles of the clip coordinates, applied before clipping (VK_NV_viewport_swizzle).
    VkPipelineViewportSwizzleStateCreateInfoNV swizzle{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_SWIZZLE_STATE_CREATE_INFO_NV};
    swizzle.viewportCount = uint32_t(desc.viewportSwizzles.size());
    swizzle.pViewportSwizzles = desc.viewportSwizzles.data();
    if (!desc.viewportSwizzles.empty()) viewport.pNext = &swizzle;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = desc.polygonMode;
    raster.cullMode = desc.cull;
    raster.frontFace = desc.frontFace;
    raster.lineWidth = 1.0f;
    // Overestimation: a fragment for every pixel the primitive touches at all (voxelization's thin walls).
    VkPipelineRasterizationConservativeStateCreateInfoEXT conservative{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_CONSERVATIVE_STATE_CREATE_INFO_EXT};
    conservative.conservativeRasterizationMode = VK_CONSERVATIVE_RASTERIZATION_MODE_OVERESTIMATE_EXT;
    if (desc.conservative) raster.pNext = &conservative;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = desc.depthFormat != VK_FORMAT_UNDEFINED && desc.depthTest;
    depth.depthWriteEnable = desc.depthFormat != VK_FORMAT_UNDEFINED && desc.depthWrite;
    depth.depthCompareOp = desc.depthCompare;

    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
    for (size_t i = 0; i < blends.size(); ++i) {
        BlendMode mode = i < desc.blend.size() ? desc.blend[i] : BlendMode::Opaque;
        VkPipelineColorBlendAttachmentState& b = blends[i];
        b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
        if (mode == BlendMode::Opaque) continue;
        b.blendEnable = VK_TRUE;
        b.srcColorBlendFactor = mode == BlendMode::Alpha ? VK_BLEND_FACTOR_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
        b.dstColorBlendFactor = mode == BlendMode::Alpha ? VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
        b.colorBlendOp = VK_BLEND_OP_ADD;
        b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        b.dstAlphaBlendFactor = mode == BlendMode::Alpha ? VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
        b.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = static_cast<uint32_t>(blends.size());
    blend.pAttachments = blends.data();

    VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                      VK_DYNAMIC_STATE_FRAGMENT_SHADING_RATE_KHR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    // KHR attachment rates: the combiner ops are dynamic state (vkCmdSetFragmentShadingRateKHR in the pass).
    dynamic.dynamicStateCount = desc.shadingRate == ShadingRateSource::KhrAttachment ? 3 : 2;
    dynamic.pDynamicStates = dynamicStates;
    // NV shading-rate image: the palette lives in the viewport state; texel value i selects palette entry i.
    std::array<VkShadingRatePaletteEntryNV, gpu::kVrsRateCount> paletteEntries{};
    for (uint32_t i = 0; i < gpu::kVrsRateCount; ++i) paletteEntries[i] = nvPaletteEntry(i);
    VkShadingRatePaletteNV palette{gpu::kVrsRateCount, paletteEntries.data()};
    VkPipelineViewportShadingRateImageStateCreateInfoNV nvRates{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_SHADING_RATE_IMAGE_STATE_CREATE_INFO_NV};
    nvRates.shadingRateImageEnable = VK_TRUE;
    nvRates.viewportCount = 1;
    nvRates.pShadingRatePalettes = &palette;
    if (desc.shadingRate == ShadingRateSource::NvImage) {  // (never with swizzles: one viewport, one palette)
        if (!desc.viewportSwizzles.empty()) throw PipelineError(name + ": NV shading-rate image with viewport swizzles");
        viewport.pNext = &nvRates;
    }

    // Dynamic rendering: the attachment formats replace a VkRenderPass.
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.viewMask = desc.viewMask;
    rendering.colorAttachmentCount = static_cast<uint32_t>(desc.colorFormats.size());
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    // Dynamic rendering with a rate attachment needs this flag on every pipeline drawn in it (VUID-vkCmdDraw-
    // imageView-06183); the KHR combiner state itself is dynamic (above).
    if (desc.shadingRate == ShadingRateSource::KhrAttachment)
        info.flags |= VK_PIPELINE_CREATE_RENDERING_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR;
    info.stageCount = static_cast<uint32_t>(stageInfos.size());
    info.pStages = stageInfos.data();
    info.pVertexInputState = meshPipeline ? nullptr : &vertexInput;
    info.pInputAssemblyState = meshPipeline ? nullptr : &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = ctx.pipelineLayout();
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkResult result = vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    for (VkShaderModule m : modules) vkDestroyShaderModule(ctx.device(), m, nullptr);
    check(result);
    ctx.setName(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
    return pipeline;
}

}  // namespace idk::vk
