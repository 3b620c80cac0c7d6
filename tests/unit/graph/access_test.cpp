// access_test.cpp: the Access table: exact masks/layouts for each entry, invalid combinations, derived usage.
#include "graph/access.hpp"

#include <gtest/gtest.h>

namespace idk::graph {
namespace {

struct Expected {
    Access access;
    ResourceKind kind;
    VkPipelineStageFlags2 stages;
    VkAccessFlags2 mask;
    VkImageLayout layout;
    bool isWrite;
};

constexpr VkPipelineStageFlags2 kShader = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                          VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kTests =
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;

TEST(AccessTable, EveryValidEntryIsExact) {
    const Expected table[] = {
        {Access::SampledRead, ResourceKind::Image, kShader, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false},
        {Access::SampledRead, ResourceKind::Buffer, kShader, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false},
        {Access::StorageRead, ResourceKind::Image, kShader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, false},
        {Access::StorageRead, ResourceKind::Buffer, kShader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false},
        {Access::StorageWrite, ResourceKind::Image, kShader, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, true},
        {Access::StorageWrite, ResourceKind::Buffer, kShader, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, true},
        {Access::StorageReadWrite, ResourceKind::Image, kShader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, true},
        {Access::StorageReadWrite, ResourceKind::Buffer, kShader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, true},
        {Access::ColorWrite, ResourceKind::Image, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true},
        {Access::ColorReadWrite, ResourceKind::Image, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true},
        {Access::DepthWrite, ResourceKind::Image, kTests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, true},
        {Access::DepthRead, ResourceKind::Image, kTests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, false},
        {Access::IndirectRead, ResourceKind::Buffer, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false},
        {Access::VertexRead, ResourceKind::Buffer, VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false},
        {Access::UniformRead, ResourceKind::Buffer, kShader, VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false},
        {Access::TransferSrc, ResourceKind::Image, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false},
        {Access::TransferSrc, ResourceKind::Buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false},
        {Access::TransferDst, ResourceKind::Image, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true},
        {Access::TransferDst, ResourceKind::Buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, true},
        {Access::Present, ResourceKind::Image, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, false},
        {Access::HostRead, ResourceKind::Buffer, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false},
        {Access::ShadingRateRead, ResourceKind::Image, VK_PIPELINE_STAGE_2_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR, VK_ACCESS_2_FRAGMENT_SHADING_RATE_ATTACHMENT_READ_BIT_KHR, VK_IMAGE_LAYOUT_FRAGMENT_SHADING_RATE_ATTACHMENT_OPTIMAL_KHR, false},
    };
    for (const Expected& e : table) {
        SCOPED_TRACE(std::string(toString(e.access)) + " on " + std::string(toString(e.kind)));
        const AccessInfo info = accessInfo(e.access, e.kind);
        EXPECT_TRUE(info.valid);
        EXPECT_EQ(info.defaultStages, e.stages);
        EXPECT_EQ(info.access, e.mask);
        EXPECT_EQ(info.layout, e.layout);
        EXPECT_EQ(info.isWrite, e.isWrite);
        EXPECT_EQ(info.defaultStages & ~info.allowedStages, 0u) << "default stages must be allowed";
        // The write flag and the access mask agree: a write access has a write bit and vice versa.
        EXPECT_EQ((info.access & kWriteAccessMask) != 0, e.isWrite);
    }
}

TEST(AccessTable, InvalidCombinations) {
    for (Access a : {Access::ColorWrite, Access::ColorReadWrite, Access::DepthWrite, Access::DepthRead, Access::Present,
                     Access::ShadingRateRead}) {
        EXPECT_FALSE(accessInfo(a, ResourceKind::Buffer).valid) << toString(a);
    }
    for (Access a : {Access::IndirectRead, Access::VertexRead, Access::UniformRead, Access::HostRead}) {
        EXPECT_FALSE(accessInfo(a, ResourceKind::Image).valid) << toString(a);
    }
    EXPECT_FALSE(accessInfo(static_cast<Access>(200), ResourceKind::Image).valid);
}

TEST(AccessTable, ShaderStagesAllowedForShaderAccessesOnly) {
    const AccessInfo sampled = accessInfo(Access::SampledRead, ResourceKind::Image);
    EXPECT_NE(sampled.allowedStages & VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT, 0u);
    EXPECT_EQ(sampled.allowedStages & VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0u);
    const AccessInfo color = accessInfo(Access::ColorWrite, ResourceKind::Image);
    EXPECT_EQ(color.allowedStages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0u);
}

TEST(AccessTable, DerivedUsage) {
    EXPECT_EQ(imageUsageFor(Access::SampledRead), VK_IMAGE_USAGE_SAMPLED_BIT);
    EXPECT_EQ(imageUsageFor(Access::StorageReadWrite), VK_IMAGE_USAGE_STORAGE_BIT);
    EXPECT_EQ(imageUsageFor(Access::ColorReadWrite), VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    EXPECT_EQ(imageUsageFor(Access::DepthRead), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    EXPECT_EQ(imageUsageFor(Access::TransferSrc), VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    EXPECT_EQ(imageUsageFor(Access::Present), 0u);
    EXPECT_EQ(imageUsageFor(Access::ShadingRateRead), VK_IMAGE_USAGE_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR);
    // VK_NV_shading_rate_image's usage, stage, access and layout are aliases of the KHR values the table uses.
    EXPECT_EQ(VK_IMAGE_USAGE_SHADING_RATE_IMAGE_BIT_NV, VK_IMAGE_USAGE_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR);
    EXPECT_EQ(VK_IMAGE_LAYOUT_SHADING_RATE_OPTIMAL_NV, VK_IMAGE_LAYOUT_FRAGMENT_SHADING_RATE_ATTACHMENT_OPTIMAL_KHR);
    EXPECT_EQ(VK_PIPELINE_STAGE_2_SHADING_RATE_IMAGE_BIT_NV, VK_PIPELINE_STAGE_2_FRAGMENT_SHADING_RATE_ATTACHMENT_BIT_KHR);
    EXPECT_EQ(VK_ACCESS_2_SHADING_RATE_IMAGE_READ_BIT_NV, VK_ACCESS_2_FRAGMENT_SHADING_RATE_ATTACHMENT_READ_BIT_KHR);
    EXPECT_EQ(bufferUsageFor(Access::IndirectRead), VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    EXPECT_EQ(bufferUsageFor(Access::VertexRead), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    EXPECT_EQ(bufferUsageFor(Access::UniformRead), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    EXPECT_EQ(bufferUsageFor(Access::StorageWrite), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    EXPECT_EQ(bufferUsageFor(Access::TransferDst), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    EXPECT_EQ(bufferUsageFor(Access::HostRead), 0u);
}

TEST(AccessTable, AspectMasks) {
    EXPECT_EQ(aspectMaskFor(VK_FORMAT_R8G8B8A8_UNORM), VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT});
    EXPECT_EQ(aspectMaskFor(VK_FORMAT_D32_SFLOAT), VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT});
    EXPECT_EQ(aspectMaskFor(VK_FORMAT_D24_UNORM_S8_UINT), VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT});
    EXPECT_TRUE(isDepthOrStencilFormat(VK_FORMAT_S8_UINT));
    EXPECT_FALSE(isDepthOrStencilFormat(VK_FORMAT_R32_UINT));
}

}  // namespace
}  // namespace idk::graph
