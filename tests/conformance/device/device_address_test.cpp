// device_address_test.cpp: buffer device addresses reach past the storage-buffer descriptor range: a 160 MiB
// buffer (lavapipe's maxStorageBufferRange is 128 MiB) is written near its end through an address in push
// constants, and the push block with a 64-bit pointer reflects to the C++ struct's size.
#include <gtest/gtest.h>

#include "support/gpu_fixture.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

class DeviceAddressTest : public GpuTest {};

struct Push {
    uint64_t target;
    uint32_t count, value;
};
static_assert(sizeof(Push) == 16);

TEST_F(DeviceAddressTest, WritesBeyondTheDescriptorRange) {
    const VkDeviceSize bytes = 160ull << 20;
    const uint32_t count = 4096;
    const VkDeviceSize offset = bytes - count * 4;  // the last 16 KiB, past 128 MiB
    vk::Buffer big = ctx().createBuffer({bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "big"});
    ASSERT_NE(big.address, 0u);
    const vk::Pipeline& fill =
        shaders().compute({vk::ShaderId::conformance_fill_address_comp, {}, sizeof(Push), {{64, 1, 1}}});
    EXPECT_TRUE(shaders().info(vk::ShaderId::conformance_fill_address_comp).uses64BitPointers);
    Push push{big.address + offset, count, 1000};
    ctx().runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, fill);
        vk::pushConstants(cmd, ctx(), push);
        vkCmdDispatch(cmd, vk::groupCount(count, 64), 1, 1);
    });
    std::vector<uint32_t> out = vk::downloadBuffer<uint32_t>(ctx(), big, count, offset);
    for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(out[i], 1000 + i) << i;
    ctx().destroy(big);
}

}  // namespace
}  // namespace idk::test
