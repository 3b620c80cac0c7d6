// point_shadow_feature.hpp: cube shadows of point and spot lights (render/point_shadow_maps.hpp holds the cubes,
// passes/point_shadows.cpp draws them). The cubes exist only while a light casts a shadow; fills
// FrameContext::pointShadows.
#pragma once
#include <memory>

#include "frame/frame_context.hpp"
#include "render/gpu_scene.hpp"
#include "render/point_shadow_maps.hpp"

namespace idk::frame {

class PointShadowFeature {
public:
    void reset() { maps_.reset(); }  // a new scene
    void addPasses(FrameContext& f, const render::GpuScene& scene);
    const render::PointShadowMaps* maps() const noexcept { return maps_.get(); }

private:
    std::unique_ptr<render::PointShadowMaps> maps_;
};

}  // namespace idk::frame
