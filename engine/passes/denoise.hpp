// denoise.hpp: the path tracer's denoiser as render-graph passes: an edge-aware a-trous wavelet filter guided by
// first-hit albedo, normal and depth (SVGF's spatial filter, Schied et al. 2017; the math is in
// shaders_glsl/shared/denoise_filter.h), with the path tracer's per-pixel variance (DenoiseInputs::variance) as the
// noise level and a final shrink toward the raw pixel where the filter's change exceeds it. Replaces IDKEngine's
// OIDN integration (reference 2.2): OIDN is not packaged in Debian. Passes: denoise_prepare, denoise_atrous_<i>
// (i < iterations, step 2^i), denoise_remodulate.
#pragma once
#include <cstdint>

#include "graph/render_graph.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::passes {

// All four inputs have the graph's output extent (storage images; read with imageLoad).
struct DenoiseInputs {
    graph::TextureHandle color;   // RGBA32F (or RGBA16F) linear radiance (noisy)
    graph::TextureHandle albedo;  // RGBA16F/32F first-hit albedo (1 for sky)
    graph::TextureHandle normal;  // RGBA16F/32F first-hit world normal (xyz), 0 for sky
    graph::TextureHandle depth;   // R32F first-hit view distance (0 or inf for sky)
    // Optional R32F: the variance of each pixel's mean luminance (from the tracer's second moments; negative when
    // unknown, e.g. at 1 spp). With it the luminance tolerance is the pixel's own noise, not its neighbourhood's
    // spread (which counts texture and lighting detail as noise and over-blurs at high spp), and the output is
    // shrunk toward the raw pixel where the filter's change exceeds that noise (denoiseShrinkWeight).
    graph::TextureHandle variance;
};

struct DenoiseSettings {
    uint32_t iterations = 5;       // a-trous iterations, steps 1, 2, 4, ... (0: demodulate + remodulate only)
    float sigmaLuminance = 4.0f;   // luminance tolerance in standard deviations of the pixel's noise
    float sigmaNormal = 128.0f;    // exponent of the normal similarity max(0, dot)^sigma
    float sigmaDepth = 1.0f;       // depth tolerance in units of the pixel's depth gradient times the distance
    float fireflyClamp = 4.0f;     // clamp a pixel's luminance to its neighbours' mean + this many standard
                                   // deviations before filtering (biased darker; <= 0: off)
};

// Returns the denoised RGBA32F image (a transient "denoised" texture of the output extent). Sky pixels (invalid
// guides) keep their input radiance; NaN/inf radiance becomes 0. Throws graph::GraphError while recording when an
// input has another format or extent.
graph::TextureHandle addDenoisePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    const DenoiseInputs& inputs, const DenoiseSettings& settings);

}  // namespace idk::passes
