// radix_sort_test.cpp: the stable LSD radix sort (8-bit digits) of 32-bit keys, alone and with 32-bit values,
// against std::sort / std::stable_sort, exactly: random, all equal, sorted, reverse sorted, few distinct keys,
// all-ones keys in a partial tile, size 1, sizes around the 2048-key tile, 1M, and shorter key widths.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "device_array.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

class RadixSortTest : public GpuTest {
protected:
    // Sorts keys (and values when given) on the GPU and returns them.
    std::pair<std::vector<uint32_t>, std::vector<uint32_t>> sort(const std::vector<uint32_t>& keys,
                                                                 const std::vector<uint32_t>* values,
                                                                 uint32_t keyBits = 32, uint32_t slotSubgroupSize = 0) {
        uint32_t count = uint32_t(keys.size());
        DeviceArray keyArray(ctx(), count, "sort keys");
        DeviceArray valueArray(ctx(), values ? count : 0, "sort values");
        DeviceArray scratch(ctx(), render::radixSortScratchElements(count, values != nullptr), "sort scratch");
        keyArray.upload(keys);
        if (values) valueArray.upload(*values);
        std::optional<render::GpuArray> v;
        if (values) v = valueArray.array();
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordRadixSort(cmd, {ctx(), shaders(), slotSubgroupSize}, keyArray.array(), v, count,
                                    scratch.array(), keyBits);
        });
        std::vector<uint32_t> sortedValues;
        if (values) sortedValues = valueArray.download<uint32_t>(count);
        return {keyArray.download<uint32_t>(count), sortedValues};
    }

    // Key+value sort with values = original index; compared with std::stable_sort, which also proves stability.
    void expectStablePairs(const std::vector<uint32_t>& keys, const char* what, uint32_t keyBits = 32) {
        std::vector<uint32_t> index(keys.size());
        std::iota(index.begin(), index.end(), 0u);
        auto [gotKeys, gotValues] = sort(keys, &index, keyBits);
        std::vector<uint32_t> order = index;
        std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
        ASSERT_EQ(gotKeys.size(), keys.size());
        for (size_t i = 0; i < keys.size(); ++i) {
            ASSERT_EQ(gotKeys[i], keys[order[i]]) << what << ": key at " << i << " of " << keys.size();
            ASSERT_EQ(gotValues[i], order[i]) << what << ": value (original index) at " << i << " of " << keys.size();
        }
    }
};

TEST_F(RadixSortTest, RandomKeysMatchStdSort1M) {
    std::vector<uint32_t> keys = randomUints(1u << 20, 0, 1);
    std::vector<uint32_t> expected = keys;
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(sort(keys, nullptr).first, expected);
}

TEST_F(RadixSortTest, KeyValuePairsAreStable1M) {
    // Few distinct keys spread over all four digits: long runs of equal keys whose values must keep their order.
    std::vector<uint32_t> keys = randomUints((1u << 20) + 3, 64, 2);
    for (uint32_t& k : keys) k = k * 0x04030201u;
    expectStablePairs(keys, "few distinct, 1M + 3");
}

TEST_F(RadixSortTest, Patterns) {
    const uint32_t n = 5000;  // two full 2048-key tiles and a partial one
    std::vector<uint32_t> equal(n, 0xABCD1234u);
    expectStablePairs(equal, "all equal");
    std::vector<uint32_t> sorted(n);
    std::iota(sorted.begin(), sorted.end(), 1000u);
    expectStablePairs(sorted, "already sorted");
    std::vector<uint32_t> reversed(sorted.rbegin(), sorted.rend());
    expectStablePairs(reversed, "reverse sorted");
    expectStablePairs(randomUints(n, 3, 3), "three distinct");
    // All-ones keys are also the padding of a partial tile: real ones must still all come out.
    std::vector<uint32_t> ones = randomUints(n, 0, 4);
    for (uint32_t i = 0; i < n; i += 3) ones[i] = 0xFFFFFFFFu;
    expectStablePairs(ones, "all-ones keys");
}

TEST_F(RadixSortTest, SizesAroundTheTile) {
    for (uint32_t count : {1u, 2u, 7u, 255u, 256u, 257u, 2047u, 2048u, 2049u, 4097u, 100003u}) {
        expectStablePairs(randomUints(count, 0, count), ("random size " + std::to_string(count)).c_str());
    }
    // Empty input records nothing.
    EXPECT_TRUE(sort({}, nullptr).first.empty());
}

TEST_F(RadixSortTest, NarrowKeysSortFewerPasses) {
    // Ray-sorting keys are often narrower than 32 bits: 8 bits (one pass + the identity pass), 16, 20 (3 -> 4).
    for (uint32_t bits : {8u, 16u, 20u}) {
        expectStablePairs(randomUints(30000, 1u << bits, bits), ("keyBits " + std::to_string(bits)).c_str(), bits);
    }
    // Rejected before anything is recorded.
    render::ComputeKernels kernels{ctx(), shaders()};
    for (uint32_t bits : {0u, 33u}) {
        EXPECT_THROW(render::recordRadixSort(VK_NULL_HANDLE, kernels, {}, std::nullopt, 10, {}, bits),
                     std::invalid_argument);
    }
}

}  // namespace
}  // namespace idk::test
