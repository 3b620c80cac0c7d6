// compute_checks.cpp: the compute primitives (engine/render/compute_primitives.hpp) against C++ oracles:
// workgroup sums and reductions (uint exact, also modulo 2^32; float within 1e-6 relative of a double sum), the
// reduce-then-scan exclusive scan (exact against std::exclusive_scan) and the stable LSD radix sort (exact against
// std::sort / std::stable_sort). Moved here from tests/conformance/compute/ so `idk conformance` runs them too.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "conformance/conformance.hpp"
#include "conformance/device_array.hpp"
#include "vk/shader_library.hpp"

namespace idk::conformance {
namespace {

using render::SumElement;

// Counts that are not multiples of the 256-wide workgroup, the edge cases around it, and the 1M case.
const uint32_t kCounts[] = {1, 255, 256, 257, 1000, 1024, 1025, (1u << 20) + 3};

// Float tolerance: inputs are positive (no cancellation, condition number 1), so the relative error is bounded by
// the depth of the summation tree times 2^-24: the GPU adds 4 values per invocation, a subgroup tree, the slot
// combination, twice (two passes for 1M), a few dozen roundings at worst and ~1e-7 typical. A naive sequential
// float sum of 1M values of ~1 loses far more (checked), so 1e-6 separates a tree reduction from a broken or
// serial one.
constexpr double kFloatRelativeTolerance = 1e-6;

// The error a float check reports is relative to the double-precision oracle.
void expectRelative(Verdict& v, double got, double expected, const std::string& what) {
    const double relative = std::abs(got - expected) / expected;
    v.recordError(relative);
    v.expect(relative <= kFloatRelativeTolerance,
             what + ": got " + std::to_string(got) + ", expected " + std::to_string(expected) + " (relative error " +
                 std::to_string(relative) + ")");
}

// Per-tile sums on the GPU, `items` elements per invocation.
template <class T>
std::vector<T> workgroupSums(CheckEnv& env, const std::vector<T>& input, SumElement element, uint32_t items) {
    const uint32_t count = uint32_t(input.size()), groups = render::workgroupSumCount(count, items);
    DeviceArray in(env.ctx, count, "sum input"), out(env.ctx, groups, "sum output");
    in.upload(input);
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        render::recordWorkgroupSum(cmd, {env.ctx, env.shaders}, element, in.array(), count, out.array(), items);
    });
    return out.download<T>(groups);
}

template <class T>
T reduce(CheckEnv& env, const std::vector<T>& input, SumElement element) {
    const uint32_t count = uint32_t(input.size());
    DeviceArray in(env.ctx, count, "reduce input"), result(env.ctx, 1, "reduce result");
    DeviceArray scratch(env.ctx, render::reduceScratchElements(count), "reduce scratch");
    in.upload(input);
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        render::recordReduce(cmd, {env.ctx, env.shaders}, element, in.array(), count, result.array(), scratch.array());
    });
    return result.download<T>(1)[0];
}

// Floats in [0.5, 1.5) on a 2^-24 grid, exact in float, from a fixed seed.
std::vector<float> randomFloats(size_t count, uint32_t seed) {
    std::vector<uint32_t> bits = randomUints(count, 1u << 24, seed);
    std::vector<float> v(count);
    for (size_t i = 0; i < count; ++i) v[i] = 0.5f + float(bits[i]) * 0x1p-24f;
    return v;
}

