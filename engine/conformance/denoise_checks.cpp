// denoise_checks.cpp: the path tracer's edge-aware a-trous denoiser (engine/passes/denoise.cpp,
// shaders_glsl/denoise/*) on the device against its CPU oracle (denoise_oracle.hpp: the same loops over the same
// per-pixel math, shaders_glsl/shared/denoise_filter.h compiled as C++), on the synthetic scene of
// denoise_harness.hpp: default settings; RGBA16F guides with 3 iterations, other sigmas and no firefly clamp; and
// the per-pixel variance input (some pixels unknown). Tolerance per channel: |gpu - cpu| <= 1e-5 + 1e-4 |cpu|; the
// reported error is the worst difference in units of that tolerance (<= 1 passes). The quality and robustness
// properties (noise falls, edges stay, fireflies, degenerate inputs) stay in tests/conformance/denoise/.
#include "conformance/conformance.hpp"
#include "conformance/denoise_harness.hpp"

namespace idk::conformance {
namespace {

void expectMatch(Verdict& v, const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu, const std::string& what) {
    const DenoiseDiff d = compareDenoised(gpu, cpu);
    v.recordError(d.worst);
    v.expectEq(d.nonFinite, size_t(0), what + ": non-finite output values");
    v.expect(d.worst <= 1.0f, what + ": worst difference " + std::to_string(d.worst) + " times the tolerance");
}

void defaultSettings(CheckEnv& env, Verdict& v) {
    const SyntheticScene s = makeSyntheticScene(72, 56, 0.6f, 7);
    const passes::DenoiseSettings settings;
    expectMatch(v, denoiseOnGpu(env.ctx, env.shaders, s.noisy, settings), DenoiseOracle(s.noisy).run(settings),
                "default settings");
}

void halfGuides(CheckEnv& env, Verdict& v) {
    const SyntheticScene s = makeSyntheticScene(64, 64, 0.3f, 11);
    const passes::DenoiseSettings settings{3, 2.0f, 32.0f, 2.0f, 0.0f};  // no firefly clamp
    const std::vector<glm::vec4> gpu = denoiseOnGpu(env.ctx, env.shaders, s.noisy, settings, /*halfGuides=*/true);
    DenoiseImages halved = s.noisy;  // the oracle sees the guides as the RGBA16F images store them
    halved.albedo = roundToHalf(halved.albedo);
    halved.normal = roundToHalf(halved.normal);
    expectMatch(v, gpu, DenoiseOracle(halved).run(settings), "half guides, 3 iterations");
}

void withVariance(CheckEnv& env, Verdict& v) {
    SyntheticScene s = makeSyntheticScene(72, 56, 0.3f, 5);
    addVariance(s, 0.3f, true);
    const passes::DenoiseSettings settings;
    expectMatch(v, denoiseOnGpu(env.ctx, env.shaders, s.noisy, settings), DenoiseOracle(s.noisy).run(settings),
                "per-pixel variance");
}

}  // namespace

std::vector<Check> denoiseChecks() {
    const std::string tolerance = "1e-5 + 1e-4 relative per channel (error in units of it)";
    return {
        {"denoise/default settings", "", tolerance, defaultSettings},
        {"denoise/half guides", "", tolerance, halfGuides},
        {"denoise/pixel variance", "", tolerance, withVariance},
    };
}

}  // namespace idk::conformance
