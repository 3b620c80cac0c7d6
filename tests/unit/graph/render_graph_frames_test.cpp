// render_graph_frames_test.cpp: execute() and what survives across frames, with a fake backend and fake
// vkCmd* entry points: history ping-pong and the first-frame (cleared) state, resize, imported resources'
// final transitions, the recorded command stream (labels, timestamps, barriers, callbacks), pool reuse.
#include "fake_backend.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace idk::graph {
namespace {

using testing::colorDesc;
using testing::eventLog;
using testing::fakeCmd;
using testing::fakeHandle;
using testing::FakeBackend;
using testing::FakeVulkanCommands;
using testing::recordedDependencies;

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kFragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
constexpr VkPipelineStageFlags2 kColorOut = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;

struct TaaFrame {
    TextureHandle history, current;
    VkImage historyImage = VK_NULL_HANDLE, currentImage = VK_NULL_HANDLE;
    bool historyValid = true;
    std::vector<PlannedBarrier> prologue, taaBarriers;
};

// One TAA-like frame: "taa" reads last frame's "taa_out" and writes this frame's.
TaaFrame runTaaFrame(ResourcePool& pool, VkExtent2D extent = {64, 64}) {
    TaaFrame f;
    RenderGraph graph(pool, extent);
    TextureDesc desc = colorDesc(VK_FORMAT_R16G16B16A16_SFLOAT);
    desc.persistent = true;
    graph.addPass("taa", [&](PassBuilder& b) {
        f.history = b.read(b.history("taa_out"), Access::SampledRead, kCompute);
        f.current = b.write(b.create("taa_out", desc), Access::StorageWrite, kCompute);
    }, [&](PassContext& ctx) {
        f.historyImage = ctx.image(f.history);
        f.currentImage = ctx.image(f.current);
        f.historyValid = ctx.historyValid(f.history);
    });
    graph.compile();
    f.prologue.assign(graph.prologueBarriers().begin(), graph.prologueBarriers().end());
    f.taaBarriers.assign(graph.barriersBefore("taa").begin(), graph.barriersBefore("taa").end());
    graph.execute(fakeCmd());
    return f;
}

TEST(GraphFrames, HistoryIsClearedOnTheFirstFrameThenPingPongs) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);

    const TaaFrame f0 = runTaaFrame(pool);
    ASSERT_EQ(backend.createdTextures.size(), 2u);
    EXPECT_EQ(backend.createdTextures[0].name, "taa_out[0]");
    EXPECT_FALSE(backend.createdTextures[0].placed) << "persistent copies are dedicated, never aliased";
    EXPECT_NE(backend.createdTextures[0].texture.usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0u);
    const VkImage copy0 = fakeHandle<VkImage>(0x1001), copy1 = fakeHandle<VkImage>(0x1002);
    EXPECT_EQ(f0.currentImage, copy0);
    EXPECT_EQ(f0.historyImage, copy1);
    // First frame: history never written -> defined as zeros: UNDEFINED -> TRANSFER_DST, clear, then read.
    EXPECT_FALSE(f0.historyValid);
    ASSERT_EQ(f0.prologue.size(), 1u);
    EXPECT_EQ(f0.prologue[0].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(f0.prologue[0].newLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    // A new image may sit in recycled memory: its first barrier waits on every earlier command (graph_plan.cpp).
    EXPECT_EQ(f0.prologue[0].srcStages, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    ASSERT_EQ(testing::clearedImages().size(), 1u);
    EXPECT_EQ(testing::clearedImages()[0], copy1);
    ASSERT_EQ(f0.taaBarriers.size(), 2u);
    EXPECT_EQ(f0.taaBarriers[0].oldLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    EXPECT_EQ(f0.taaBarriers[0].newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(f0.taaBarriers[0].srcStages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    EXPECT_EQ(f0.taaBarriers[0].srcAccess, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    EXPECT_EQ(f0.taaBarriers[0].dstStages, kCompute);
    EXPECT_EQ(f0.taaBarriers[0].dstAccess, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    EXPECT_EQ(f0.taaBarriers[1].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(f0.taaBarriers[1].newLayout, VK_IMAGE_LAYOUT_GENERAL);

    // Second frame: the copies swap; last frame's write is the history; no clear.
    testing::clearedImages().clear();
    const TaaFrame f1 = runTaaFrame(pool);
    EXPECT_EQ(backend.createdTextures.size(), 2u) << "copies are reused across frames";
    EXPECT_EQ(f1.currentImage, copy1);
    EXPECT_EQ(f1.historyImage, copy0);
    EXPECT_TRUE(f1.historyValid);
    EXPECT_TRUE(f1.prologue.empty());
    EXPECT_TRUE(testing::clearedImages().empty());
    ASSERT_EQ(f1.taaBarriers.size(), 2u);
    // History (copy0) was last written in GENERAL by frame 0's StorageWrite at COMPUTE.
    EXPECT_EQ(f1.taaBarriers[0].oldLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(f1.taaBarriers[0].newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(f1.taaBarriers[0].srcStages, kCompute);
    EXPECT_EQ(f1.taaBarriers[0].srcAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    // Current (copy1) was read as history at COMPUTE in frame 0: overwrite waits on that read (WAR), discards.
    EXPECT_EQ(f1.taaBarriers[1].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(f1.taaBarriers[1].newLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(f1.taaBarriers[1].srcStages, kCompute);
    EXPECT_EQ(f1.taaBarriers[1].srcAccess, VK_ACCESS_2_NONE);

    const TaaFrame f2 = runTaaFrame(pool);
    EXPECT_EQ(f2.currentImage, copy0);
    EXPECT_EQ(f2.historyImage, copy1);
    EXPECT_TRUE(f2.historyValid);
    EXPECT_EQ(pool.frameIndex(), 3u);
}

TEST(GraphFrames, ResizeRecreatesTheCopiesAndClearsHistory) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    runTaaFrame(pool, {64, 64});
    runTaaFrame(pool, {64, 64});
    const TaaFrame resized = runTaaFrame(pool, {128, 64});
    EXPECT_EQ(backend.destroyedImages.size(), 2u);
    ASSERT_EQ(backend.createdTextures.size(), 4u);
    EXPECT_EQ(backend.createdTextures[2].texture.extent.width, 128u);
    EXPECT_FALSE(resized.historyValid);
    EXPECT_EQ(resized.prologue.size(), 1u);
}

TEST(GraphFrames, HistoryOfAFrameThatDidNotWriteIsCleared) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    runTaaFrame(pool);
    {   // A frame that only reads the history (the persistent resource is not written).
        RenderGraph graph(pool, {64, 64});
        bool valid = false;
        TextureHandle h;
        graph.addPass("peek", [&](PassBuilder& b) { h = b.read(b.history("taa_out"), Access::SampledRead); b.sideEffect(); },
                      [&](PassContext& ctx) { valid = ctx.historyValid(h); });
        graph.execute(fakeCmd());
        EXPECT_TRUE(valid);
    }
    const TaaFrame after = runTaaFrame(pool);
    EXPECT_FALSE(after.historyValid) << "last frame did not write taa_out";
}

TEST(GraphFrames, ImportedSwapchainGetsItsFinalTransition) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {64, 64});
    PhysicalTexture swapchainImage;
    swapchainImage.image = fakeHandle<VkImage>(0xABC);
    swapchainImage.format = VK_FORMAT_B8G8R8A8_SRGB;
    ResourceState acquired;
    acquired.writeStages = kColorOut;   // acquire semaphore waited at COLOR_ATTACHMENT_OUTPUT
    const TextureHandle swapchain = graph.importTexture("swapchain", swapchainImage, acquired, FinalUse{Access::Present});
    graph.addPass("ui", [&](PassBuilder& b) { b.write(swapchain, Access::ColorReadWrite); }, {});
    graph.compile();
    const auto before = graph.barriersBefore("ui");
    ASSERT_EQ(before.size(), 1u);
    EXPECT_EQ(before[0].srcStages, kColorOut);
    EXPECT_EQ(before[0].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(before[0].newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    const auto final = graph.finalBarriers();
    ASSERT_EQ(final.size(), 1u);
    // A final layout transition also waits on the frame's shaders and their storage writes (the ui pass is a draw:
    // its vertex and fragment shaders), as one between passes does: graph_plan.cpp, for the validation layer.
    EXPECT_EQ(final[0].srcStages, kColorOut | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | kFragment);
    EXPECT_EQ(final[0].srcAccess, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(final[0].dstStages, VK_PIPELINE_STAGE_2_NONE);
    EXPECT_EQ(final[0].dstAccess, VK_ACCESS_2_NONE);
    EXPECT_EQ(final[0].oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(final[0].newLayout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    EXPECT_EQ(graph.finalState(swapchain).layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);

    graph.execute(fakeCmd());
    ASSERT_FALSE(recordedDependencies().empty());
    const auto& last = recordedDependencies().back();
    ASSERT_EQ(last.images.size(), 1u);
    EXPECT_EQ(last.images[0].image, swapchainImage.image);
    EXPECT_EQ(last.images[0].newLayout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    EXPECT_EQ(last.images[0].subresourceRange.aspectMask, VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT});
    EXPECT_EQ(last.images[0].subresourceRange.levelCount, VK_REMAINING_MIP_LEVELS);
    EXPECT_EQ(last.images[0].srcQueueFamilyIndex, VK_QUEUE_FAMILY_IGNORED);
}

// The VXGI voxel grid's frame: written as storage, sampled, then left in GENERAL for the next frame while later
// passes (the OIT composite) write other images through the bindless storage array. The synchronization
// validation layer (1.3.239) charges such a dispatch with a storage write of every image in the array, so the
// final SHADER_READ_ONLY -> GENERAL transition must include the later compute writes in its source scope (without
// it: SYNC-HAZARD-WRITE-AFTER-WRITE on the grid, tests/gpu/vxgi/vxgi_oit_sync_test.cpp). A final barrier without a
// layout change keeps its plain scope.
TEST(GraphFrames, FinalLayoutTransitionWaitsOnLaterShaderWrites) {
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {64, 64});
    const TextureHandle grid = graph.importTexture("grid", PhysicalTexture{.format = VK_FORMAT_R16G16B16A16_SFLOAT},
                                                   stateAfterAccess(Access::StorageRead, ResourceKind::Image, kCompute),
                                                   FinalUse{Access::StorageRead, kCompute});
    const TextureHandle volume =
        graph.importTexture("volume", PhysicalTexture{.format = VK_FORMAT_R16G16B16A16_SFLOAT},
                            stateAfterAccess(Access::SampledRead, ResourceKind::Image, kCompute),
                            FinalUse{Access::SampledRead, kCompute});
    TextureHandle written;
    graph.addPass("merge", [&](PassBuilder& b) {
        written = b.write(grid, Access::StorageWrite, kCompute);
        b.sideEffect();
    }, {});
    graph.addPass("trace", [&](PassBuilder& b) {
        b.read(written, Access::SampledRead, kCompute);
        b.read(volume, Access::SampledRead, kCompute);
        b.sideEffect();
    }, {});
    graph.addPass("composite", [&](PassBuilder& b) {
        b.write(b.create("hdr", colorDesc(VK_FORMAT_R16G16B16A16_SFLOAT)), Access::StorageWrite, kCompute);
        b.sideEffect();
    }, {});
    graph.compile();
    const auto final = graph.finalBarriers();
    ASSERT_EQ(final.size(), 1u) << "the volume stays where it was sampled";
    EXPECT_EQ(graph.resourceName(final[0].resource), "grid");
    EXPECT_EQ(final[0].oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(final[0].newLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(final[0].srcStages, kCompute);
    EXPECT_EQ(final[0].srcAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(final[0].dstStages, kCompute);
    EXPECT_EQ(final[0].dstAccess, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

TEST(GraphFrames, ImportedBufferFinalUseAndStateForNextFrame) {
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {64, 64});
    PhysicalBuffer draws;
    draws.buffer = fakeHandle<VkBuffer>(0xD0);
    draws.size = 4096;
    const BufferHandle in = graph.importBuffer("draws", draws, stateAfterAccess(Access::IndirectRead, ResourceKind::Buffer),
                                               FinalUse{Access::IndirectRead});
    BufferHandle out;
    graph.addPass("cull", [&](PassBuilder& b) { out = b.write(in, Access::StorageWrite, kCompute); }, {});
    graph.compile();
    const auto before = graph.barriersBefore("cull");
    ASSERT_EQ(before.size(), 1u);   // WAR against last frame's indirect reads: execution only
    EXPECT_EQ(before[0].srcStages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
    EXPECT_EQ(before[0].srcAccess, VK_ACCESS_2_NONE);
    EXPECT_EQ(before[0].dstAccess, VK_ACCESS_2_NONE);
    const auto final = graph.finalBarriers();
    ASSERT_EQ(final.size(), 1u);
    EXPECT_EQ(final[0].kind, ResourceKind::Buffer);
    EXPECT_EQ(final[0].srcStages, kCompute);
    EXPECT_EQ(final[0].srcAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(final[0].dstStages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
    EXPECT_EQ(final[0].dstAccess, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    EXPECT_EQ(graph.finalState(out).unflushedWrites, VK_ACCESS_2_NONE);
    EXPECT_EQ(graph.finalState(out).readStages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
}

TEST(GraphFrames, UnusedImportStillReachesItsFinalState) {
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {64, 64});
    const TextureHandle t = graph.importTexture("ui_atlas", PhysicalTexture{.format = VK_FORMAT_R8_UNORM},
                                                stateAfterAccess(Access::TransferDst, ResourceKind::Image),
                                                FinalUse{Access::SampledRead, kFragment});
    graph.compile();
    ASSERT_EQ(graph.finalBarriers().size(), 1u);
    EXPECT_EQ(graph.finalBarriers()[0].oldLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    EXPECT_EQ(graph.finalBarriers()[0].newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(graph.finalBarriers()[0].srcAccess, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    EXPECT_EQ(graph.finalState(t).layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

TEST(GraphFrames, ExecuteRecordsLabelsTimestampsBarriersAndCallbacksInOrder) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {16, 16});
    TextureHandle t;
    BufferHandle buf;
    graph.addPass("produce", [&](PassBuilder& b) {
        t = b.write(b.create("t", colorDesc()), Access::ColorWrite);
        buf = b.write(b.create("buf", BufferDesc{64}), Access::TransferDst);
    }, [&](PassContext& ctx) {
        eventLog().push_back("exec " + std::string(ctx.passName()));
        EXPECT_NE(ctx.image(t), VK_NULL_HANDLE);
        EXPECT_NE(ctx.view(t), VK_NULL_HANDLE);
        EXPECT_NE(ctx.vkBuffer(buf), VK_NULL_HANDLE);
        EXPECT_EQ(ctx.commandBuffer(), fakeCmd());
    });
    graph.addPass("unused", [&](PassBuilder& b) { b.read(t, Access::TransferSrc); },
                  [&](PassContext&) { eventLog().push_back("exec unused"); });
    graph.addPass("consume", [&](PassBuilder& b) {
        b.read(t, Access::SampledRead, kCompute);
        b.read(buf, Access::StorageRead, kCompute);
        b.sideEffect();
    }, [&](PassContext& ctx) {
        eventLog().push_back("exec " + std::string(ctx.passName()));
        EXPECT_THROW(ctx.image(TextureHandle{}), GraphError);
    });
    graph.execute(fakeCmd());
    const std::vector<std::string> expected{
        "beginFrame 2",  // produce: the two new heaps' unknown history goes out as global memory barriers
        "label produce", "timestampBegin 0 produce", "barrier m2 i1", "exec produce", "timestampEnd 0", "endLabel",
        "label consume", "timestampBegin 1 consume", "barrier m1 i1", "exec consume", "timestampEnd 1", "endLabel",
    };
    EXPECT_EQ(eventLog(), expected);
    // The consume barrier: the buffer as a global memory barrier, the image with its layout transition.
    const auto& dep = recordedDependencies()[1];
    EXPECT_EQ(dep.memory[0].srcStageMask, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    EXPECT_EQ(dep.memory[0].srcAccessMask, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    EXPECT_EQ(dep.memory[0].dstStageMask, kCompute);
    EXPECT_EQ(dep.memory[0].dstAccessMask, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    EXPECT_EQ(dep.images[0].oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(dep.images[0].newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_THROW(graph.execute(fakeCmd()), GraphError) << "a graph executes once";
}

TEST(GraphFrames, LabelsAreSkippedWithoutDebugUtils) {
    FakeVulkanCommands fakes;
    vkCmdBeginDebugUtilsLabelEXT = nullptr;
    vkCmdEndDebugUtilsLabelEXT = nullptr;
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {16, 16});
    graph.addPass("p", [](PassBuilder& b) { b.sideEffect(); }, {});
    graph.execute(fakeCmd());
    EXPECT_EQ(eventLog(), (std::vector<std::string>{"beginFrame 1", "timestampBegin 0 p", "timestampEnd 0"}));
}

TEST(GraphFrames, ExecuteWithoutLoadedBarrierFunctionFails) {
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {16, 16});
    graph.addPass("p", [](PassBuilder& b) { b.sideEffect(); }, {});
    EXPECT_THROW(graph.execute(fakeCmd()), GraphError);
}

TEST(GraphFrames, PoolReusesTransientsAndReleasesThemWhenUnused) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    const auto frame = [&](bool withBlur) {
        RenderGraph graph(pool, {32, 32});
        TextureHandle t;
        graph.addPass("draw", [&](PassBuilder& b) { t = b.write(b.create("t", colorDesc()), Access::ColorWrite); }, {});
        graph.addPass("show", [&](PassBuilder& b) { b.read(t, Access::SampledRead); b.sideEffect(); }, {});
        if (withBlur) {
            graph.addPass("blur", [&](PassBuilder& b) {
                b.read(t, Access::SampledRead, kCompute);
                b.write(b.create("blurred", colorDesc(VK_FORMAT_R16G16B16A16_SFLOAT)), Access::StorageWrite, kCompute);
                b.sideEffect();
            }, {});
        }
        graph.execute(fakeCmd());
    };
    frame(true);
    EXPECT_EQ(backend.createdTextures.size(), 2u);
    EXPECT_EQ(backend.allocatedHeaps.size(), 1u);
    for (int i = 0; i < 3; ++i) frame(true);
    EXPECT_EQ(backend.createdTextures.size(), 2u) << "same plan, same objects";
    EXPECT_EQ(backend.allocatedHeaps.size(), 1u);
    for (int i = 0; i < 8; ++i) frame(false);
    EXPECT_EQ(backend.destroyedImages.size(), 1u) << "'blurred' unused for several frames is released";
    EXPECT_EQ(pool.stats().transientTextures, 1u);
    pool.releaseAll();
    EXPECT_EQ(backend.destroyedImages.size(), 2u);
    EXPECT_EQ(backend.releasedHeaps.size(), 1u);
}

TEST(GraphFrames, HeapGrowsWhenTheFrameNeedsMoreMemory) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    const auto frame = [&](uint32_t size) {
        RenderGraph graph(pool, {size, size});
        graph.addPass("draw", [&](PassBuilder& b) { b.write(b.create("t", colorDesc()), Access::ColorWrite); b.sideEffect(); }, {});
        graph.execute(fakeCmd());
    };
    frame(16);
    frame(8);    // smaller: the heap is kept
    ASSERT_EQ(backend.allocatedHeaps.size(), 1u);
    EXPECT_EQ(backend.allocatedHeaps[0].size, 16u * 16u * 4u);
    frame(32);   // bigger: a new heap; the old one and what was placed in it are released
    ASSERT_EQ(backend.allocatedHeaps.size(), 2u);
    EXPECT_EQ(backend.allocatedHeaps[1].size, 32u * 32u * 4u);
    EXPECT_EQ(backend.releasedHeaps.size(), 1u);
    EXPECT_EQ(backend.destroyedImages.size(), 2u) << "the 16x16 and 8x8 images placed in the old heap";
    EXPECT_EQ(pool.stats().heaps, 1u);
}

TEST(GraphFrames, BufferHistoryIsFilledWithZerosOnTheFirstFrame) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    for (int frame = 0; frame < 2; ++frame) {
        RenderGraph graph(pool, {8, 8});
        graph.addPass("exposure", [&](PassBuilder& b) {
            b.read(b.historyBuffer("luminance"), Access::StorageRead, kCompute);
            b.write(b.create("luminance", BufferDesc{16, true}), Access::StorageWrite, kCompute);
        }, {});
        graph.execute(fakeCmd());
        const auto fills = std::count(eventLog().begin(), eventLog().end(), "fillBuffer");
        EXPECT_EQ(fills, frame == 0 ? 1 : 0);
        eventLog().clear();
    }
    EXPECT_EQ(backend.createdBuffers.size(), 2u);
    EXPECT_NE(backend.createdBuffers[0].buffer.usage & VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0u);
}

}  // namespace
}  // namespace idk::graph
