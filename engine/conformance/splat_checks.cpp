// splat_checks.cpp: the float-atomics ladder (engine/render/float_splat.hpp) on each rung against its CPU oracle,
// the rungs against each other on one input, and the GL-interop memory round trip (gl/interop_probe.hpp).
// Inputs are chosen so float addition is exact in any order: values are multiples of 1/8 below 8 and every
// partial sum stays below 2^21, so each bin and the total have one right answer and the tolerance is "exact".
#include <algorithm>
#include <random>

#include "conformance/conformance.hpp"
#include "gl/interop_probe.hpp"
#include "render/float_splat.hpp"
#include "vk/context.hpp"

namespace idk::conformance {
namespace {

// 100,000 samples over 1,000 bins: a tenth of them land in bin 7 (the contended case a CAS loop or an atomic
// unit must get right), 1% carry an out-of-range bin (dropped), the rest are uniform.
render::SplatInput splatInput(uint32_t seed) {
    render::SplatInput in;
    in.binCount = 1000;
    std::mt19937 rng(seed);
    for (uint32_t i = 0; i < 100000; ++i) {
        const uint32_t r = rng() % 1000;
        in.bins.push_back(r < 100 ? 7u : r < 110 ? in.binCount + r : uint32_t(rng() % in.binCount));
        in.values.push_back(float(rng() % 64) / 8.0f);
    }
    return in;
}

void compare(Verdict& v, const render::SplatResult& got, const render::SplatResult& want, const std::string& what) {
    if (!v.expectEq(got.bins.size(), want.bins.size(), what + ": bin count")) return;
    for (size_t b = 0; b < got.bins.size(); ++b) {
        v.recordError(std::abs(double(got.bins[b]) - want.bins[b]));
        v.expect(got.bins[b] == want.bins[b], what + ": bin " + std::to_string(b) + " is " + std::to_string(got.bins[b]) +
                                                  ", expected " + std::to_string(want.bins[b]));
    }
    v.recordError(std::abs(double(got.total) - want.total));
    v.expect(got.total == want.total,
             what + ": total " + std::to_string(got.total) + ", expected " + std::to_string(want.total));
}

void splatOnRung(CheckEnv& env, Verdict& v) {
    const render::SplatInput input = splatInput(1);
    const render::SplatResult oracle = render::splatOracle(input);
    v.expect(oracle.bins[7] > 1000.0f, "the input has no hot bin");  // the contended case is really there
    compare(v, render::runSplatGraph(env.ctx, env.shaders, input, env.rung, env.glShaderDir), oracle, "splat");
}

void rungsAgree(CheckEnv& env, Verdict& v) {
    const render::SplatInput input = splatInput(2);
    std::vector<std::pair<vk::Rung, render::SplatResult>> results;
    for (const vk::RungOption& o : env.ctx.ladder("float-atomics").options)
        if (o.available) results.emplace_back(o.rung, render::runSplatGraph(env.ctx, env.shaders, input, o.rung, env.glShaderDir));
    if (results.size() < 2) {
        v.skip("fewer than two float-atomics rungs on this device");
        return;
    }
    for (size_t i = 1; i < results.size(); ++i)
        compare(v, results[i].second, results[0].second,
                std::string(vk::rungName(results[i].first)) + " vs " + vk::rungName(results[0].first));
}

void glRoundTrip(CheckEnv& env, Verdict& v) {
    if (!env.ctx.glContext()) {
        v.skip("GL interop absent: " + env.ctx.capabilities().glInteropNote);
        return;
    }
    const std::string error = gl::roundTrip(env.ctx, *env.ctx.glContext(), 37, 19);
    v.expect(error.empty(), error);
}

}  // namespace

std::vector<Check> splatChecks() {
    return {
        {"float-atomics/splat", "float-atomics", "exact", splatOnRung},
        {"float-atomics/rungs agree", "", "bit-identical bins and total", rungsAgree},
        {"gl-interop/round trip", "", "exact bytes", glRoundTrip},
    };
}

}  // namespace idk::conformance
