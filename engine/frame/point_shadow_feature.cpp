// point_shadow_feature.cpp: keeps the point-shadow cubes in step with the frame's lights and adds their pass.
#include "frame/point_shadow_feature.hpp"

namespace idk::frame {

void PointShadowFeature::addPasses(FrameContext& f, const render::GpuScene& scene) {
    if (!render::updatePointShadowMaps(f.ctx, scene, *f.lights, f.settings.pointShadows, maps_)) return;
    f.pointShadows = passes::addPointShadowPass(f.graph, f.ctx, f.shaders, f.scene, *maps_, *f.lights, &f.log);
}

}  // namespace idk::frame
