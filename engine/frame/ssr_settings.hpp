// ssr_settings.hpp: options of the screen-space reflections (frame/ssr_feature.hpp); rows in
// frame/settings_table.cpp expose them as --ssr, --ssr-steps and --ssr-thickness.
#pragma once
#include <cstdint>

namespace idk::frame {

struct SsrSettings {
    bool enabled = false;    // off by default, as in IDKEngine
    uint32_t maxSteps = 64;  // Hi-Z iterations per ray; a ray still marching after them is a miss
    float thickness = 0.1f;  // world units a surface is taken to extend behind its depth (thinner: rays pass behind)
};

}  // namespace idk::frame
