// vrs_rate_image_test.cpp: the hardware VRS rungs' rate-image converter (vrs/rate_image.comp.glsl) on the device:
// every palette index (and out-of-palette values) in tile counts that do and do not fill the last packed word,
// in both encodings, against the CPU encodings that tests/unit/app/shading_rate_test.cpp checks against the
// spec (KHR: (log2 w << 2) | log2 h; NV: the palette index, clamped to 4x4). The converter runs on lavapipe even
// though the rungs that read its output do not; the bytes past the last tile must be zero and the buffer past
// the last word untouched.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "passes/vrs_passes.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/shading_rate.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {


class VrsRateImageTest : public GpuTest {
protected:
    // The converter's bytes for `rates` (tile order) in one encoding, plus the bytes after them.
    std::vector<uint8_t> convert(const std::vector<uint32_t>& rates, bool nv) {
        const uint32_t tiles = uint32_t(rates.size()), words = (tiles + 3) / 4;
        std::vector<uint32_t> header(4 + tiles);
        header[1] = tiles;
        header[2] = 1;
        std::copy(rates.begin(), rates.end(), header.begin() + 4);
        vk::Buffer in = vk::createBufferWithData(
            ctx(), {header.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "rates", "test"},
            header.data(), header.size() * 4);
        const std::vector<uint32_t> sentinel(words + 1, 0xabababab);  // one spare word: must stay untouched
        vk::Buffer out = vk::createBufferWithData(
            ctx(), {sentinel.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "texels", "test"},
            sentinel.data(), sentinel.size() * 4);
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            passes::recordVrsRateTexels(cmd, ctx(), shaders(), in.address, out.address, tiles, nv);
        });
        const std::vector<uint32_t> words32 = vk::downloadBuffer<uint32_t>(ctx(), out, sentinel.size());
        ctx().destroy(in);
        ctx().destroy(out);
        std::vector<uint8_t> bytes(words32.size() * 4);
        std::memcpy(bytes.data(), words32.data(), bytes.size());
        return bytes;
    }

    void check(const std::vector<uint32_t>& rates) {
        for (bool nv : {false, true}) {
            SCOPED_TRACE(std::string(nv ? "NV" : "KHR") + ", " + std::to_string(rates.size()) + " tiles");
            const std::vector<uint8_t> bytes = convert(rates, nv);
            const size_t used = (rates.size() + 3) / 4 * 4;
            for (size_t i = 0; i < rates.size(); ++i) {
                const uint8_t expected = nv ? uint8_t(std::min(rates[i], 4u)) : vk::khrShadingRateTexel(rates[i]);
                ASSERT_EQ(bytes[i], expected) << "tile " << i << " rate " << rates[i];
            }
            for (size_t i = rates.size(); i < used; ++i) EXPECT_EQ(bytes[i], 0u) << "padding byte " << i;
            for (size_t i = used; i < bytes.size(); ++i) EXPECT_EQ(bytes[i], 0xabu) << "overrun at byte " << i;
        }
    }
};

TEST_F(VrsRateImageTest, EveryPaletteIndexInBothEncodings) {
    std::vector<uint32_t> rates;
    for (uint32_t r = 0; r < 5; ++r) rates.push_back(r);
    rates.insert(rates.end(), {5u, 17u, 0xffffffffu});  // never written by the classifier: clamped to 4x4
    check(rates);  // 8 tiles: two full words
}

TEST_F(VrsRateImageTest, TileCountsThatDoNotFillTheLastWord) {
    std::mt19937 rng(14);
    for (uint32_t tiles : {1u, 2u, 3u, 5u, 255u, 80u * 45u + 1u}) {  // 80x45 + 1: a 1280x720 frame's 16x16 tiles + 1
        std::vector<uint32_t> rates(tiles);
        for (uint32_t& r : rates) r = rng() % 5;
        check(rates);
    }
}

}  // namespace
}  // namespace idk::test
