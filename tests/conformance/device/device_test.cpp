// device_test.cpp: the device layer on the real Vulkan device: context creation, buffers through staging and
// mapped paths, bindless storage buffers, a compute dispatch through the shader library, image round trips.
#include <gtest/gtest.h>

#include <numeric>

#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

using vk::ShaderId;

class DeviceTest : public GpuTest {};

TEST_F(DeviceTest, ReportsBaselineAndSubgroupSize) {
    const vk::DeviceInfo& info = ctx().info();
    EXPECT_GE(info.apiVersion, VK_API_VERSION_1_3);
    EXPECT_FALSE(info.name.empty());
    EXPECT_GT(ctx().capabilities().subgroupSize, 0u);
    EXPECT_FALSE(ctx().ladders().empty());
}

TEST_F(DeviceTest, BufferRoundTripMatches) {
    std::vector<uint32_t> values(10000);
    std::iota(values.begin(), values.end(), 7u);
    vk::Buffer buffer = ctx().createBuffer({values.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            vk::MemoryUsage::GpuOnly, "round trip"});
    vk::uploadBuffer(ctx(), buffer, std::span<const uint32_t>(values));
    EXPECT_EQ(vk::downloadBuffer<uint32_t>(ctx(), buffer, values.size()), values);
    // Partial upload at an offset leaves the rest alone.
    uint32_t patch[2] = {1, 2};
    vk::uploadBuffer(ctx(), buffer, patch, sizeof(patch), 40);
    auto after = vk::downloadBuffer<uint32_t>(ctx(), buffer, 12);
    EXPECT_EQ(after[9], 16u);
    EXPECT_EQ(after[10], 1u);
    EXPECT_EQ(after[11], 2u);
    ctx().destroy(buffer);
}

TEST_F(DeviceTest, UploadPastTheEndThrows) {
    vk::Buffer buffer = ctx().createBuffer({16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "small"});
    uint8_t data[32] = {};
    EXPECT_THROW(vk::uploadBuffer(ctx(), buffer, data, sizeof(data), 0), std::out_of_range);
    ctx().destroy(buffer);
}

TEST_F(DeviceTest, ComputeFillThroughBindlessBuffer) {
    const uint32_t count = 1000;
    vk::Buffer buffer = ctx().createBuffer({count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly,
                                            "fill target"});
    vk::StorageBufferIndex index = ctx().bindless().addBuffer(buffer.buffer);
    struct Push {
        uint32_t count, value, buffer;
    } push{count, 0xC0FFEEu, index.value};
    const vk::Pipeline& fill = shaders().compute({ShaderId::conformance_fill_comp, {}, sizeof(Push), {{64, 1, 1}}});
    ctx().runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, fill);
        ctx().bindless().bind(cmd);
        vk::pushConstants(cmd, ctx(), push);
        vkCmdDispatch(cmd, vk::groupCount(count, 64), 1, 1);
    });
    auto out = vk::downloadBuffer<uint32_t>(ctx(), buffer, count);
    for (uint32_t v : out) ASSERT_EQ(v, 0xC0FFEEu);
    ctx().bindless().release(index);
    ctx().destroyDeferred(buffer);
}

TEST_F(DeviceTest, WrongPushSizeIsRejectedBeforeThePipelineExists) {
    EXPECT_THROW(shaders().compute({ShaderId::conformance_fill_comp, {}, 4, std::nullopt}), vk::PipelineError);
    EXPECT_THROW(shaders().compute({ShaderId::conformance_fill_comp, {}, 12, {{32, 1, 1}}}), vk::PipelineError);
}

TEST_F(DeviceTest, ImageRoundTrip) {
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.extent = {17, 9, 1};
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = "round trip image";
    vk::Image image = ctx().createImage(desc);
    std::vector<uint8_t> texels(17 * 9 * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<uint8_t>(i * 31);
    vk::uploadImage(ctx(), image, texels.data(), texels.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(vk::readbackImage(ctx(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), texels);
    ctx().destroy(image);
}

}  // namespace
}  // namespace idk::test
