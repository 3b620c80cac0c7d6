// vrs_settings.hpp: what variable-rate shading (frame/vrs_feature.*) is asked to do; a member of
// render::RenderSettings. Off by default, as in IDKEngine.
#pragma once
#include "shared/vrs_types.h"

namespace idk::frame {

struct VrsSettings {
    bool enabled = false;        // --vrs on: lighting and sky at the rates classified from the previous frame
    bool debug = false;          // --vrs-debug: tint each tile by its rate (the rate overlay)
    float speedFactor = gpu::kVrsSpeedFactor;              // the original's SpeedFactor
    float lumVarianceFactor = gpu::kVrsLumVarianceFactor;  // the original's LumVarianceFactor
    float frameSeconds = 1.0f / 60.0f;  // converts motion per frame to per second (the viewer sets its dt)
    int fixedRate = -1;          // --vrs-rate: -1 classify; 0..4 every tile at that palette rate (1x1 .. 4x4)
    // Test hook (Hdr output only): the target is filled with kVrsSentinel before lighting and not reconstructed,
    // so a test sees exactly which pixels lighting and sky shaded.
    bool testShadedOnly = false;
    // Checks and tests: the software rung even where the "vrs" ladder chose a hardware one (rungs compared on one
    // device; `--rung vrs=fallback` does the same for a whole run).
    bool softwareRung = false;
};

}  // namespace idk::frame
