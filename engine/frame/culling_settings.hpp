// culling_settings.hpp: what GPU culling is asked to do (frame/culling_feature.hpp does it); a member of
// render::RenderSettings, set by the --culling row of frame/settings_table.cpp.
#pragma once
#include <cstdint>

namespace idk::frame {

enum class CullingMode : uint8_t {
    Off,      // every draw, one vkCmdDrawIndexedIndirect
    Frustum,  // each instance's world box against the view frustum, survivors drawn by vkCmdDrawIndexedIndirectCount
    Hiz,      // frustum, then two-phase occlusion culling against the Hi-Z pyramid (culling_types.h, kCullEarly)
};

struct CullingSettings {
    CullingMode mode = CullingMode::Hiz;  // the issue asks for occlusion culling on by default
    // Keep culling with the camera of the frame this was turned on while the view moves (inspect the culled set
    // from outside). Occlusion culling pauses meanwhile: the frozen view has no depth of its own.
    bool freeze = false;
};

}  // namespace idk::frame
