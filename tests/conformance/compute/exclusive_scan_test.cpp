// exclusive_scan_test.cpp: the reduce-then-scan exclusive prefix scan of uint32 (modulo 2^32) against
// std::exclusive_scan, exactly, for empty, single-tile, multi-tile, 1M and 2^20 + 3 inputs, in and out of place.
#include <gtest/gtest.h>

#include <numeric>

#include "device_array.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

class ExclusiveScanTest : public GpuTest {
protected:
    std::vector<uint32_t> scan(const std::vector<uint32_t>& input, bool inPlace,
                               uint32_t slotSubgroupSize = 0) {
        uint32_t count = uint32_t(input.size());
        DeviceArray in(ctx(), count, "scan input");
        DeviceArray out(ctx(), inPlace ? 0 : count, "scan output");
        DeviceArray scratch(ctx(), render::exclusiveScanScratchElements(count), "scan scratch");
        in.upload(input);
        DeviceArray& result = inPlace ? in : out;
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordExclusiveScan(cmd, {ctx(), shaders(), slotSubgroupSize}, in.array(), result.array(), count,
                                        scratch.array());
        });
        return result.download<uint32_t>(count);
    }
};

std::vector<uint32_t> expectedScan(const std::vector<uint32_t>& input) {
    std::vector<uint32_t> out(input.size());
    std::exclusive_scan(input.begin(), input.end(), out.begin(), 0u);
    return out;
}

TEST_F(ExclusiveScanTest, MatchesStdExclusiveScan) {
    // 0, 1, one partial tile, exactly one tile (2048), just past it, several tiles, 1M, 1M + 3 (two levels).
    for (uint32_t count : {0u, 1u, 1000u, 2048u, 2049u, 100000u, 1u << 20, (1u << 20) + 3}) {
        // Values below 4096 keep the sums wrap-free; the wrap-around case is its own test.
        std::vector<uint32_t> input = randomUints(count, 4096, count);
        std::vector<uint32_t> got = scan(input, false);
        ASSERT_EQ(got.size(), input.size());
        std::vector<uint32_t> expected = expectedScan(input);
        for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(got[i], expected[i]) << "count " << count << " at " << i;
    }
}

TEST_F(ExclusiveScanTest, InPlaceAndWrappingModulo2To32) {
    std::vector<uint32_t> input = randomUints((1u << 20) + 3, 0, 5);  // full range: the sums wrap many times
    EXPECT_EQ(scan(input, true), expectedScan(input));
}

TEST_F(ExclusiveScanTest, ThreeLevelsOfBlockSums) {
    // More than 2048 * 2048 elements: the block sums themselves need a second reduce-then-scan level.
    const uint32_t count = (1u << 22) + 2049;
    std::vector<uint32_t> input = randomUints(count, 16, 9);
    ASSERT_GT(render::exclusiveScanScratchElements(count), render::kScanTile + 1);
    EXPECT_EQ(scan(input, false), expectedScan(input));
}

}  // namespace
}  // namespace idk::test
