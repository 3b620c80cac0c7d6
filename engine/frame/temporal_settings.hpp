// temporal_settings.hpp: the options of the temporal passes (frame/temporal_feature.hpp): anti-aliasing mode and
// the length of the jitter sequence. Rows in frame/settings_table.cpp expose them as --aa and --temporal-frames.
#pragma once
#include <cstdint>

namespace idk::frame {

// Upscale: the temporal upscaler (frame/upscale_feature.hpp) renders at `upscale` x output size and reconstructs.
enum class AntiAliasing : uint8_t { None, Taa, Upscale };

struct TemporalSettings {
    AntiAliasing aa = AntiAliasing::None;
    // Halton(2,3) jitter phases; a still renders this many jittered frames and the accumulation's per-pixel weight
    // is capped at it (the still converges to the mean of the phases; motion keeps 1/frames of each new frame).
    uint32_t frames = 16;
    float clipGamma = 1.25f;    // variance clipping box: mean +- gamma * sigma (YCoCg)
    bool clampHistory = true;   // off: "naive" TAA (tests show the ghosting it prevents)
    float upscale = 0.5f;       // --aa upscale: render scale S in [0.5, 1] of each output dimension
};

}  // namespace idk::frame
