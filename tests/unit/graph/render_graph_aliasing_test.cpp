// render_graph_aliasing_test.cpp: transient lifetimes and memory aliasing at graph level: resources with
// disjoint lifetimes share bytes, overlapping ones never do (brute-force oracle over random graphs), and
// the first use of aliased memory starts from UNDEFINED and waits on the previous occupant, in the same
// frame and across frames.
#include "fake_backend.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>

namespace idk::graph {
namespace {

using testing::absoluteDesc;
using testing::fakeCmd;
using testing::FakeBackend;
using testing::FakeVulkanCommands;
using testing::recordedDependencies;

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kFragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

const PlannedBarrier* findBarrier(std::span<const PlannedBarrier> barriers, uint32_t resource) {
    for (const PlannedBarrier& b : barriers) {
        if (b.resource == resource) return &b;
    }
    return nullptr;
}

// a -> t1 -> b -> t2 -> c -> t3 -> d: t1 [0,1], t2 [1,2], t3 [2,3]; t3 can reuse t1's bytes.
struct Chain {
    TextureHandle t1, t2, t3;
};
Chain buildChain(RenderGraph& graph) {
    Chain c;
    graph.addPass("a", [&](PassBuilder& b) { c.t1 = b.write(b.create("t1", absoluteDesc(32, 32)), Access::StorageWrite, kCompute); }, {});
    graph.addPass("b", [&](PassBuilder& b) {
        b.read(c.t1, Access::SampledRead, kFragment);
        c.t2 = b.write(b.create("t2", absoluteDesc(32, 32)), Access::ColorWrite);
    }, {});
    graph.addPass("c", [&](PassBuilder& b) {
        b.read(c.t2, Access::SampledRead, kCompute);
        c.t3 = b.write(b.create("t3", absoluteDesc(32, 32)), Access::StorageWrite, kCompute);
    }, {});
    graph.addPass("d", [&](PassBuilder& b) { b.read(c.t3, Access::StorageRead, kCompute); b.sideEffect(); }, {});
    return c;
}

TEST(GraphAliasing, DisjointLifetimesShareBytesAndTheSecondOccupantWaitsOnTheFirst) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {64, 64});
    const Chain c = buildChain(graph);
    graph.compile();
    const AliasSlot* s1 = graph.aliasSlot(c.t1);
    const AliasSlot* s2 = graph.aliasSlot(c.t2);
    const AliasSlot* s3 = graph.aliasSlot(c.t3);
    ASSERT_TRUE(s1 && s2 && s3);
    EXPECT_EQ(s1->firstPass, 0u);
    EXPECT_EQ(s1->lastPass, 1u);
    EXPECT_EQ(s3->firstPass, 2u);
    EXPECT_EQ(s3->lastPass, 3u);
    EXPECT_EQ(s1->offset, s3->offset) << "t3 reuses t1's bytes";
    EXPECT_FALSE(bytesOverlap(*s1, *s2));
    EXPECT_FALSE(bytesOverlap(*s2, *s3));
    EXPECT_EQ(graph.aliasingPlan().totalBytes(), 2 * 32 * 32 * 4u);

