// range_allocator_test.cpp: checks idk::core::RangeAllocator on scripted sequences (exact offsets, alignment,
// coalescing, fragmentation, exhaustion, errors) and on 10k seeded random operations against a byte-occupancy
// oracle that predicts the exact best-fit offset of every allocation.
#include "core/range_allocator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using idk::core::RangeAllocator;

namespace {

void expectValid(const RangeAllocator& a) {
    std::string why;
    EXPECT_TRUE(a.checkInvariants(&why)) << why;
}

}  // namespace

TEST(RangeAllocator, FreshAllocatorIsOneFreeRange) {
    RangeAllocator a(1000);
    EXPECT_EQ(a.capacity(), 1000u);
    EXPECT_EQ(a.used(), 0u);
    EXPECT_EQ(a.freeBytes(), 1000u);
    EXPECT_EQ(a.largestFreeRange(), 1000u);
    EXPECT_EQ(a.allocationCount(), 0u);
    EXPECT_EQ(a.freeRangeCount(), 1u);
    expectValid(a);
}

TEST(RangeAllocator, ScriptedBestFitOffsets) {
    RangeAllocator a(1000);
    EXPECT_EQ(a.allocate(100), 0u);
    EXPECT_EQ(a.allocate(200), 100u);
    EXPECT_EQ(a.allocate(300), 300u);
    EXPECT_EQ(a.used(), 600u);
    a.free(100);  // holes: [100,300) and [600,1000)
    EXPECT_EQ(a.largestFreeRange(), 400u);
    EXPECT_EQ(a.allocate(150), 100u);  // the 200-byte hole is the best fit
    EXPECT_EQ(a.allocate(60), 600u);   // the 50 bytes left at 250 are too small
    EXPECT_EQ(a.allocate(50), 250u);   // exact fit
    EXPECT_EQ(a.freeRangeCount(), 1u);
    EXPECT_EQ(a.used(), 660u);
    EXPECT_EQ(a.allocationSize(600), 60u);
    EXPECT_EQ(a.allocationSize(601), std::nullopt);
    expectValid(a);
}

TEST(RangeAllocator, TiesGoToTheLowestOffset) {
    RangeAllocator a(400);
    for (int i = 0; i < 4; ++i) {
        ASSERT_EQ(a.allocate(100), uint64_t(i) * 100);
    }
    a.free(300);
    a.free(100);  // two equal 100-byte holes
    EXPECT_EQ(a.allocate(10), 100u);
    EXPECT_EQ(a.allocate(90), 110u);
    EXPECT_EQ(a.allocate(100), 300u);
    expectValid(a);
}

TEST(RangeAllocator, AlignmentKeepsPaddingFree) {
    RangeAllocator a(1024);
    EXPECT_EQ(a.allocate(1, 1), 0u);
    EXPECT_EQ(a.allocate(16, 256), 256u);  // [1,256) stays free
    EXPECT_EQ(a.freeRangeCount(), 2u);
    EXPECT_EQ(a.allocate(100, 1), 1u);     // the 255-byte padding hole is the best fit
    EXPECT_EQ(a.allocate(64, 64), 128u);   // [101,128) is padding, [192,256) stays free
    EXPECT_EQ(a.allocate(64, 64), 192u);
    EXPECT_EQ(a.allocate(8, 512), 512u);
    expectValid(a);
    for (uint64_t offset : {0u, 256u, 1u, 128u, 192u, 512u}) {
        a.free(offset);
        expectValid(a);
    }
    EXPECT_EQ(a.largestFreeRange(), 1024u);
    EXPECT_EQ(a.freeRangeCount(), 1u);
}

TEST(RangeAllocator, AlignmentSkipsTooSmallAlignedCandidates) {
    RangeAllocator a(4096);
    ASSERT_EQ(a.allocate(1), 0u);
    ASSERT_EQ(a.allocate(1024), 1u);  // free: [1025,4096)
    ASSERT_EQ(a.allocate(8), 1025u);  // free: [1033,4096)
    a.free(1);                        // free: [1,1025) (1024 bytes), [1033,4096) (3063 bytes)
    // 1024 bytes aligned to 1024 do not fit in [1,1025) even though the range is 1024 bytes long.
    EXPECT_EQ(a.allocate(1024, 1024), 2048u);
    expectValid(a);
}