void uintTileSums(CheckEnv& env, Verdict& v) {
    for (uint32_t items : {1u, render::kSumItemsPerInvocation}) {  // 1 = the original one-value-per-invocation form
        for (uint32_t count : kCounts) {
            // Values below 4096: even 2^20 + 3 of them cannot wrap 2^32, so this checks plain integer sums.
            std::vector<uint32_t> input = randomUints(count, 4096, count);
            std::vector<uint32_t> got = workgroupSums(env, input, SumElement::Uint, items);
            const uint32_t tile = 256 * items;
            if (!v.expectEq(got.size(), size_t((count + tile - 1) / tile), "tile count")) return;
            for (uint32_t g = 0; g < got.size(); ++g) {
                auto begin = input.begin() + g * tile;
                auto end = input.begin() + std::min<size_t>(size_t(g + 1) * tile, count);
                v.expectEq(got[g], std::accumulate(begin, end, 0u),
                           "count " + std::to_string(count) + " items " + std::to_string(items) + " tile " + std::to_string(g));
            }
        }
    }
}

void uintReduce(CheckEnv& env, Verdict& v) {
    v.expectEq(reduce(env, std::vector<uint32_t>{}, SumElement::Uint), 0u, "empty input");
    for (uint32_t count : kCounts) {
        std::vector<uint32_t> input = randomUints(count, 4096, count + 1);
        const uint64_t expected = std::accumulate(input.begin(), input.end(), uint64_t(0));  // < 2^32 by construction
        v.expectEq(reduce(env, input, SumElement::Uint), uint32_t(expected), "count " + std::to_string(count));
    }
    // Full-range values wrap many times; addition modulo 2^32 is associative, so any summation order is exact.
    std::vector<uint32_t> input = randomUints((1u << 20) + 3, 0, 7);
    v.expectEq(reduce(env, input, SumElement::Uint), std::accumulate(input.begin(), input.end(), 0u), "wrapping sum");
}

void floatTileSums(CheckEnv& env, Verdict& v) {
    for (uint32_t count : kCounts) {
        std::vector<float> input = randomFloats(count, count);
        std::vector<float> got = workgroupSums(env, input, SumElement::Float, render::kSumItemsPerInvocation);
        const uint32_t tile = 256 * render::kSumItemsPerInvocation;
        for (uint32_t g = 0; g < got.size(); ++g) {
            const double expected = std::accumulate(input.begin() + g * tile,
                                                    input.begin() + std::min<size_t>(size_t(g + 1) * tile, count), 0.0);
            expectRelative(v, got[g], expected, "count " + std::to_string(count) + " tile " + std::to_string(g));
        }
    }
}

void floatReduce(CheckEnv& env, Verdict& v) {
    v.expectEq(reduce(env, std::vector<float>{}, SumElement::Float), 0.0f, "empty input");
    for (uint32_t count : kCounts) {
        std::vector<float> input = randomFloats(count, count + 11);
        const double expected = std::accumulate(input.begin(), input.end(), 0.0);
        const float got = reduce(env, input, SumElement::Float);
        expectRelative(v, got, expected, "count " + std::to_string(count));
        if (count == (1u << 20) + 3) {
            float serial = 0.0f;
            for (float x : input) serial += x;
            v.expect(std::abs(serial - expected) / expected > kFloatRelativeTolerance,
                     "the tolerance would not catch a serial float sum");
        }
    }
}

std::vector<uint32_t> scan(CheckEnv& env, const std::vector<uint32_t>& input, bool inPlace) {
    const uint32_t count = uint32_t(input.size());
    DeviceArray in(env.ctx, count, "scan input"), out(env.ctx, inPlace ? 0 : count, "scan output");
    DeviceArray scratch(env.ctx, render::exclusiveScanScratchElements(count), "scan scratch");
    in.upload(input);
    DeviceArray& result = inPlace ? in : out;
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        render::recordExclusiveScan(cmd, {env.ctx, env.shaders}, in.array(), result.array(), count, scratch.array());
    });
    return result.download<uint32_t>(count);
}

std::vector<uint32_t> expectedScan(const std::vector<uint32_t>& input) {
    std::vector<uint32_t> out(input.size());
    std::exclusive_scan(input.begin(), input.end(), out.begin(), 0u);
    return out;
}

