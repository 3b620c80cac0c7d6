// shadow_culling.hpp: GPU culling of the point-shadow cube faces (issue 10): each face of each cube is a view
// (render/cube_face_views.hpp: the face's 90-degree frustum from the light, cut at the cube's near and far planes)
// and gets one dispatch of the culling kernel (passes/cull_shadows.cpp), whose compacted commands and count the
// point_shadows pass draws. Frustum only (a face has no depth to test against before it is drawn). BLEND casters
// are culled like the others. Runs whenever --culling is not off; the records, per-slot face views and the stats readback exist only then.
#pragma once
#include <optional>
#include <vector>

#include "frame/frame_context.hpp"
#include "passes/culling.hpp"
#include "render/gpu_scene.hpp"
#include "render/point_shadow_maps.hpp"

namespace idk::frame {

class ShadowCulling {
public:
    ShadowCulling() = default;
    ~ShadowCulling() { release(); }
    ShadowCulling(const ShadowCulling&) = delete;
    ShadowCulling& operator=(const ShadowCulling&) = delete;

    void release();  // a new scene (the records are rebuilt at the next culled frame)
    void beginFrame() { lastLights_.clear(); }  // every frame, before addPasses (which a frame may skip)
    // The culled draws of every face of `maps` (view c * 6 + face for cube c), or nothing when culling is off.
    std::optional<passes::ShadowCulledDraws> addPasses(FrameContext& f, const render::GpuScene& scene,
                                                       const render::PointShadowMaps& maps,
                                                       const render::PointShadowFrame& cubes);
    // Per face of the last frame that culled them: "light L face F" (F = +X -X +Y -Y +Z -Z), instances tested and
    // drawn, triangles drawn. Valid once that frame's GPU work has finished.
    std::vector<passes::CullingViewStats> lastStats() const;

private:
    vk::Context* ctx_ = nullptr;
    vk::Buffer draws_;                       // GpuCullDraw per scene draw (static)
    std::vector<vk::Buffer> views_, stats_;  // per frame slot, host-visible: GpuCullView[], GpuCullCounters[]
    uint32_t viewCapacity_ = 0;              // views each of them holds
    uint32_t lastSlot_ = 0;
    std::vector<uint32_t> lastLights_;       // light index per cube of the last culled frame (empty: none)
};

}  // namespace idk::frame