TEST(RangeAllocator, CoalescesBackToOneRange) {
    RangeAllocator a(256);
    for (int i = 0; i < 4; ++i) {
        ASSERT_EQ(a.allocate(64), uint64_t(i) * 64);
    }
    EXPECT_EQ(a.largestFreeRange(), 0u);
    a.free(64);
    a.free(192);
    EXPECT_EQ(a.freeRangeCount(), 2u);
    a.free(0);  // merges with the right neighbour
    EXPECT_EQ(a.freeRangeCount(), 2u);
    EXPECT_EQ(a.largestFreeRange(), 128u);
    a.free(128);  // merges on both sides
    EXPECT_EQ(a.freeRangeCount(), 1u);
    EXPECT_EQ(a.largestFreeRange(), 256u);
    EXPECT_EQ(a.used(), 0u);
    EXPECT_EQ(a.allocationCount(), 0u);
    expectValid(a);
}

TEST(RangeAllocator, FragmentationThenFill) {
    RangeAllocator a(1024);
    for (int i = 0; i < 16; ++i) {
        ASSERT_EQ(a.allocate(64), uint64_t(i) * 64);
    }
    for (int i = 0; i < 16; i += 2) {
        a.free(uint64_t(i) * 64);
    }
    EXPECT_EQ(a.freeBytes(), 512u);
    EXPECT_EQ(a.largestFreeRange(), 64u);
    EXPECT_EQ(a.allocate(65), std::nullopt);  // 512 bytes free, none contiguous enough
    for (int i = 0; i < 16; i += 2) {
        EXPECT_EQ(a.allocate(64), uint64_t(i) * 64);
    }
    EXPECT_EQ(a.used(), 1024u);
    EXPECT_EQ(a.freeRangeCount(), 0u);
    EXPECT_EQ(a.allocate(1), std::nullopt);
    expectValid(a);
}

TEST(RangeAllocator, OutOfSpaceReturnsNullopt) {
    RangeAllocator a(100);
    EXPECT_EQ(a.allocate(101), std::nullopt);
    EXPECT_EQ(a.allocate(100), 0u);
    EXPECT_EQ(a.allocate(1), std::nullopt);
    a.free(0);
    EXPECT_EQ(a.allocate(1, 128), 0u);
    EXPECT_EQ(a.allocate(1, 128), std::nullopt);  // no 128-aligned offset left below 100
    EXPECT_EQ(a.used(), 1u);
    expectValid(a);
}

TEST(RangeAllocator, HugeCapacityDoesNotOverflow) {
    constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();
    RangeAllocator a(kMax);
    EXPECT_EQ(a.allocate(1, uint64_t(1) << 63), 0u);
    EXPECT_EQ(a.allocate(1, uint64_t(1) << 63), uint64_t(1) << 63);
    EXPECT_EQ(a.allocate(1, uint64_t(1) << 63), std::nullopt);
    constexpr uint64_t kHalf = uint64_t(1) << 63;
    EXPECT_EQ(a.allocate(kMax - 2), std::nullopt);  // free space is split by the block at 2^63
    EXPECT_EQ(a.allocate(kHalf - 2), kHalf + 1);    // best fit: [2^63+1, 2^64-1) is the smaller range
    EXPECT_EQ(a.allocate(kHalf - 1), 1u);
    EXPECT_EQ(a.used(), kMax);
    EXPECT_EQ(a.freeRangeCount(), 0u);
    expectValid(a);
}

TEST(RangeAllocator, RejectsBadArguments) {
    EXPECT_THROW(RangeAllocator(0), std::invalid_argument);
    RangeAllocator a(1024);
    EXPECT_THROW((void)a.allocate(0), std::invalid_argument);
    EXPECT_THROW((void)a.allocate(8, 0), std::invalid_argument);
    EXPECT_THROW((void)a.allocate(8, 3), std::invalid_argument);
    EXPECT_THROW((void)a.allocate(8, 48), std::invalid_argument);
    EXPECT_THROW(a.free(0), std::logic_error);
    const auto offset = a.allocate(64, 64);
    ASSERT_EQ(offset, 0u);
    EXPECT_THROW(a.free(1), std::logic_error);  // inside a block, not its start
    a.free(0);
    EXPECT_THROW(a.free(0), std::logic_error);  // double free
    expectValid(a);
    EXPECT_EQ(a.used(), 0u);
}

