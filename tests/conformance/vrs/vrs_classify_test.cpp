// vrs_classify_test.cpp: the GPU shading-rate classifier (vrs/classify.comp.glsl) against its CPU oracle
// (frame::classifyTilesCpu) on the HDR frame the renderer produced for DamagedHelmet (a shared asset; the
// registered check "vrs/classify" runs the same comparison on the Cornell box on each reduction rung), with a
// velocity field of camera-like motion, at a size that leaves partial tiles on the right and bottom, plus the
// edge-case tiles: zero luminance, constant colour, NaN pixels, +inf and 65504 (the RGBA16F image cannot hold 1e6:
// it stores +inf, which the classifier clamps like 1e6), velocities of 1e6 and NaN. Rates must be identical on
// every tile for the subgroup and the shared-memory reductions and tile sizes 8, 16, 32. Second test: the
// documented rate of each edge-case tile. The frame, the edge cases and the comparison live in
// engine/conformance/vrs_classify_support.hpp.
#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>

#include "app/default_scene.hpp"
#include "conformance/vrs_classify_support.hpp"
#include "frame/vrs_oracle.hpp"
#include "passes/vrs_passes.hpp"
#include "render/renderer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

using namespace idk::conformance;  // the frame, edge cases, GPU run and oracle comparison, shared with the registry

class VrsClassifyTest : public GpuTest {
protected:
    std::array<int, 5> compare(const VrsFrame& f, const passes::VrsClassifyParams& params, const std::string& what) {
        Verdict v;
        const std::array<int, 5> histogram = expectClassifierMatches(v, ctx(), shaders(), f, params, what);
        EXPECT_TRUE(v.passed()) << v.messages() << " (" << v.failures() << " failures)";
        return histogram;
    }
};

TEST_F(VrsClassifyTest, SubgroupAndSharedMemoryReductionsMatchTheCpuClassifierOnDamagedHelmet) {
    const bool subgroups = ctx().capabilities().subgroupArithmetic;
    std::cout << "[ vrs ] subgroup size " << ctx().capabilities().subgroupSize
              << (subgroups ? "" : " (no subgroup arithmetic: shared-memory variant only)") << "\n";
    std::array<int, 5> total{};
    for (const char* name : {"helmet"}) {
        scene::Scene scene =
            scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
        VrsFrame f = recordVrsFrame(ctx(), shaders(), scene);
        patchVrsEdgeCases(f);
        for (uint32_t tile : {8u, 16u, 32u}) {
            for (bool subgroup : {true, false}) {
                if (subgroup && !subgroups) continue;
                // The original's factors, and stronger ones so that the speed term decides some tiles.
                std::vector<float> speedFactors{gpu::kVrsSpeedFactor};
                if (tile == 16u) speedFactors.push_back(8.0f);
                for (float speedFactor : speedFactors) {
                    passes::VrsClassifyParams params;
                    params.tileSize = tile;
                    params.subgroupReduce = subgroup;
                    params.speedFactor = speedFactor;
                    std::string what = std::string(name) + (subgroup ? " subgroup" : " shared-memory");
                    std::array<int, 5> h = compare(f, params, what);
                    for (int r = 0; r < 5; ++r) total[r] += h[r];
                }
            }
        }
    }
    std::cout << "[ vrs ] tiles per rate 1x1..4x4:";
    for (int r = 0; r < 5; ++r) std::cout << " " << total[r];
    std::cout << "\n";
    for (int r = 0; r < 5; ++r) EXPECT_GT(total[r], 0) << "no tile at rate " << r << ": the frames do not exercise it";
}

TEST_F(VrsClassifyTest, EdgeCaseTilesGetTheDocumentedRates) {
    VrsFrame f = recordVrsFrame(ctx(), shaders(), app::loadDefaultScene());
    for (glm::vec2& v : f.velocity) v = glm::vec2(0.0f);  // no motion but the patched tiles'
    patchVrsEdgeCases(f);
    passes::VrsClassifyParams params;
    params.tileSize = 32;
    params.subgroupReduce = ctx().capabilities().subgroupArithmetic;
    std::vector<uint32_t> rates = classifyOnGpu(ctx(), shaders(), f, params);
    const uint32_t row = (kVrsWidth + 31) / 32;
    EXPECT_EQ(rates[0], 4u) << "zero luminance: dark, 4x4";
    EXPECT_EQ(rates[1], 4u) << "constant colour: CV 0, 4x4";
    EXPECT_EQ(rates[2], 0u) << "NaN pixels count as black: CV 0.71, 0.04/CV -> 1x1";
    EXPECT_EQ(rates[3], 0u) << "+inf clamped to 65504: CV 2 -> 1x1";
    EXPECT_EQ(rates[4], 0u) << "65504 / 0.01 alternating: CV ~1 -> 1x1";
    EXPECT_EQ(rates[5], 4u) << "negative radiance counts as black: dark, 4x4";
    EXPECT_EQ(rates[row + 0], 4u) << "1e6 UV per frame: the speed term saturates, 4x4";
    EXPECT_EQ(rates[row + 1], 0u) << "NaN velocity counts as still: CV 1/3 alone -> 1x1";
    EXPECT_EQ(rates[row + 2], 4u) << "mean luminance 0.00095 <= 0.001: dark, 4x4";
    frame::VrsTileRates cpu = frame::classifyTilesCpu(f.lit, f.velocity, kVrsWidth, kVrsHeight, 32, params.frameSeconds,
                                                      params.speedFactor, params.lumVarianceFactor);
    EXPECT_EQ(rates, cpu.rates);
}

}  // namespace
}  // namespace idk::test
