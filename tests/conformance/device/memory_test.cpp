// memory_test.cpp: the Vulkan memory sub-allocator, deferred destruction and bindless slot reuse on the device,
// and both upload paths (mapped and staged) whatever the process-wide staging setting is.
#include <gtest/gtest.h>

#include <numeric>
#include <set>

#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"
#include "shared/bindings.h"

namespace idk::test {
namespace {

class MemoryTest : public GpuTest {};

vk::BufferDesc storage(VkDeviceSize size, const char* name, const char* category = "test") {
    vk::BufferDesc d;
    d.size = size;
    d.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    d.name = name;
    d.category = category;
    return d;
}

TEST_F(MemoryTest, SmallBuffersShareBlocksWithoutOverlap) {
    uint32_t before = ctx().allocator().stats().deviceMemoryCount;
    std::vector<vk::Buffer> buffers;
    for (int i = 0; i < 64; ++i) buffers.push_back(ctx().createBuffer(storage(1000 + 37 * i, "small")));
    // 64 small buffers fit in at most one new block per memory type (a block is 64 MiB).
    EXPECT_LE(ctx().allocator().stats().deviceMemoryCount, before + 1);
    // Ranges in the same VkDeviceMemory never overlap and respect alignment.
    std::vector<std::pair<VkDeviceSize, VkDeviceSize>> ranges;
    for (const vk::Buffer& b : buffers) {
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(ctx().device(), b.buffer, &req);
        EXPECT_EQ(b.allocation.offset % req.alignment, 0u);
        if (b.allocation.memory == buffers[0].allocation.memory)
            ranges.emplace_back(b.allocation.offset, b.allocation.offset + b.allocation.size);
    }
    std::sort(ranges.begin(), ranges.end());
    for (size_t i = 1; i < ranges.size(); ++i) EXPECT_LE(ranges[i - 1].second, ranges[i].first);
    // Every buffer keeps its own contents.
    for (size_t i = 0; i < buffers.size(); ++i) {
        std::vector<uint32_t> v(buffers[i].size / 4, uint32_t(i));
        vk::uploadBuffer(ctx(), buffers[i], std::span<const uint32_t>(v));
    }
    for (size_t i = 0; i < buffers.size(); ++i) {
        auto v = vk::downloadBuffer<uint32_t>(ctx(), buffers[i], buffers[i].size / 4);
        for (uint32_t x : v) ASSERT_EQ(x, uint32_t(i));
    }
    for (vk::Buffer& b : buffers) ctx().destroy(b);
}

TEST_F(MemoryTest, LargeBuffersGetDedicatedMemoryAndStatsFollow) {
    const VkDeviceSize big = vk::MemoryAllocator::kDedicatedThreshold + 4096;
    vk::MemoryStats before = ctx().allocator().stats();
    vk::Buffer b = ctx().createBuffer(storage(big, "big", "test-big"));
    vk::MemoryStats during = ctx().allocator().stats();
    EXPECT_EQ(b.allocation.block, -1);
    EXPECT_EQ(during.deviceMemoryCount, before.deviceMemoryCount + 1);
    EXPECT_GE(during.bytesByCategory.at("test-big"), big);
    ctx().destroy(b);
    vk::MemoryStats after = ctx().allocator().stats();
    EXPECT_EQ(after.deviceMemoryCount, before.deviceMemoryCount);
    EXPECT_EQ(after.bytesByCategory.count("test-big"), 0u);
}

TEST_F(MemoryTest, DeferredDestructionWaitsForSubmittedWork) {
    bool released = false;
    // Nothing submitted after this point is pending, so a release queued now runs at the next collection.
    ctx().waitIdle();
    ctx().destroyDeferred([&] { released = true; });
    ctx().runImmediate([](VkCommandBuffer) {});
    EXPECT_TRUE(released);
}

TEST_F(MemoryTest, BindlessSlotsAreReusedOnlyAfterRetirement) {
    vk::Buffer b = ctx().createBuffer(storage(256, "bindless"));
    vk::StorageBufferIndex first = ctx().bindless().addBuffer(b.buffer);
    uint32_t live = ctx().bindless().liveCount(gpu::kBindingStorageBuffers);
    ctx().bindless().release(first);
    EXPECT_EQ(ctx().bindless().liveCount(gpu::kBindingStorageBuffers), live - 1);
    // Submit work that could still read the slot; until it completes, the slot is not handed out again.
    ctx().runImmediate([](VkCommandBuffer) {});
    vk::StorageBufferIndex second = ctx().bindless().addBuffer(b.buffer);
    EXPECT_EQ(second.value, first.value);  // retired after the submission above completed
    vk::StorageBufferIndex third = ctx().bindless().addBuffer(b.buffer);
    EXPECT_NE(third.value, second.value);
    ctx().bindless().release(second);
    ctx().bindless().release(third);
    ctx().destroyDeferred(b);
}

// The other upload path than the shared context's: a second context with the opposite staging setting.
TEST(MemoryPaths, StagedAndMappedUploadsAgree) {
    for (bool forceStaging : {false, true}) {
        vk::ContextDesc desc;
        desc.validation = true;
        desc.forceStaging = forceStaging;
        vk::Context ctx(desc);
        vk::Buffer b = ctx.createBuffer(storage(4096 * 4, "path"));
        EXPECT_EQ(b.mapped() == nullptr, forceStaging || !ctx.allocator().isUma());
        std::vector<uint32_t> v(4096);
        std::iota(v.begin(), v.end(), 3u);
        vk::uploadBuffer(ctx, b, std::span<const uint32_t>(v));
        EXPECT_EQ(vk::downloadBuffer<uint32_t>(ctx, b, v.size()), v) << "forceStaging=" << forceStaging;
        ctx.destroy(b);
        ctx.waitIdle();
        EXPECT_EQ(ctx.validationErrors(), 0u);
    }
}

}  // namespace
}  // namespace idk::test
