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

// How the culled camera view's G-buffer draws its geometry (--geometry).
enum class GeometryPath : uint8_t {
    Auto,  // the "mesh-shading" ladder's rung (--rung mesh-shading=..., --fallback)
    Mesh,  // VK_EXT_mesh_shader: a task shader culls each surviving instance's meshlets (render/meshlets.hpp)
    Mdi,   // whole instances by vkCmdDrawIndexedIndirectCount
};

struct CullingSettings {
    CullingMode mode = CullingMode::Hiz;  // the issue asks for occlusion culling on by default
    GeometryPath geometry = GeometryPath::Auto;  // only with culling on: culling off draws every instance at once
    // Keep culling with the camera of the frame this was turned on while the view moves (inspect the culled set
    // from outside). Occlusion culling pauses meanwhile: the frozen view has no depth of its own.
    bool freeze = false;
};

inline const char* toString(CullingMode m) {
    return m == CullingMode::Off ? "off" : m == CullingMode::Frustum ? "frustum" : "hiz";
}

}  // namespace idk::frame
