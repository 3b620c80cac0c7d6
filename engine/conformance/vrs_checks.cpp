// vrs_checks.cpp: the variable-rate shading checks (`idk conformance`, ctest label conformance):
//  * "vrs/classify": the GPU shading-rate classifier (vrs/classify.comp.glsl, the frame's VRS feature) against its
//    CPU oracle (frame::classifyTilesCpu) on each rung of the "subgroup reductions" ladder (native:
//    subgroupAdd/Max; fallback: the shared-memory tree), on the Cornell box's HDR frame with camera-like motion and
//    the edge-case tiles of vrs_classify_support.hpp, tile sizes 8, 16 and 32 (partial tiles at the right and
//    bottom), with the original's speed factor and a stronger one: identical rates on every tile;
//  * "vrs/rate image": the hardware rungs' rate-image converter (vrs/rate_image.comp.glsl) against the CPU
//    encodings that tests/unit/app/shading_rate_test.cpp holds to the spec (KHR: (log2 w << 2) | log2 h; NV: the
//    palette index, clamped to 4x4), for every palette index, out-of-palette values and tile counts that do and do
//    not fill the last packed word; the bytes past the last tile must be zero and the buffer past the last word
//    untouched. The converter runs on any device, though only the hardware rungs read its output;
//  * the frame checks of vrs_frame_checks.cpp (software rung at 1x1 and at coarse rates, the hardware rung).
// The DamagedHelmet frame and the documented edge-case rates stay in tests/conformance/vrs/.
#include <algorithm>
#include <cstring>
#include <random>

#include "app/default_scene.hpp"
#include "conformance/vrs_classify_support.hpp"
#include "vk/context.hpp"
#include "vk/shading_rate.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {
namespace {

void classifyOnRung(CheckEnv& env, Verdict& v) {
    VrsFrame f = recordVrsFrame(env.ctx, env.shaders, app::loadDefaultScene());
    patchVrsEdgeCases(f);
    std::array<int, 5> total{};
    for (uint32_t tile : {8u, 16u, 32u}) {
        for (float speedFactor : {gpu::kVrsSpeedFactor, 8.0f}) {
            passes::VrsClassifyParams params;
            params.tileSize = tile;
            params.subgroupReduce = env.rung == vk::Rung::Native;
            params.speedFactor = speedFactor;
            const std::array<int, 5> h =
                expectClassifierMatches(v, env.ctx, env.shaders, f, params, "speed factor " + std::to_string(speedFactor));
            for (int r = 0; r < 5; ++r) total[r] += h[r];
        }
    }
    // The input must exercise the finest and the coarsest rate, or a classifier stuck at one rate could pass.
    v.expect(total[0] > 0 && total[4] > 0, "the frame gives no 1x1 or no 4x4 tile");
}

// The converter's bytes for `rates` (tile order) in one encoding, plus one spare word after them.
std::vector<uint8_t> convertRates(CheckEnv& env, const std::vector<uint32_t>& rates, bool nv) {
    const uint32_t tiles = uint32_t(rates.size()), words = (tiles + 3) / 4;
    std::vector<uint32_t> header(4 + tiles);
    header[1] = tiles;
    header[2] = 1;
    std::copy(rates.begin(), rates.end(), header.begin() + 4);
    vk::Buffer in = vk::createBufferWithData(
        env.ctx, {header.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "check rates", "test"},
        header.data(), header.size() * 4);
    const std::vector<uint32_t> sentinel(words + 1, 0xabababab);  // the spare word must stay untouched
    vk::Buffer out = vk::createBufferWithData(
        env.ctx, {sentinel.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "check texels", "test"},
        sentinel.data(), sentinel.size() * 4);
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        passes::recordVrsRateTexels(cmd, env.ctx, env.shaders, in.address, out.address, tiles, nv);
    });
    const std::vector<uint32_t> words32 = vk::downloadBuffer<uint32_t>(env.ctx, out, sentinel.size());
    env.ctx.destroy(in);
    env.ctx.destroy(out);
    std::vector<uint8_t> bytes(words32.size() * 4);
    std::memcpy(bytes.data(), words32.data(), bytes.size());
    return bytes;
}

void rateImage(CheckEnv& env, Verdict& v) {
    std::vector<std::vector<uint32_t>> cases = {{0u, 1u, 2u, 3u, 4u, 5u, 17u, 0xffffffffu}};  // 5+: clamped to 4x4
    std::mt19937 rng(14);
    for (uint32_t tiles : {1u, 2u, 3u, 5u, 255u, 80u * 45u + 1u}) {  // 80x45 + 1: a 1280x720 frame's 16x16 tiles + 1
        std::vector<uint32_t> rates(tiles);
        for (uint32_t& r : rates) r = rng() % 5;
        cases.push_back(rates);
    }
    for (const std::vector<uint32_t>& rates : cases) {
        for (bool nv : {false, true}) {
            const std::string what = std::string(nv ? "NV" : "KHR") + ", " + std::to_string(rates.size()) + " tiles";
            const std::vector<uint8_t> bytes = convertRates(env, rates, nv);
            const size_t used = (rates.size() + 3) / 4 * 4;
            size_t wrong = 0, padding = 0, overrun = 0;
            for (size_t i = 0; i < rates.size(); ++i)
                wrong += bytes[i] != (nv ? uint8_t(std::min(rates[i], 4u)) : vk::khrShadingRateTexel(rates[i]));
            for (size_t i = rates.size(); i < used; ++i) padding += bytes[i] != 0u;
            for (size_t i = used; i < bytes.size(); ++i) overrun += bytes[i] != 0xabu;
            v.expectEq(wrong, size_t(0), what + ": texels differing from the CPU encoding");
            v.expectEq(padding, size_t(0), what + ": non-zero padding bytes");
            v.expectEq(overrun, size_t(0), what + ": bytes written past the last word");
        }
    }
}

}  // namespace

std::vector<Check> vrsChecks() {
    std::vector<Check> checks = {{"vrs/classify", "subgroup-arithmetic", "identical rates per tile", classifyOnRung},
                                 {"vrs/rate image", "", "exact", rateImage}};
    for (Check& c : vrsFrameChecks()) checks.push_back(std::move(c));
    return checks;
}

}  // namespace idk::conformance
