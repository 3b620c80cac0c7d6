// bloom_settings.hpp: the options of the bloom (frame/bloom_feature.hpp); rows in frame/settings_table.cpp expose
// them as --bloom and --bloom-strength. `karis` has no flag (always on for frames): the bloom tests set
// passes::BloomParams::karis directly (energy conservation is measured without it, the loss with it).
#pragma once

namespace idk::frame {

struct BloomSettings {
    bool enabled = false;
    float strength = 0.04f;  // blend toward the blurred image (Jimenez 2014 suggests ~0.04)
    bool karis = true;       // Karis average on the first downsample (suppresses fireflies; not energy exact)
};

}  // namespace idk::frame
