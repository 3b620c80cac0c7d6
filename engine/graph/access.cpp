// access.cpp: the (Access, kind) -> {stages, access mask, layout, isWrite} table and the usage it implies.
#include "graph/access.hpp"

#include <array>

namespace idk::graph {
namespace {

constexpr VkPipelineStageFlags2 kAnyShaderStage =
    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT |
    VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT | VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT |
    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
    VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT | VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT |
    VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT | VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT |
    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
constexpr VkPipelineStageFlags2 kColorStages = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
constexpr VkPipelineStageFlags2 kDepthStages =
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
constexpr VkPipelineStageFlags2 kGraphicsOrAll = VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT | VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
constexpr VkPipelineStageFlags2 kTransferStages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT |
                                                  VK_PIPELINE_STAGE_2_BLIT_BIT | VK_PIPELINE_STAGE_2_RESOLVE_BIT |
                                                  VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;

struct Row {
    Access access;
    AccessInfo image;
    AccessInfo buffer;
};

constexpr AccessInfo kInvalid{};

// clang-format off
// SYNC: the layout is the one the access REQUIRES (SHADER_READ_ONLY for sampling, GENERAL for storage images,
// *_ATTACHMENT_OPTIMAL for attachments, TRANSFER_*_OPTIMAL for copies). DEPTH_STENCIL_* layouts are used (not
// the depth-only ones) because they are valid for every depth format, with or without stencil.
constexpr std::array<Row, kAccessCount> kTable{{
    {Access::SampledRead,
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false},
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}},
    {Access::StorageRead,
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, false},
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}},
    {Access::StorageWrite,
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, true},
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, true}},
    {Access::StorageReadWrite,
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, true},
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, true}},
    {Access::ColorWrite,
     {true, kColorStages, kColorStages | kGraphicsOrAll, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true},
     kInvalid},
    {Access::ColorReadWrite,
     {true, kColorStages, kColorStages | kGraphicsOrAll, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true},
     kInvalid},
    // SYNC: the depth test reads the attachment in the early and late test stages, so a depth write carries
    // both READ and WRITE and both stages.
    {Access::DepthWrite,
     {true, kDepthStages, kDepthStages | kGraphicsOrAll, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, true},
     kInvalid},
    {Access::DepthRead,
     {true, kDepthStages, kDepthStages | kGraphicsOrAll, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, false},
     kInvalid},
    // SYNC: indirect dispatch arguments are also read in DRAW_INDIRECT (there is no dispatch-indirect stage).
    {Access::IndirectRead,
     kInvalid,
     {true, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | kGraphicsOrAll, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}},
    {Access::VertexRead,
     kInvalid,
     {true, VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT, VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT | VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | kGraphicsOrAll,
      VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}},
    {Access::UniformRead,
     kInvalid,
     {true, kDefaultShaderStages, kAnyShaderStage, VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}},
    {Access::TransferSrc,
     {true, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, kTransferStages, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false},
     {true, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, kTransferStages, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}},
    {Access::TransferDst,
     {true, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, kTransferStages, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true},
     {true, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, kTransferStages, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, true}},
    // SYNC: the presentation engine is synchronized by the semaphore vkQueuePresentKHR waits on, not by a
    // pipeline stage, so the transition to PRESENT_SRC names no destination stage or access. The submit
    // must signal that semaphore at ALL_COMMANDS so the layout transition is inside its first scope.
    {Access::Present,
     {true, VK_PIPELINE_STAGE_2_NONE, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, false},
     kInvalid},
    // SYNC: a host read after the fence still needs a device-side barrier to the HOST stage, which makes
    // the GPU's writes available to the host domain (the fence alone does not).
    {Access::HostRead,
     kInvalid,
     {true, VK_PIPELINE_STAGE_2_HOST_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false}},
    // SYNC: the rasterizer reads the rate texels in their own stage; VK_NV_shading_rate_image's stage, access and
    // layout (SHADING_RATE_IMAGE_BIT_NV, SHADING_RATE_IMAGE_READ_BIT_NV, SHADING_RATE_OPTIMAL_NV) are aliases of these.
    {Access::ShadingRateRead,
     {true, VK_PIPELINE_STAGE_2_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR, VK_PIPELINE_STAGE_2_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR | kGraphicsOrAll,
      VK_ACCESS_2_FRAGMENT_SHADING_RATE_ATTACHMENT_READ_BIT_KHR, VK_IMAGE_LAYOUT_FRAGMENT_SHADING_RATE_ATTACHMENT_OPTIMAL_KHR, false},
     kInvalid},
}};
// clang-format on

