// shading_rate_test.cpp: the hardware VRS rungs' pure arithmetic (engine/vk/shading_rate.*) without a device:
// every palette index in the VK_KHR_fragment_shading_rate attachment encoding against the spec's table
// ((log2 w << 2) | log2 h) and its decoding, the VK_NV_shading_rate_image palette entries, and the tile (texel)
// size chosen from fake device limits shaped like real GPUs' (and impossible ones, refused with a reason).
#include <gtest/gtest.h>

#include "shared/vrs_types.h"
#include "vk/shading_rate.hpp"

namespace idk::vk {
namespace {

// The spec's texel values for the fragment sizes of the classifier's palette (1x1, 2x1, 2x2, 4x2, 4x4):
// width 2^((t >> 2) & 3), height 2^(t & 3).
constexpr uint8_t kSpecTexel[5] = {0u, 4u, 5u, 9u, 10u};

TEST(ShadingRateEncoding, KhrTexelOfEveryPaletteIndexMatchesTheSpec) {
    for (uint32_t rate = 0; rate < gpu::kVrsRateCount; ++rate) {
        EXPECT_EQ(khrShadingRateTexel(rate), kSpecTexel[rate]) << "rate " << rate;
        const VkExtent2D size = khrFragmentSize(khrShadingRateTexel(rate));
        const glm::uvec2 cell = gpu::vrsCellSize(rate);
        EXPECT_EQ(size.width, cell.x) << "rate " << rate;
        EXPECT_EQ(size.height, cell.y) << "rate " << rate;
    }
    // Out-of-palette indices (never written by the classifier) clamp to the coarsest rate, 4x4.
    for (uint32_t rate : {5u, 17u, 0xffffffffu}) EXPECT_EQ(khrShadingRateTexel(rate), 10u) << rate;
}

TEST(ShadingRateEncoding, KhrDecodingCoversEveryFragmentSize) {
    // All nine sizes the extension can express (1, 2, 4 per axis), against the formula written out.
    for (uint32_t lw = 0; lw < 3; ++lw)
        for (uint32_t lh = 0; lh < 3; ++lh) {
            const VkExtent2D s = khrFragmentSize(uint8_t((lw << 2) | lh));
            EXPECT_EQ(s.width, 1u << lw);
            EXPECT_EQ(s.height, 1u << lh);
        }
}

TEST(ShadingRateEncoding, NvPaletteEntryOfEveryIndexShadesItsCell) {
    const VkShadingRatePaletteEntryNV expected[5] = {
        VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_PIXEL_NV, VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_2X1_PIXELS_NV,
        VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_2X2_PIXELS_NV,
        VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_4X2_PIXELS_NV,
        VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_4X4_PIXELS_NV};
    for (uint32_t rate = 0; rate < gpu::kVrsRateCount; ++rate) EXPECT_EQ(nvPaletteEntry(rate), expected[rate]) << rate;
    EXPECT_EQ(nvPaletteEntry(9), VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_4X4_PIXELS_NV);
    // The palette is bound in index order, so distinct indices select distinct entries.
    for (uint32_t a = 0; a < gpu::kVrsRateCount; ++a)
        for (uint32_t b = a + 1; b < gpu::kVrsRateCount; ++b) EXPECT_NE(nvPaletteEntry(a), nvPaletteEntry(b));
}

ShadingRateTexelLimits limits(uint32_t minW, uint32_t minH, uint32_t maxW, uint32_t maxH, uint32_t aspect = 2) {
    return {{minW, minH}, {maxW, maxH}, aspect};
}

TEST(ShadingRateTile, PicksTheOriginals16WhereTheDeviceAllowsIt) {
    EXPECT_EQ(khrShadingRateTile(limits(16, 16, 16, 16)).size, 16u);  // NVIDIA-like: fixed 16x16
    EXPECT_EQ(khrShadingRateTile(limits(8, 8, 32, 32, 4)).size, 16u);  // a range around 16
    EXPECT_EQ(khrShadingRateTile(limits(8, 16, 16, 32)).size, 16u);    // non-square ranges whose squares include 16
    EXPECT_EQ(khrShadingRateTile(limits(4, 4, 64, 64, 8)).size, 16u);
}

TEST(ShadingRateTile, ClampsToTheNearestSquareTheDeviceAndClassifierShare) {
    const ShadingRateTile amd = khrShadingRateTile(limits(8, 8, 8, 8, 1));  // RDNA2-like: fixed 8x8
    EXPECT_EQ(amd.size, 8u);
    EXPECT_TRUE(amd.error.empty());
    EXPECT_EQ(khrShadingRateTile(limits(4, 4, 8, 8)).size, 8u);
    EXPECT_EQ(khrShadingRateTile(limits(32, 32, 64, 64)).size, 32u);
    EXPECT_EQ(khrShadingRateTile(limits(16, 32, 64, 32)).size, 32u);  // square sides: max(16,32)..min(64,32)
}

TEST(ShadingRateTile, RefusesLimitsWithoutASquareTheClassifierHandles) {
    for (const ShadingRateTexelLimits& l : {limits(64, 64, 128, 128), limits(2, 2, 4, 4), limits(32, 8, 64, 16),
                                            limits(0, 0, 0, 0, 0), limits(12, 12, 16, 16)}) {
        const ShadingRateTile t = khrShadingRateTile(l);
        EXPECT_EQ(t.size, 0u) << l.min.width << "x" << l.min.height << ".." << l.max.width << "x" << l.max.height;
        EXPECT_FALSE(t.error.empty());
    }
    EXPECT_NE(khrShadingRateTile(limits(64, 64, 128, 128)).error.find("64x64..128x128"), std::string::npos);
}

TEST(ShadingRateTile, NvTexelMustBeASquareClassifierTile) {
    EXPECT_EQ(nvShadingRateTile({16, 16}).size, 16u);  // Turing/Ampere report 16x16
    EXPECT_EQ(nvShadingRateTile({8, 8}).size, 8u);
    EXPECT_EQ(nvShadingRateTile({32, 32}).size, 32u);
    for (VkExtent2D bad : {VkExtent2D{16, 8}, VkExtent2D{64, 64}, VkExtent2D{4, 4}, VkExtent2D{0, 0}, VkExtent2D{24, 24}}) {
        const ShadingRateTile t = nvShadingRateTile(bad);
        EXPECT_EQ(t.size, 0u) << bad.width << "x" << bad.height;
        EXPECT_NE(t.error.find(std::to_string(bad.width) + "x" + std::to_string(bad.height)), std::string::npos);
    }
}

}  // namespace
}  // namespace idk::vk
