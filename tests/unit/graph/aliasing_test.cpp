// aliasing_test.cpp: the greedy transient packer: disjoint lifetimes share bytes, overlapping ones never do
// (checked by a brute-force oracle over random request sets), alignment, heap keys.
#include "graph/aliasing.hpp"

#include <gtest/gtest.h>

#include <random>

namespace idk::graph {
namespace {

AliasRequest request(uint32_t id, VkDeviceSize size, uint32_t first, uint32_t last, VkDeviceSize alignment = 256,
                     uint32_t typeBits = 1, ResourceKind kind = ResourceKind::Image) {
    AliasRequest r;
    r.resource = id;
    r.requirements = MemoryRequirements{size, alignment, typeBits};
    r.key = HeapKey{kind, false, typeBits};
    r.firstPass = first;
    r.lastPass = last;
    return r;
}

// Brute-force checks of a plan against its requests.
void checkPlan(const std::vector<AliasRequest>& requests, const AliasingPlan& plan) {
    ASSERT_EQ(plan.slots.size(), requests.size());
    for (size_t i = 0; i < requests.size(); ++i) {
        const AliasSlot& s = plan.slots[i];
        const AliasRequest& r = requests[i];
        EXPECT_EQ(s.resource, r.resource);
        ASSERT_LT(s.heap, plan.heaps.size());
        EXPECT_EQ(plan.heaps[s.heap].key, r.key) << "resource placed in a heap of another kind/memory type";
        EXPECT_EQ(s.offset % r.requirements.alignment, 0u) << "misaligned offset";
        EXPECT_GE(s.size, r.requirements.size);
        EXPECT_LE(s.offset + s.size, plan.heaps[s.heap].size) << "slot outside its heap";
        EXPECT_EQ(s.firstPass, r.firstPass);
        EXPECT_EQ(s.lastPass, r.lastPass);
        for (size_t j = 0; j < i; ++j) {
            const AliasSlot& o = plan.slots[j];
            const bool lifetimes = s.firstPass <= o.lastPass && o.firstPass <= s.lastPass;
            const bool bytes = s.heap == o.heap && s.offset < o.offset + o.size && o.offset < s.offset + s.size;
            EXPECT_FALSE(lifetimes && bytes) << "resources " << s.resource << " and " << o.resource
                                             << " live at the same time in the same bytes";
            EXPECT_EQ(lifetimesOverlap(s, o), lifetimes);
            EXPECT_EQ(bytesOverlap(s, o), bytes);
        }
    }
}

TEST(Aliasing, DisjointLifetimesShareMemory) {
    const std::vector<AliasRequest> requests{request(0, 1024, 0, 1), request(1, 1024, 2, 3)};
    const AliasingPlan plan = planAliasing(requests);
    checkPlan(requests, plan);
    ASSERT_EQ(plan.heaps.size(), 1u);
    EXPECT_EQ(plan.slots[0].offset, 0u);
    EXPECT_EQ(plan.slots[1].offset, 0u);
    EXPECT_EQ(plan.heaps[0].size, 1024u);
    EXPECT_EQ(plan.totalBytes(), 1024u);
    EXPECT_EQ(plan.unaliasedBytes(), 2048u);
}

TEST(Aliasing, OverlappingLifetimesNeverShare) {
    // Lifetimes touching in one pass (1..2 and 2..3) overlap: both are used by pass 2.
    const std::vector<AliasRequest> requests{request(0, 1024, 0, 2), request(1, 1024, 2, 3)};
    const AliasingPlan plan = planAliasing(requests);
    checkPlan(requests, plan);
    EXPECT_EQ(plan.heaps[0].size, 2048u);
}

TEST(Aliasing, ChainReusesTheFirstSlot) {
    // t0 [0,1], t1 [1,2], t2 [2,3]: t2 can take t0's bytes, t1 cannot.
    const std::vector<AliasRequest> requests{request(0, 512, 0, 1), request(1, 512, 1, 2), request(2, 512, 2, 3)};
    const AliasingPlan plan = planAliasing(requests);
    checkPlan(requests, plan);
    EXPECT_EQ(plan.slots[0].offset, 0u);
    EXPECT_EQ(plan.slots[1].offset, 512u);
    EXPECT_EQ(plan.slots[2].offset, 0u);
    EXPECT_EQ(plan.heaps[0].size, 1024u);
}

TEST(Aliasing, LargestFirstAndAlignment) {
    // The big one goes first at 0; the small one (overlapping) goes after it, rounded up to its alignment.
    const std::vector<AliasRequest> requests{request(0, 100, 0, 5, 64), request(1, 1000, 0, 5, 256)};
    const AliasingPlan plan = planAliasing(requests);
    checkPlan(requests, plan);
    EXPECT_EQ(plan.slots[1].offset, 0u);
    EXPECT_EQ(plan.slots[0].offset, 1024u);
    EXPECT_EQ(plan.heaps[0].alignment, 256u);
}

TEST(Aliasing, FillsAGapBetweenLiveResources) {
    // a [0,9] at 0 (1024), b [0,9] at 1024 (1024)... c [0,4] 512 and d [5,9] 512 can share the slot after.
    const std::vector<AliasRequest> requests{request(0, 1024, 0, 9), request(1, 512, 0, 4), request(2, 512, 5, 9)};
    const AliasingPlan plan = planAliasing(requests);
    checkPlan(requests, plan);
    EXPECT_EQ(plan.slots[1].offset, 1024u);
    EXPECT_EQ(plan.slots[2].offset, 1024u);
    EXPECT_EQ(plan.heaps[0].size, 1536u);
}

TEST(Aliasing, HeapKeysSeparateKindsAndMemoryTypes) {
    const std::vector<AliasRequest> requests{request(0, 256, 0, 0, 256, 1, ResourceKind::Image),
                                             request(1, 256, 1, 1, 256, 1, ResourceKind::Buffer),
                                             request(2, 256, 2, 2, 256, 2, ResourceKind::Image)};
    const AliasingPlan plan = planAliasing(requests);
    checkPlan(requests, plan);
    EXPECT_EQ(plan.heaps.size(), 3u);
}

TEST(Aliasing, EmptyRequestList) {
    const AliasingPlan plan = planAliasing({});
    EXPECT_TRUE(plan.heaps.empty());
    EXPECT_TRUE(plan.slots.empty());
    EXPECT_EQ(plan.slotOf(3), nullptr);
}

TEST(Aliasing, RandomRequestsAgainstBruteForceOracle) {
    std::mt19937 rng(42);
    VkDeviceSize totalSaved = 0;
    for (int trial = 0; trial < 500; ++trial) {
        std::vector<AliasRequest> requests;
        const uint32_t count = 1 + rng() % 24;
        const uint32_t passes = 1 + rng() % 12;
        for (uint32_t i = 0; i < count; ++i) {
            const uint32_t a = rng() % passes, b = rng() % passes;
            const VkDeviceSize alignment = VkDeviceSize{1} << (rng() % 12);
            requests.push_back(request(i, 1 + rng() % 100000, std::min(a, b), std::max(a, b), alignment,
                                       1u + rng() % 2, rng() % 4 == 0 ? ResourceKind::Buffer : ResourceKind::Image));
        }
        const AliasingPlan plan = planAliasing(requests);
        checkPlan(requests, plan);
        if (HasFailure()) return;
        EXPECT_LE(plan.totalBytes(), plan.unaliasedBytes() + plan.heaps.size() * 4096);
        totalSaved += plan.unaliasedBytes() > plan.totalBytes() ? plan.unaliasedBytes() - plan.totalBytes() : 0;
    }
    EXPECT_GT(totalSaved, 0u) << "aliasing never saved anything over 500 random frames";
}

}  // namespace
}  // namespace idk::graph