constexpr bool tableInEnumOrder() {
    for (uint32_t i = 0; i < kAccessCount; ++i) {
        if (static_cast<uint32_t>(kTable[i].access) != i) return false;
    }
    return true;
}
static_assert(tableInEnumOrder(), "kTable rows must follow the order of enum Access");

}  // namespace

AccessInfo accessInfo(Access access, ResourceKind kind) noexcept {
    const auto index = static_cast<uint32_t>(access);
    if (index >= kAccessCount) return kInvalid;
    return kind == ResourceKind::Image ? kTable[index].image : kTable[index].buffer;
}

VkImageUsageFlags imageUsageFor(Access access) noexcept {
    switch (access) {
        case Access::SampledRead: return VK_IMAGE_USAGE_SAMPLED_BIT;
        case Access::StorageRead:
        case Access::StorageWrite:
        case Access::StorageReadWrite: return VK_IMAGE_USAGE_STORAGE_BIT;
        case Access::ColorWrite:
        case Access::ColorReadWrite: return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        case Access::DepthWrite:
        case Access::DepthRead: return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        case Access::TransferSrc: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        case Access::TransferDst: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        case Access::ShadingRateRead: return VK_IMAGE_USAGE_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR;
        default: return 0;
    }
}

VkBufferUsageFlags bufferUsageFor(Access access) noexcept {
    switch (access) {
        case Access::SampledRead: return VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        case Access::StorageRead:
        case Access::StorageWrite:
        case Access::StorageReadWrite: return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        case Access::IndirectRead: return VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
        case Access::VertexRead: return VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
        case Access::UniformRead: return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
        case Access::TransferSrc: return VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
        case Access::TransferDst: return VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        default: return 0;
    }
}

std::string_view toString(Access access) noexcept {
    switch (access) {
        case Access::SampledRead: return "SampledRead";
        case Access::StorageRead: return "StorageRead";
        case Access::StorageWrite: return "StorageWrite";
        case Access::StorageReadWrite: return "StorageReadWrite";
        case Access::ColorWrite: return "ColorWrite";
        case Access::ColorReadWrite: return "ColorReadWrite";
        case Access::DepthWrite: return "DepthWrite";
        case Access::DepthRead: return "DepthRead";
        case Access::IndirectRead: return "IndirectRead";
        case Access::VertexRead: return "VertexRead";
        case Access::UniformRead: return "UniformRead";
        case Access::TransferSrc: return "TransferSrc";
        case Access::TransferDst: return "TransferDst";
        case Access::Present: return "Present";
        case Access::HostRead: return "HostRead";
        case Access::ShadingRateRead: return "ShadingRateRead";
    }
    return "?";
}

std::string_view toString(ResourceKind kind) noexcept { return kind == ResourceKind::Image ? "image" : "buffer"; }

bool isDepthOrStencilFormat(VkFormat format) noexcept { return aspectMaskFor(format) != VK_IMAGE_ASPECT_COLOR_BIT; }

VkImageAspectFlags aspectMaskFor(VkFormat format) noexcept {
    switch (format) {
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_X8_D24_UNORM_PACK32:
        case VK_FORMAT_D32_SFLOAT: return VK_IMAGE_ASPECT_DEPTH_BIT;
        case VK_FORMAT_S8_UINT: return VK_IMAGE_ASPECT_STENCIL_BIT;
        case VK_FORMAT_D16_UNORM_S8_UINT:
        case VK_FORMAT_D24_UNORM_S8_UINT:
        case VK_FORMAT_D32_SFLOAT_S8_UINT: return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
        default: return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

}  // namespace idk::graph