// Fails naming the first index where the arrays differ.
void expectSame(Verdict& v, const std::vector<uint32_t>& got, const std::vector<uint32_t>& want, const std::string& what) {
    if (!v.expectEq(got.size(), want.size(), what + ": size")) return;
    auto [g, w] = std::mismatch(got.begin(), got.end(), want.begin());
    if (g != got.end())
        v.expect(false, what + ": at " + std::to_string(g - got.begin()) + " got " + std::to_string(*g) + ", expected " +
                            std::to_string(*w));
}

void exclusiveScan(CheckEnv& env, Verdict& v) {
    // 0, 1, one partial tile, exactly one tile (2048), just past it, several tiles, 1M, 1M + 3 (two levels).
    for (uint32_t count : {0u, 1u, 1000u, 2048u, 2049u, 100000u, 1u << 20, (1u << 20) + 3}) {
        std::vector<uint32_t> input = randomUints(count, 4096, count);  // wrap-free; wrapping is its own check
        expectSame(v, scan(env, input, false), expectedScan(input), "count " + std::to_string(count));
    }
}

void exclusiveScanInPlaceWrapping(CheckEnv& env, Verdict& v) {
    std::vector<uint32_t> input = randomUints((1u << 20) + 3, 0, 5);  // full range: the sums wrap many times
    expectSame(v, scan(env, input, true), expectedScan(input), "in place, wrapping");
}

void exclusiveScanThreeLevels(CheckEnv& env, Verdict& v) {
    // More than 2048 * 2048 elements: the block sums themselves need a second reduce-then-scan level.
    const uint32_t count = (1u << 22) + 2049;
    std::vector<uint32_t> input = randomUints(count, 16, 9);
    v.expect(render::exclusiveScanScratchElements(count) > render::kScanTile + 1, "input too small for three levels");
    expectSame(v, scan(env, input, false), expectedScan(input), "three levels");
}

// Sorts keys (and values when given) on the GPU and returns them.
std::pair<std::vector<uint32_t>, std::vector<uint32_t>> sort(CheckEnv& env, const std::vector<uint32_t>& keys,
                                                             const std::vector<uint32_t>* values, uint32_t keyBits = 32) {
    const uint32_t count = uint32_t(keys.size());
    DeviceArray keyArray(env.ctx, count, "sort keys"), valueArray(env.ctx, values ? count : 0, "sort values");
    DeviceArray scratch(env.ctx, render::radixSortScratchElements(count, values != nullptr), "sort scratch");
    keyArray.upload(keys);
    if (values) valueArray.upload(*values);
    std::optional<render::GpuArray> valueRange;
    if (values) valueRange = valueArray.array();
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        render::recordRadixSort(cmd, {env.ctx, env.shaders}, keyArray.array(), valueRange, count, scratch.array(), keyBits);
    });
    std::vector<uint32_t> sortedValues;
    if (values) sortedValues = valueArray.download<uint32_t>(count);
    return {keyArray.download<uint32_t>(count), sortedValues};
}

// Key+value sort with values = original index; compared with std::stable_sort, which also proves stability.
void expectStablePairs(CheckEnv& env, Verdict& v, const std::vector<uint32_t>& keys, const std::string& what,
                       uint32_t keyBits = 32) {
    std::vector<uint32_t> index(keys.size());
    std::iota(index.begin(), index.end(), 0u);
    auto [gotKeys, gotValues] = sort(env, keys, &index, keyBits);
    std::vector<uint32_t> order = index;
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
    std::vector<uint32_t> expectedKeys(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) expectedKeys[i] = keys[order[i]];
    expectSame(v, gotKeys, expectedKeys, what + ": keys");
    expectSame(v, gotValues, order, what + ": values (original indices)");
}

void radixKeys1M(CheckEnv& env, Verdict& v) {
    std::vector<uint32_t> keys = randomUints(1u << 20, 0, 1);
    std::vector<uint32_t> expected = keys;
    std::sort(expected.begin(), expected.end());
    expectSame(v, sort(env, keys, nullptr).first, expected, "1M random keys");
}