// Oracle: one byte per byte of the range. For each allocation it predicts the exact best-fit offset: among the
// maximal free runs that can hold the aligned block, the shortest, lowest offset on ties.
namespace {

struct Oracle {
    explicit Oracle(uint64_t capacity) : used(capacity, 0) {}

    struct Run {
        uint64_t offset, size;
    };
    std::vector<Run> freeRuns() const {
        std::vector<Run> runs;
        uint64_t i = 0;
        while (i < used.size()) {
            if (used[i]) {
                ++i;
                continue;
            }
            uint64_t j = i;
            while (j < used.size() && !used[j]) {
                ++j;
            }
            runs.push_back({i, j - i});
            i = j;
        }
        return runs;
    }
    std::optional<uint64_t> predict(uint64_t size, uint64_t alignment) const {
        std::optional<Run> best;
        for (const Run& r : freeRuns()) {
            const uint64_t aligned = (r.offset + alignment - 1) / alignment * alignment;
            if (aligned + size <= r.offset + r.size && (!best || r.size < best->size)) {
                best = r;
            }
        }
        if (!best) {
            return std::nullopt;
        }
        return (best->offset + alignment - 1) / alignment * alignment;
    }
    uint64_t largestRun() const {
        uint64_t largest = 0;
        for (const Run& r : freeRuns()) {
            largest = std::max(largest, r.size);
        }
        return largest;
    }
    std::vector<uint8_t> used;
    uint64_t usedBytes = 0;
};

}  // namespace

TEST(RangeAllocator, RandomizedAgainstByteOracle) {
    constexpr uint64_t kCapacity = 8192;
    constexpr int kOps = 10000;
    std::mt19937_64 rng(0x1d4u);
    RangeAllocator a(kCapacity);
    Oracle oracle(kCapacity);
    struct Live {
        uint64_t offset, size;
    };
    std::vector<Live> live;
    int allocations = 0, failures = 0;

    for (int op = 0; op < kOps; ++op) {
        const bool doAllocate = live.empty() || rng() % 100 < 55;
        if (doAllocate) {
            // Mostly small blocks, sometimes large ones, alignments 1..512.
            const uint64_t size = rng() % 8 == 0 ? 1 + rng() % 2048 : 1 + rng() % 200;
            const uint64_t alignment = uint64_t(1) << (rng() % 10);
            const auto expected = oracle.predict(size, alignment);
            const auto got = a.allocate(size, alignment);
            ASSERT_EQ(got, expected) << "op " << op << " size " << size << " alignment " << alignment;
            if (got) {
                ASSERT_EQ(*got % alignment, 0u);
                ASSERT_LE(*got + size, kCapacity);
                for (uint64_t b = *got; b < *got + size; ++b) {
                    ASSERT_EQ(oracle.used[b], 0) << "overlap at byte " << b << " (op " << op << ")";
                    oracle.used[b] = 1;
                }
                oracle.usedBytes += size;
                live.push_back({*got, size});
                ++allocations;
            } else {
                ++failures;
            }
        } else {
            const size_t index = rng() % live.size();
            const Live victim = live[index];
            live[index] = live.back();
            live.pop_back();
            ASSERT_EQ(a.allocationSize(victim.offset), victim.size);
            a.free(victim.offset);
            for (uint64_t b = victim.offset; b < victim.offset + victim.size; ++b) {
                oracle.used[b] = 0;
            }
            oracle.usedBytes -= victim.size;
        }
        ASSERT_EQ(a.used(), oracle.usedBytes) << "op " << op;
        ASSERT_EQ(a.allocationCount(), live.size()) << "op " << op;
        if (op % 64 == 0) {
            ASSERT_EQ(a.largestFreeRange(), oracle.largestRun()) << "op " << op;
            std::string why;
            ASSERT_TRUE(a.checkInvariants(&why)) << "op " << op << ": " << why;
        }
    }
    // The run must have exercised both outcomes.
    EXPECT_GT(allocations, 1000);
    EXPECT_GT(failures, 10);

    std::shuffle(live.begin(), live.end(), rng);
    for (const Live& l : live) {
        a.free(l.offset);
    }
    EXPECT_EQ(a.used(), 0u);
    EXPECT_EQ(a.allocationCount(), 0u);
    EXPECT_EQ(a.largestFreeRange(), kCapacity);
    EXPECT_EQ(a.freeRangeCount(), 1u);
    expectValid(a);
}
