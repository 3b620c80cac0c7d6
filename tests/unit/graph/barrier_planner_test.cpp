// barrier_planner_test.cpp: truth table of the pure planner (RAW/WAR/WAW on images and buffers, read-after-
// read, layout transitions, discard/UNDEFINED, aliasing), exact masks and layouts.
#include "graph/barrier_planner.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace idk::graph {
namespace {

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kFragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
constexpr VkPipelineStageFlags2 kVertex = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
constexpr VkPipelineStageFlags2 kColorOut = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
constexpr VkPipelineStageFlags2 kTests =
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
constexpr VkPipelineStageFlags2 kTransfer = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;

Use image(Access a, VkPipelineStageFlags2 stages = 0, bool discard = false) {
    return Use{ResourceKind::Image, a, stages, discard};
}
Use buffer(Access a, VkPipelineStageFlags2 stages = 0) { return Use{ResourceKind::Buffer, a, stages, false}; }

PlannedBarrier expectBarrier(ResourceKind kind, VkPipelineStageFlags2 src, VkAccessFlags2 srcAccess,
                             VkPipelineStageFlags2 dst, VkAccessFlags2 dstAccess, VkImageLayout oldLayout,
                             VkImageLayout newLayout, bool aliasing = false) {
    PlannedBarrier b;
    b.kind = kind;
    b.srcStages = src;
    b.srcAccess = srcAccess;
    b.dstStages = dst;
    b.dstAccess = dstAccess;
    b.oldLayout = oldLayout;
    b.newLayout = newLayout;
    b.aliasing = aliasing;
    return b;
}

// Applies uses in sequence; returns the barrier of each step.
std::vector<std::optional<PlannedBarrier>> run(ResourceState state, const std::vector<Use>& uses,
                                               ResourceState* finalState = nullptr) {
    std::vector<std::optional<PlannedBarrier>> out;
    for (const Use& use : uses) {
        const Transition t = applyUse(state, use);
        out.push_back(t.barrier);
        state = t.after;
    }
    if (finalState) *finalState = state;
    return out;
}

// ---- First use / layout transitions ----

TEST(BarrierPlanner, FirstUseOfTransientImageTransitionsFromUndefined) {
    const auto b = planBarrier(ResourceState{}, image(Access::StorageWrite, kCompute, true));
    ASSERT_TRUE(b);
    EXPECT_EQ(*b, expectBarrier(ResourceKind::Image, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, kCompute,
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL));
}

TEST(BarrierPlanner, FirstUseAsColorAttachment) {
    const auto b = planBarrier(ResourceState{}, image(Access::ColorWrite));
    ASSERT_TRUE(b);
    EXPECT_EQ(*b, expectBarrier(ResourceKind::Image, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, kColorOut,
                                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL));
}

TEST(BarrierPlanner, StateAfterFirstWrite) {
    const Transition t = applyUse(ResourceState{}, image(Access::StorageWrite, kCompute, true));
    EXPECT_EQ(t.after.layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(t.after.writeStages, kCompute);
    EXPECT_EQ(t.after.unflushedWrites, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(t.after.readStages, VK_PIPELINE_STAGE_2_NONE);
}

TEST(BarrierPlanner, SwapchainAcquireWaitsOnAcquireStage) {
    ResourceState acquired;
    acquired.writeStages = kColorOut;   // the acquire semaphore is waited on at COLOR_ATTACHMENT_OUTPUT
    const auto b = planBarrier(acquired, image(Access::ColorWrite));
    ASSERT_TRUE(b);
    EXPECT_EQ(*b, expectBarrier(ResourceKind::Image, kColorOut, VK_ACCESS_2_NONE, kColorOut,
                                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL));
}

TEST(BarrierPlanner, RawWithLayoutTransition) {
    const auto b = run({}, {image(Access::StorageWrite, kCompute, true), image(Access::SampledRead, kFragment)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Image, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kFragment,
                                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
}

TEST(BarrierPlanner, ColorToPresent) {
    const auto b = run({}, {image(Access::ColorWrite), image(Access::Present)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Image, kColorOut, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                   VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR));
}

TEST(BarrierPlanner, DepthWriteThenDepthReadThenSampled) {
    const auto b = run({}, {image(Access::DepthWrite), image(Access::DepthRead), image(Access::SampledRead, kCompute)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Image, kTests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, kTests,
                                   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                                   VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                                   VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL));
    // The second transition waits on the first transition's stages (chain) and the depth readers; nothing
    // to flush any more.
    ASSERT_TRUE(b[2]);
    EXPECT_EQ(*b[2], expectBarrier(ResourceKind::Image, kTests, VK_ACCESS_2_NONE, kCompute,
                                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
}

TEST(BarrierPlanner, ReadOnlyToReadOnlyLayoutChangeWaitsOnReaders) {
    // Imported as sampled at FRAGMENT (nothing to make visible), then copied from.
    const ResourceState sampled = stateAfterAccess(Access::SampledRead, ResourceKind::Image, kFragment);
    const auto b = planBarrier(sampled, image(Access::TransferSrc));
    ASSERT_TRUE(b);
    EXPECT_EQ(*b, expectBarrier(ResourceKind::Image, kFragment, VK_ACCESS_2_NONE, kTransfer, VK_ACCESS_2_TRANSFER_READ_BIT,
                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
}

TEST(BarrierPlanner, DiscardKeepsLayoutButStartsFromUndefined) {
    // Same layout (GENERAL) but the contents are not needed: still a barrier, old layout UNDEFINED, and it
    // still waits on (and flushes) the earlier write.
    const auto b = run({}, {image(Access::StorageWrite, kCompute, true), image(Access::StorageWrite, kCompute, true)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Image, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute,
                                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                   VK_IMAGE_LAYOUT_GENERAL));
}

// ---- Same layout: RAW / WAW / WAR on images ----

TEST(BarrierPlanner, ImageRawSameLayout) {
    const auto b = run({}, {image(Access::StorageWrite, kCompute, true), image(Access::StorageRead, kFragment)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Image, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kFragment,
                                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL));
}

TEST(BarrierPlanner, ImageWawSameLayout) {
    const auto b = run({}, {image(Access::StorageWrite, kCompute, true), image(Access::StorageWrite, kCompute)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Image, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute,
                                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL));
}

TEST(BarrierPlanner, ImagePureWarIsExecutionOnly) {
    const ResourceState readOnly = stateAfterAccess(Access::StorageRead, ResourceKind::Image, kFragment);
    const auto b = planBarrier(readOnly, image(Access::StorageWrite, kCompute));
    ASSERT_TRUE(b);
    EXPECT_EQ(*b, expectBarrier(ResourceKind::Image, kFragment, VK_ACCESS_2_NONE, kCompute, VK_ACCESS_2_NONE,
                                VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL));
}

TEST(BarrierPlanner, WarAfterWriteWaitsOnReadersAndKeepsWriteOrdered) {
    // write(C) -> read(F) -> write(C): the reads need only an execution dependency, but the earlier write is
    // also a WAW hazard: the barrier waits on both and makes memory visible to the new write.
    const auto b = run({}, {image(Access::StorageWrite, kCompute, true), image(Access::StorageRead, kFragment),
                            image(Access::StorageWrite, kCompute)});
    ASSERT_TRUE(b[2]);
    EXPECT_EQ(*b[2], expectBarrier(ResourceKind::Image, kCompute | kFragment, VK_ACCESS_2_NONE, kCompute,
                                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL));
}

// ---- Read after read ----

TEST(BarrierPlanner, ReadAfterReadSameStageNeedsNoBarrier) {
    ResourceState last;
    const auto b = run({}, {image(Access::StorageWrite, kCompute, true), image(Access::StorageRead, kCompute),
                            image(Access::StorageRead, kCompute)}, &last);
    EXPECT_TRUE(b[1]);
    EXPECT_FALSE(b[2]);
    EXPECT_EQ(last.readStages, kCompute);
}

TEST(BarrierPlanner, ReadAfterReadCoveredByEarlierBarrierNeedsNoBarrier) {
    // One transition for readers in FRAGMENT|COMPUTE covers later reads in either stage.
    const auto b = run({}, {image(Access::ColorWrite), image(Access::SampledRead, kFragment | kCompute),
                            image(Access::SampledRead, kCompute), image(Access::SampledRead, kFragment)});
    EXPECT_TRUE(b[1]);
    EXPECT_FALSE(b[2]);
    EXPECT_FALSE(b[3]);
}

TEST(BarrierPlanner, ReadInNewStageStillNeedsVisibility) {
    // SYNC: the write was made visible to FRAGMENT only; a COMPUTE read needs its own visibility operation, and
    // repeats the write's availability (the first barrier is not in this one's dependency chain).
    const auto b = run({}, {image(Access::StorageWrite, kCompute, true), image(Access::StorageRead, kFragment),
                            image(Access::StorageRead, kCompute)});
    ASSERT_TRUE(b[2]);
    EXPECT_EQ(*b[2], expectBarrier(ResourceKind::Image, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute,
                                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL));
}

TEST(BarrierPlanner, ReadersAccumulateSoTheNextWriteWaitsOnAll) {
    // Imported as sampled by FRAGMENT: later sampled reads in VERTEX and COMPUTE need no barrier, but the
    // write that follows must wait on all three stages.
    ResourceState last;
    const auto b = run(stateAfterAccess(Access::SampledRead, ResourceKind::Image, kFragment),
                       {image(Access::SampledRead, kVertex), image(Access::SampledRead, kCompute),
                        image(Access::StorageWrite, kCompute)}, &last);
    EXPECT_FALSE(b[0]);
    EXPECT_FALSE(b[1]);
    ASSERT_TRUE(b[2]);
    EXPECT_EQ(*b[2], expectBarrier(ResourceKind::Image, kFragment | kVertex | kCompute, VK_ACCESS_2_NONE, kCompute,
                                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                   VK_IMAGE_LAYOUT_GENERAL));
    EXPECT_EQ(last.readStages, VK_PIPELINE_STAGE_2_NONE);
    EXPECT_EQ(last.writeStages, kCompute);
}

// ---- Buffers ----

TEST(BarrierPlanner, FreshBufferWriteNeedsNoBarrier) {
    EXPECT_FALSE(planBarrier(ResourceState{}, buffer(Access::StorageWrite, kCompute)));
    EXPECT_FALSE(planBarrier(ResourceState{}, buffer(Access::TransferDst)));
}

TEST(BarrierPlanner, BufferRawIndirect) {
    const auto b = run({}, {buffer(Access::StorageWrite, kCompute), buffer(Access::IndirectRead)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Buffer, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                   VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                                   VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED));
}

TEST(BarrierPlanner, BufferWawTransferThenCompute) {
    const auto b = run({}, {buffer(Access::TransferDst), buffer(Access::StorageWrite, kCompute)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Buffer, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, kCompute,
                                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                   VK_IMAGE_LAYOUT_UNDEFINED));
}

TEST(BarrierPlanner, BufferPureWarIsExecutionOnly) {
    const auto b = planBarrier(stateAfterAccess(Access::VertexRead, ResourceKind::Buffer), buffer(Access::TransferDst));
    ASSERT_TRUE(b);
    EXPECT_EQ(*b, expectBarrier(ResourceKind::Buffer, VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT, VK_ACCESS_2_NONE, kTransfer,
                                VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED));
}

TEST(BarrierPlanner, BufferReadAfterReadNeedsNoBarrier) {
    const auto b = run(stateAfterAccess(Access::VertexRead, ResourceKind::Buffer),
                       {buffer(Access::VertexRead), buffer(Access::UniformRead, kVertex)});
    EXPECT_FALSE(b[0]);
    EXPECT_FALSE(b[1]);
}

TEST(BarrierPlanner, BufferNewAccessTypeInSameStageNeedsVisibility) {
    const auto b = run({}, {buffer(Access::StorageWrite, kCompute), buffer(Access::StorageRead, kCompute),
                            buffer(Access::UniformRead, kCompute)});
    ASSERT_TRUE(b[1]);
    ASSERT_TRUE(b[2]);
    EXPECT_EQ(*b[2], expectBarrier(ResourceKind::Buffer, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute,
                                   VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED));
}

TEST(BarrierPlanner, BufferHostReadbackNeedsHostBarrier) {
    const auto b = run({}, {buffer(Access::StorageWrite, kCompute), buffer(Access::HostRead)});
    ASSERT_TRUE(b[1]);
    EXPECT_EQ(*b[1], expectBarrier(ResourceKind::Buffer, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                   VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                   VK_IMAGE_LAYOUT_UNDEFINED));
}

TEST(BarrierPlanner, BufferReadWriteAccessFlushesOnlyWriteBits) {
    ResourceState last;
    run({}, {buffer(Access::StorageReadWrite, kCompute)}, &last);
    EXPECT_EQ(last.unflushedWrites, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

// ---- Aliasing and invalid input ----

TEST(BarrierPlanner, AliasedMemoryWaitsOnPreviousOccupant) {
    ResourceState previousOccupant;
    run({}, {image(Access::ColorWrite), image(Access::SampledRead, kFragment)}, &previousOccupant);
    const ResourceState seed = mergeForAliasing(ResourceState{}, previousOccupant);
    EXPECT_TRUE(seed.aliasedMemory);
    EXPECT_EQ(seed.layout, VK_IMAGE_LAYOUT_UNDEFINED);
    const Transition t = applyUse(seed, image(Access::StorageWrite, kCompute, true));
    ASSERT_TRUE(t.barrier);
    EXPECT_EQ(*t.barrier, expectBarrier(ResourceKind::Image, kFragment, VK_ACCESS_2_NONE, kCompute,
                                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                        VK_IMAGE_LAYOUT_GENERAL, true));
    EXPECT_FALSE(t.after.aliasedMemory);
}

TEST(BarrierPlanner, AliasingFlushesThePreviousOccupantsWrites) {
    ResourceState previousOccupant;
    run({}, {buffer(Access::StorageWrite, kCompute)}, &previousOccupant);
    const auto b = planBarrier(mergeForAliasing(ResourceState{}, previousOccupant), buffer(Access::TransferDst));
    ASSERT_TRUE(b);
    EXPECT_EQ(*b, expectBarrier(ResourceKind::Buffer, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kTransfer,
                                VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED,
                                true));
}

TEST(BarrierPlanner, MergeOfNothingIsNotAliased) {
    EXPECT_EQ(mergeForAliasing(ResourceState{}, ResourceState{}), ResourceState{});
}

TEST(BarrierPlanner, InvalidUseChangesNothing) {
    ResourceState s = stateAfterAccess(Access::StorageWrite, ResourceKind::Buffer, kCompute);
    const Transition t = applyUse(s, buffer(Access::ColorWrite));
    EXPECT_FALSE(t.barrier);
    EXPECT_EQ(t.after, s);
}

TEST(BarrierPlanner, DefaultStagesComeFromTheTable) {
    EXPECT_EQ(effectiveStages(image(Access::ColorWrite)), kColorOut);
    EXPECT_EQ(effectiveStages(image(Access::SampledRead, kCompute)), kCompute);
}

}  // namespace
}  // namespace idk::graph
