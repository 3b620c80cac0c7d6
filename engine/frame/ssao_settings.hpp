// ssao_settings.hpp: options of the screen-space ambient occlusion (frame/ssao_feature.hpp); rows in
// frame/settings_table.cpp expose them as --ssao, --ssao-radius and --ssao-samples.
#pragma once
#include <cstdint>

namespace idk::frame {

struct SsaoSettings {
    bool enabled = false;
    float radius = 0.2f;   // world units (IDKEngine's default); occluders farther away do not darken
    uint32_t samples = 16; // rays per pixel per frame (TAA averages the per-frame noise)
};

}  // namespace idk::frame
