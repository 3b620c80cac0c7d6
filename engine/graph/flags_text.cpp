// flags_text.cpp: bit-by-bit names for the stage/access bits the graph uses; anything else prints as hex.
#include "graph/flags_text.hpp"
#include "graph/text_format.hpp"

#include <utility>

namespace idk::graph {
namespace {

template <class Flags, size_t N>
std::string names(Flags flags, const std::pair<Flags, const char*> (&table)[N]) {
    if (flags == 0) return "NONE";
    std::string text;
    for (const auto& [bit, name] : table) {
        if ((flags & bit) != bit) continue;
        if (!text.empty()) text += '|';
        text += name;
        flags &= ~bit;
    }
    if (flags != 0) text += (text.empty() ? "" : "|") + hex(flags);
    return text;
}

}  // namespace

std::string stageNames(VkPipelineStageFlags2 stages) {
    static const std::pair<VkPipelineStageFlags2, const char*> kTable[] = {
        {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "ALL_COMMANDS"},
        {VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, "ALL_GRAPHICS"},
        {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, "ALL_TRANSFER"},
        {VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, "TOP_OF_PIPE"},
        {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, "DRAW_INDIRECT"},
        {VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT, "VERTEX_INPUT"},
        {VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, "INDEX_INPUT"},
        {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, "VERTEX_ATTRIBUTE_INPUT"},
        {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, "VERTEX"},
        {VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT, "TESS_CONTROL"},
        {VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT, "TESS_EVALUATION"},
        {VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT, "GEOMETRY"},
        {VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT, "TASK"},
        {VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT, "MESH"},
        {VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT, "PRE_RASTERIZATION"},
        {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "FRAGMENT"},
        {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT, "EARLY_FRAGMENT_TESTS"},
        {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "LATE_FRAGMENT_TESTS"},
        {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "COLOR_ATTACHMENT_OUTPUT"},
        {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "COMPUTE"},
        {VK_PIPELINE_STAGE_2_COPY_BIT, "COPY"},
        {VK_PIPELINE_STAGE_2_BLIT_BIT, "BLIT"},
        {VK_PIPELINE_STAGE_2_RESOLVE_BIT, "RESOLVE"},
        {VK_PIPELINE_STAGE_2_CLEAR_BIT, "CLEAR"},
        {VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, "BOTTOM_OF_PIPE"},
        {VK_PIPELINE_STAGE_2_HOST_BIT, "HOST"},
    };
    return names(stages, kTable);
}

std::string accessNames(VkAccessFlags2 access) {
    static const std::pair<VkAccessFlags2, const char*> kTable[] = {
        {VK_ACCESS_2_MEMORY_READ_BIT, "MEMORY_READ"},
        {VK_ACCESS_2_MEMORY_WRITE_BIT, "MEMORY_WRITE"},
        {VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, "INDIRECT_COMMAND_READ"},
        {VK_ACCESS_2_INDEX_READ_BIT, "INDEX_READ"},
        {VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, "VERTEX_ATTRIBUTE_READ"},
        {VK_ACCESS_2_UNIFORM_READ_BIT, "UNIFORM_READ"},
        {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "SHADER_SAMPLED_READ"},
        {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "SHADER_STORAGE_READ"},
        {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "SHADER_STORAGE_WRITE"},
        {VK_ACCESS_2_SHADER_READ_BIT, "SHADER_READ"},
        {VK_ACCESS_2_SHADER_WRITE_BIT, "SHADER_WRITE"},
        {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "COLOR_ATTACHMENT_READ"},
        {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "COLOR_ATTACHMENT_WRITE"},
        {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, "DEPTH_STENCIL_ATTACHMENT_READ"},
        {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, "DEPTH_STENCIL_ATTACHMENT_WRITE"},
        {VK_ACCESS_2_TRANSFER_READ_BIT, "TRANSFER_READ"},
        {VK_ACCESS_2_TRANSFER_WRITE_BIT, "TRANSFER_WRITE"},
        {VK_ACCESS_2_HOST_READ_BIT, "HOST_READ"},
        {VK_ACCESS_2_HOST_WRITE_BIT, "HOST_WRITE"},
    };
    return names(access, kTable);
}

std::string_view layoutName(VkImageLayout layout) {
    switch (layout) {
        case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
        case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
        case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "DEPTH_STENCIL_ATTACHMENT";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "DEPTH_STENCIL_READ_ONLY";
        case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY";
        case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC";
        case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST";
        case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return "PRESENT_SRC";
        case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL: return "READ_ONLY";
        case VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL: return "ATTACHMENT";
        default: return "OTHER_LAYOUT";
    }
}

std::string describe(const PlannedBarrier& b, std::string_view resourceName) {
    std::string text = strformat("{} '{}'", toString(b.kind), resourceName);
    if (b.kind == ResourceKind::Image && b.oldLayout != b.newLayout) {
        text += strformat(" {}->{}", layoutName(b.oldLayout), layoutName(b.newLayout));
    }
    text += strformat(" [{}:{} -> {}:{}]", stageNames(b.srcStages), accessNames(b.srcAccess), stageNames(b.dstStages),
                        accessNames(b.dstAccess));
    if (b.aliasing) text += " (aliased memory)";
    return text;
}

}  // namespace idk::graph