void radixPairsStable1M(CheckEnv& env, Verdict& v) {
    // Few distinct keys spread over all four digits: long runs of equal keys whose values must keep their order.
    std::vector<uint32_t> keys = randomUints((1u << 20) + 3, 64, 2);
    for (uint32_t& k : keys) k = k * 0x04030201u;
    expectStablePairs(env, v, keys, "few distinct, 1M + 3");
}

void radixPatterns(CheckEnv& env, Verdict& v) {
    const uint32_t n = 5000;  // two full 2048-key tiles and a partial one
    expectStablePairs(env, v, std::vector<uint32_t>(n, 0xABCD1234u), "all equal");
    std::vector<uint32_t> sorted(n);
    std::iota(sorted.begin(), sorted.end(), 1000u);
    expectStablePairs(env, v, sorted, "already sorted");
    expectStablePairs(env, v, std::vector<uint32_t>(sorted.rbegin(), sorted.rend()), "reverse sorted");
    expectStablePairs(env, v, randomUints(n, 3, 3), "three distinct");
    // All-ones keys are also the padding of a partial tile: real ones must still all come out.
    std::vector<uint32_t> ones = randomUints(n, 0, 4);
    for (uint32_t i = 0; i < n; i += 3) ones[i] = 0xFFFFFFFFu;
    expectStablePairs(env, v, ones, "all-ones keys");
}

void radixSizesAroundTheTile(CheckEnv& env, Verdict& v) {
    for (uint32_t count : {1u, 2u, 7u, 255u, 256u, 257u, 2047u, 2048u, 2049u, 4097u, 100003u})
        expectStablePairs(env, v, randomUints(count, 0, count), "random size " + std::to_string(count));
    v.expect(sort(env, {}, nullptr).first.empty(), "empty input records nothing");
}

void radixNarrowKeys(CheckEnv& env, Verdict& v) {
    // Ray-sorting keys are often narrower than 32 bits: 8 bits (one pass + the identity pass), 16, 20 (3 -> 4).
    for (uint32_t bits : {8u, 16u, 20u})
        expectStablePairs(env, v, randomUints(30000, 1u << bits, bits), "keyBits " + std::to_string(bits), bits);
    // Rejected before anything is recorded.
    for (uint32_t bits : {0u, 33u}) {
        bool threw = false;
        try {
            render::recordRadixSort(VK_NULL_HANDLE, {env.ctx, env.shaders}, {}, std::nullopt, 10, {}, bits);
        } catch (const std::invalid_argument&) {
            threw = true;
        }
        v.expect(threw, "keyBits " + std::to_string(bits) + " must be rejected");
    }
}

}  // namespace

std::vector<Check> computeChecks() {
    return {
        {"sum/uint tiles", "", "exact", uintTileSums},
        {"sum/uint reduce", "", "exact (also modulo 2^32)", uintReduce},
        {"sum/float tiles", "", "1e-6 relative to a double sum", floatTileSums},
        {"sum/float reduce", "", "1e-6 relative to a double sum", floatReduce},
        {"scan/exclusive", "", "exact", exclusiveScan},
        {"scan/exclusive in place, wrapping", "", "exact (modulo 2^32)", exclusiveScanInPlaceWrapping},
        {"scan/exclusive three levels", "", "exact", exclusiveScanThreeLevels},
        {"sort/radix keys 1M", "", "exact", radixKeys1M},
        {"sort/radix pairs stable 1M", "", "exact, stable", radixPairsStable1M},
        {"sort/radix patterns", "", "exact, stable", radixPatterns},
        {"sort/radix sizes around the tile", "", "exact, stable", radixSizesAroundTheTile},
        {"sort/radix narrow keys", "", "exact, stable", radixNarrowKeys},
    };
}

}  // namespace idk::conformance
