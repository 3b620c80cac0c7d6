// temporal_settings.hpp: the options of the temporal passes (frame/temporal_feature.hpp): anti-aliasing mode and
// the length of the jitter sequence. Rows in frame/settings_table.cpp expose them as --aa and --temporal-frames.
#pragma once
#include <cstdint>

namespace idk::frame {

// Taa with upscale < 1, or Upscale (at any scale, 1 included): the temporal upscaler (frame/upscale_feature.hpp)
// renders at `upscale` x output size and reconstructs; Taa at scale 1 resolves at full size (temporal_feature.cpp).
enum class AntiAliasing : uint8_t { None, Taa, Upscale };

struct TemporalSettings {
    AntiAliasing aa = AntiAliasing::None;
    // Halton(2,3) jitter phases; a still renders this many jittered frames and the accumulation's per-pixel weight
    // is capped at it (the still converges to the mean of the phases; motion keeps 1/frames of each new frame).
    uint32_t frames = 16;
    float clipGamma = 1.25f;    // variance clipping box: mean +- gamma * sigma (YCoCg)
    bool clampHistory = true;   // off: "naive" TAA (tests show the ghosting it prevents)
    float upscale = 1.0f;       // --upscale S: render scale in [0.5, 1] of each output dimension (1 = none)
};

// The temporal upscaler runs instead of TAA's full-size resolve: `--aa taa --upscale S` with S < 1, or
// `--aa upscale` (kept as an alias that also runs it at S = 1).
inline bool upscalerRuns(const TemporalSettings& t) {
    return t.aa == AntiAliasing::Upscale || (t.aa == AntiAliasing::Taa && t.upscale < 1.0f);
}

}  // namespace idk::frame
