// vrs_checks.cpp: the GPU shading-rate classifier (vrs/classify.comp.glsl, the frame's VRS feature) against its CPU
// oracle (frame::classifyTilesCpu) on each rung of the "subgroup reductions" ladder (native: subgroupAdd/Max;
// fallback: the shared-memory tree), on the Cornell box's HDR frame with camera-like motion and the edge-case tiles
// of vrs_classify_support.hpp, tile sizes 8, 16 and 32 (partial tiles at the right and bottom), with the
// original's speed factor and a stronger one. Rates identical on every tile. The DamagedHelmet frame and the
// documented edge-case rates stay in tests/conformance/vrs/.
#include "app/default_scene.hpp"
#include "conformance/vrs_classify_support.hpp"

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

}  // namespace

std::vector<Check> vrsChecks() {
    return {{"vrs/classify", "subgroup-arithmetic", "identical rates per tile", classifyOnRung}};
}

}  // namespace idk::conformance
