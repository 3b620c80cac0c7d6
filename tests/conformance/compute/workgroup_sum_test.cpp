// workgroup_sum_test.cpp: the workgroup-wide sum (subgroupAdd + one shared slot per subgroup) and the full
// reduction built from it, against C++ oracles: exact for uint (also modulo 2^32), 1e-6 relative for float
// against a double-precision sum.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numeric>

#include "device_array.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

using render::SumElement;

class WorkgroupSumTest : public GpuTest {
protected:
    render::ComputeKernels kernels() { return {ctx(), shaders()}; }

    // Per-tile sums on the GPU, `items` elements per invocation.
    template <class T>
    std::vector<T> workgroupSums(const std::vector<T>& input, SumElement element, uint32_t items) {
        uint32_t count = uint32_t(input.size());
        uint32_t groups = render::workgroupSumCount(count, items);
        DeviceArray in(ctx(), count, "sum input");
        DeviceArray out(ctx(), groups, "sum output");
        in.upload(input);
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordWorkgroupSum(cmd, kernels(), element, in.array(), count, out.array(), items);
        });
        return out.download<T>(groups);
    }

    template <class T>
    T reduce(const std::vector<T>& input, SumElement element) {
        uint32_t count = uint32_t(input.size());
        DeviceArray in(ctx(), count, "reduce input");
        DeviceArray result(ctx(), 1, "reduce result");
        DeviceArray scratch(ctx(), render::reduceScratchElements(count), "reduce scratch");
        in.upload(input);
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordReduce(cmd, kernels(), element, in.array(), count, result.array(), scratch.array());
        });
        return result.download<T>(1)[0];
    }
};

// Floats in [0.5, 1.5) on a 2^-24 grid, exact in float, from a fixed seed.
std::vector<float> randomFloats(size_t count, uint32_t seed) {
    std::vector<uint32_t> bits = randomUints(count, 1u << 24, seed);
    std::vector<float> v(count);
    for (size_t i = 0; i < count; ++i) v[i] = 0.5f + float(bits[i]) * 0x1p-24f;
    return v;
}

double sumDouble(const std::vector<float>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// Counts that are not multiples of the 256-wide workgroup, the edge cases around it, and the 1M case.
const uint32_t kCounts[] = {1, 255, 256, 257, 1000, 1024, 1025, (1u << 20) + 3};

TEST_F(WorkgroupSumTest, UintTileSumsAreExact) {
    for (uint32_t items : {1u, render::kSumItemsPerInvocation}) {  // 1 = the original one-value-per-invocation form
        for (uint32_t count : kCounts) {
            // Values below 4096: even 2^20 + 3 of them cannot wrap 2^32, so this checks plain integer sums.
            std::vector<uint32_t> input = randomUints(count, 4096, count);
            std::vector<uint32_t> got = workgroupSums(input, SumElement::Uint, items);
            uint32_t tile = 256 * items;
            ASSERT_EQ(got.size(), (count + tile - 1) / tile);
            for (uint32_t g = 0; g < got.size(); ++g) {
                auto begin = input.begin() + g * tile;
                auto end = input.begin() + std::min<size_t>(size_t(g + 1) * tile, count);
                ASSERT_EQ(got[g], std::accumulate(begin, end, 0u)) << "count " << count << " items " << items
                                                                   << " tile " << g;
            }
        }
    }
}

TEST_F(WorkgroupSumTest, UintReduceIsExact) {
    EXPECT_EQ(reduce(std::vector<uint32_t>{}, SumElement::Uint), 0u);
    for (uint32_t count : kCounts) {
        std::vector<uint32_t> input = randomUints(count, 4096, count + 1);
        uint64_t expected = std::accumulate(input.begin(), input.end(), uint64_t(0));
        ASSERT_LT(expected, uint64_t(1) << 32);  // wrap-free by construction
        EXPECT_EQ(reduce(input, SumElement::Uint), uint32_t(expected)) << "count " << count;
    }
}

TEST_F(WorkgroupSumTest, UintReduceWrapsModulo2To32) {
    // Full-range values wrap many times; addition modulo 2^32 is associative, so any summation order is exact.
    std::vector<uint32_t> input = randomUints((1u << 20) + 3, 0, 7);
    EXPECT_EQ(reduce(input, SumElement::Uint), std::accumulate(input.begin(), input.end(), 0u));
}

// Float tolerance: inputs are positive (no cancellation, condition number 1), so the relative error is bounded by
// the depth of the summation tree times 2^-24: the GPU adds 4 values per invocation, a subgroup tree, the slot
// combination, twice (two passes for 1M), a few dozen roundings at worst and ~1e-7 typical. A naive sequential
// float sum of 1M values of ~1 loses far more (checked below), so 1e-6 separates a tree reduction from a broken
// or serial one.
constexpr double kFloatRelativeTolerance = 1e-6;

TEST_F(WorkgroupSumTest, FloatTileSumsWithinTolerance) {
    for (uint32_t count : kCounts) {
        std::vector<float> input = randomFloats(count, count);
        std::vector<float> got = workgroupSums(input, SumElement::Float, render::kSumItemsPerInvocation);
        uint32_t tile = 256 * render::kSumItemsPerInvocation;
        for (uint32_t g = 0; g < got.size(); ++g) {
            double expected = std::accumulate(input.begin() + g * tile,
                                              input.begin() + std::min<size_t>(size_t(g + 1) * tile, count), 0.0);
            ASSERT_NEAR(got[g], expected, expected * kFloatRelativeTolerance) << "count " << count << " tile " << g;
        }
    }
}

TEST_F(WorkgroupSumTest, FloatReduceWithinToleranceOfDoubleSum) {
    EXPECT_EQ(reduce(std::vector<float>{}, SumElement::Float), 0.0f);
    for (uint32_t count : kCounts) {
        std::vector<float> input = randomFloats(count, count + 11);
        double expected = sumDouble(input);
        float got = reduce(input, SumElement::Float);
        EXPECT_NEAR(got, expected, expected * kFloatRelativeTolerance) << "count " << count;
        if (count == (1u << 20) + 3) {
            std::cout << "[ float sum ] n=" << count << " relative error GPU " << std::abs(got - expected) / expected;
            float serial = 0.0f;
            for (float x : input) serial += x;
            double serialError = std::abs(serial - expected) / expected;
            std::cout << ", naive serial float " << serialError << "\n";
            EXPECT_GT(serialError, kFloatRelativeTolerance) << "the tolerance would not catch a serial float sum";
        }
    }
}

}  // namespace
}  // namespace idk::test
