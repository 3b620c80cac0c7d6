// point_shadow_feature.hpp: shadows of every punctual light: cubes of point lights (and of spots too wide for one
// map; render/point_shadow_maps.hpp, passes/point_shadows.cpp), cascades of directional lights and single maps of
// spot lights (render/light_shadow_maps.hpp, passes/light_shadow_maps.cpp), and the frame's shadow table. Each
// kind of map exists only while a light needs it; fills FrameContext::pointShadows. With --culling on, every cube
// face draws only the instances its frustum culling keeps (frame/shadow_culling.hpp).
#pragma once
#include <memory>

#include "frame/frame_context.hpp"
#include "frame/shadow_culling.hpp"
#include "render/gpu_scene.hpp"
#include "render/light_shadow_maps.hpp"
#include "render/point_shadow_maps.hpp"

namespace idk::frame {

class PointShadowFeature {
public:
    void reset() {  // a new scene
        maps_.reset();
        lightMaps_.reset();
        cull_.release();
    }
    void addPasses(FrameContext& f, const render::GpuScene& scene);
    const render::PointShadowMaps* maps() const noexcept { return maps_.get(); }
    const render::LightShadowMaps* lightMaps() const noexcept { return lightMaps_.get(); }
    // GPU culling's counters per cube face of the last frame (empty when it did not cull them).
    std::vector<passes::CullingViewStats> cullStats() const { return cull_.lastStats(); }

private:
    std::unique_ptr<render::PointShadowMaps> maps_;
    std::unique_ptr<render::LightShadowMaps> lightMaps_;
    ShadowCulling cull_;  // per-face culling of the cubes (--culling frustum|hiz)
};

}  // namespace idk::frame