    // t1's first use: a new heap, whose memory may have held freed resources: it waits on every earlier command
    // (graph_plan.cpp, heapTail: the validation layer does not see the host's timeline waits).
    const PlannedBarrier* first = findBarrier(graph.barriersBefore("a"), c.t1.resource);
    ASSERT_NE(first, nullptr);
    EXPECT_TRUE(first->aliasing);
    EXPECT_EQ(first->srcStages, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    EXPECT_EQ(first->srcAccess, VK_ACCESS_2_MEMORY_WRITE_BIT);
    // t3's first use: UNDEFINED, waits on t1's last access (sampled in FRAGMENT, after the transition), on t2's
    // accesses so far (its transition to a COMPUTE read in this same pass), on the new heap's unknown history, and
    // on every shader stage that ran before with its storage writes (a draw counts its vertex and fragment shaders):
    // graph_plan.cpp says why (the synchronization validation layer cannot place optimal-tiling texels in memory,
    // nor tell which element of a bindless array a shader uses).
    const PlannedBarrier* reuse = findBarrier(graph.barriersBefore("c"), c.t3.resource);
    ASSERT_NE(reuse, nullptr);
    EXPECT_TRUE(reuse->aliasing);
    EXPECT_EQ(reuse->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(reuse->newLayout, VK_IMAGE_LAYOUT_GENERAL);
    constexpr VkPipelineStageFlags2 kEarlier =
        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | kFragment | kCompute;
    EXPECT_EQ(reuse->srcStages, kEarlier);
    EXPECT_EQ(reuse->srcAccess, VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(reuse->dstStages, kCompute);
    EXPECT_EQ(reuse->dstAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

    graph.execute(fakeCmd());
    // Pass c: t2's transition plus t3's aliasing barrier, which also goes out as a global memory barrier.
    const auto& dep = recordedDependencies()[2];
    EXPECT_EQ(dep.images.size(), 2u);
    ASSERT_EQ(dep.memory.size(), 1u);
    EXPECT_EQ(dep.memory[0].srcStageMask, kEarlier);
    EXPECT_EQ(dep.memory[0].dstStageMask, kCompute);
    // Both placed at the same offset of the same heap.
    ASSERT_EQ(backend.createdTextures.size(), 3u);
    EXPECT_EQ(backend.createdTextures[0].placement.heap, backend.createdTextures[2].placement.heap);
    EXPECT_EQ(backend.createdTextures[0].placement.offset, backend.createdTextures[2].placement.offset);
    EXPECT_TRUE(backend.createdTextures[0].placed);
}

TEST(GraphAliasing, NextFrameWaitsOnLastFramesOccupants) {
    FakeVulkanCommands fakes;
    FakeBackend backend;
    ResourcePool pool(backend);
    {
        RenderGraph graph(pool, {64, 64});
        buildChain(graph);
        graph.execute(fakeCmd());
    }
    RenderGraph graph(pool, {64, 64});
    const Chain c = buildChain(graph);
    graph.compile();
    // Same memory, used in submission order by last frame: the first use waits on all its last accesses.
    const PlannedBarrier* first = findBarrier(graph.barriersBefore("a"), c.t1.resource);
    ASSERT_NE(first, nullptr);
    EXPECT_TRUE(first->aliasing);
    EXPECT_EQ(first->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(first->srcStages & (kCompute | kFragment), kCompute | kFragment);
    graph.execute(fakeCmd());
    EXPECT_EQ(backend.createdTextures.size(), 3u) << "placed objects reused";
    EXPECT_EQ(backend.allocatedHeaps.size(), 1u);
}

TEST(GraphAliasing, ImagesBuffersAndHostVisibleBuffersUseSeparateHeaps) {
    FakeBackend backend;
    ResourcePool pool(backend);
    RenderGraph graph(pool, {64, 64});
    graph.addPass("p", [&](PassBuilder& b) {
        b.write(b.create("img", absoluteDesc(8, 8)), Access::StorageWrite);
        b.write(b.create("buf", BufferDesc{256}), Access::StorageWrite);
        b.sideEffect();
    }, {});
    BufferHandle readback;
    graph.addPass("q", [&](PassBuilder& b) { readback = b.write(b.create("readback", BufferDesc{64}), Access::TransferDst); }, {});
    graph.addPass("r", [&](PassBuilder& b) { b.read(readback, Access::HostRead); b.sideEffect(); }, {});
    graph.addPass("s", [&](PassBuilder& b) { b.write(b.create("late", BufferDesc{64}), Access::TransferDst); b.sideEffect(); }, {});
    graph.compile();
    EXPECT_EQ(graph.aliasingPlan().heaps.size(), 3u);
    // A host-read buffer lives to the end of the frame (the CPU reads it after the fence).
    EXPECT_EQ(graph.aliasSlot(readback)->lastPass, 3u);
}

// ---- Random graphs against a brute-force oracle ----

struct DeclaredUse {
    uint32_t resource;
    VkPipelineStageFlags2 stages;
};

TEST(GraphAliasing, RandomGraphsNeverOverlapLiveResources) {
    std::mt19937 rng(7);
    uint64_t sharedPairs = 0;
    for (int trial = 0; trial < 300; ++trial) {
        FakeBackend backend;
        ResourcePool pool(backend);
        RenderGraph graph(pool, {64, 64});
        std::vector<TextureHandle> textures;   // latest version of each created texture
        std::vector<BufferHandle> buffers;
        std::map<std::string, std::vector<DeclaredUse>> usesByPass;
        const uint32_t passCount = 2 + rng() % 14;
        for (uint32_t p = 0; p < passCount; ++p) {
            const std::string name = "p" + std::to_string(p);
            graph.addPass(name, [&](PassBuilder& b) {
                auto& uses = usesByPass[name];
                const auto stage = [&] { return rng() % 2 ? kCompute : kFragment; };
                std::vector<bool> taken(textures.size(), false), takenBuffer(buffers.size(), false);
                for (uint32_t k = rng() % 3; k > 0 && !textures.empty(); --k) {
                    const size_t i = rng() % textures.size();
                    if (taken[i]) continue;
                    taken[i] = true;
                    const VkPipelineStageFlags2 s = stage();
                    if (rng() % 4 == 0) {
                        textures[i] = b.write(textures[i], Access::StorageReadWrite, s);
                    } else {
                        b.read(textures[i], Access::SampledRead, s);
                    }
                    uses.push_back({textures[i].resource, s});
                }
                if (!buffers.empty() && rng() % 2) {
                    const size_t i = rng() % buffers.size();
                    const VkPipelineStageFlags2 s = stage();
                    b.read(buffers[i], Access::StorageRead, s);
                    uses.push_back({buffers[i].resource, s});
                }
                for (uint32_t k = rng() % 3; k > 0; --k) {
                    const VkPipelineStageFlags2 s = stage();
                    if (rng() % 3 == 0) {
                        buffers.push_back(b.write(b.create(name + "_b" + std::to_string(k), BufferDesc{16 + rng() % 5000}),
                                                  Access::StorageWrite, s));
                        uses.push_back({buffers.back().resource, s});
                    } else {
                        textures.push_back(b.write(b.create(name + "_t" + std::to_string(k),
                                                            absoluteDesc(1 + rng() % 64, 1 + rng() % 64)),
                                                   Access::StorageWrite, s));
                        uses.push_back({textures.back().resource, s});
                    }
                }
                if (rng() % 4 == 0) b.sideEffect();
            }, {});
        }
        graph.compile();

        // Oracle lifetimes from the execution order and the declared uses.
        const std::vector<std::string> order = graph.executionOrder();
        std::map<uint32_t, std::pair<uint32_t, uint32_t>> lifetime;
        std::map<uint32_t, VkPipelineStageFlags2> lastStages;
        for (uint32_t pos = 0; pos < order.size(); ++pos) {
            for (const DeclaredUse& u : usesByPass[order[pos]]) {
                auto [it, inserted] = lifetime.emplace(u.resource, std::make_pair(pos, pos));
                if (it->second.second != pos) lastStages[u.resource] = 0;
                it->second.second = pos;
                lastStages[u.resource] |= u.stages;
            }
        }
        const AliasingPlan& plan = graph.aliasingPlan();
        ASSERT_EQ(plan.slots.size(), lifetime.size()) << "every used transient gets memory, nothing else";
        for (const AliasSlot& s : plan.slots) {
            ASSERT_TRUE(lifetime.count(s.resource));
            EXPECT_EQ(s.firstPass, lifetime[s.resource].first);
            EXPECT_EQ(s.lastPass, lifetime[s.resource].second);
        }
        for (const AliasSlot& a : plan.slots) {
            for (const AliasSlot& b : plan.slots) {
                if (a.resource == b.resource || !bytesOverlap(a, b)) continue;
                ASSERT_FALSE(a.firstPass <= b.lastPass && b.firstPass <= a.lastPass)
                    << "'" << graph.resourceName(a.resource) << "' and '" << graph.resourceName(b.resource)
                    << "' share bytes while both alive\n" << graph.toText();
                if (a.lastPass < b.firstPass) {
                    ++sharedPairs;
                    const PlannedBarrier* barrier = findBarrier(graph.barriersBefore(order[b.firstPass]), b.resource);
                    ASSERT_NE(barrier, nullptr) << "aliased first use without a barrier";
                    EXPECT_TRUE(barrier->aliasing);
                    EXPECT_EQ(barrier->srcStages & lastStages[a.resource], lastStages[a.resource])
                        << "'" << graph.resourceName(b.resource) << "' does not wait on '"
                        << graph.resourceName(a.resource) << "'";
                    if (barrier->kind == ResourceKind::Image) {
                        EXPECT_EQ(barrier->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
                    }
                }
            }
        }
        if (HasFailure()) return;
    }
    EXPECT_GT(sharedPairs, 50u) << "random graphs should alias often";
}

}  // namespace
}  // namespace idk::graph
