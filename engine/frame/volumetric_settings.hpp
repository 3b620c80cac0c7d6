// volumetric_settings.hpp: the options of volumetric lighting (frame/volumetrics_feature.hpp), apart so that
// render/render_settings.hpp can hold them without the feature's dependencies.
#pragma once
#include <cstdint>

namespace idk::frame {

struct VolumetricSettings {
    bool enabled = false;
    float density = 0.05f;     // scattering coefficient sigma_s per metre (no absorption: sigma_t = sigma_s)
    float anisotropy = 0.3f;   // Henyey-Greenstein g in (-1, 1): > 0 scatters forward (shafts towards the light)
    uint32_t scale = 2;        // 2: half resolution, 4: quarter
    uint32_t steps = 32;       // midpoint steps per view ray
};

}  // namespace idk::frame
