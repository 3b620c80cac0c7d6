// pt_settings.hpp: what a path-traced image is rendered with, shared by the CPU reference tracer
// (cpu_path_tracer.hpp) and the GPU wavefront tracer (render/path_tracer.hpp), so that both read the same knobs.
// IDKEngine's defaults (reference 2.1): RayDepth 7 (segments), 1 sample per frame, roulette on from the second hit.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

namespace idk::pathtrace {

// Where the random numbers of a path come from (shared/pt_sampler.h). Sobol: Owen-scrambled Sobol' points padded
// in 2D, lower error at equal spp (tests/unit/pathtrace/sampler_test.cpp, BENCHMARKS.md); Independent: a PCG
// stream per pixel and sample, kept for comparison.
enum class PtSampler : uint8_t { Sobol, Independent };
const char* samplerName(PtSampler sampler);                      // "sobol", "independent"
std::optional<PtSampler> parseSampler(std::string_view name);    // nullopt for an unknown name
uint32_t samplerId(PtSampler sampler);                           // gpu::kPtSampler*

struct PtSettings {
    uint32_t spp = 16;           // samples per pixel
    // Longest path in ray segments from the camera (IDKEngine's RayDepth): 1 = only what the camera rays hit
    // (emission, environment), 2 = direct lighting, ... Emission is collected at every hit up to maxDepth; light
    // sampling (NEE) at a hit k happens only when k < maxDepth, so NEE+MIS and BSDF-only count the same paths.
    uint32_t maxDepth = 8;
    uint32_t seed = 0;           // mixed into every pixel's RNG (ptRngInit)
    bool nee = true;             // next-event estimation + MIS; false: BSDF sampling only (IDKEngine's approach;
                                 // punctual lights then contribute nothing, as nothing can hit them)
    uint32_t rouletteDepth = 3;  // Russian roulette after this many segments (0: from the first)
    // GPU tracer: the first sample index rendered (samples firstSample .. firstSample + spp - 1 of the seed's
    // sequence), so that render farm tasks split one image's samples (`idk render --sample-range a:b`).
    uint32_t firstSample = 0;
    PtSampler sampler = PtSampler::Sobol;
};

}  // namespace idk::pathtrace
