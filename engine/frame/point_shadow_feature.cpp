// point_shadow_feature.cpp: keeps the cubes and the cascade/spot maps in step with the frame's lights, builds the
// shadow table (per-light entries, then the maps' projection records) and adds the passes.
#include "frame/point_shadow_feature.hpp"

#include <cstring>

namespace idk::frame {

void PointShadowFeature::addPasses(FrameContext& f, const render::GpuScene& scene) {
    cull_.beginFrame();
    if (f.settings.lightShadows.rayTraced) {  // frame/rt_shadow_feature.cpp traces them instead
        reset();
        return;
    }
    const std::vector<gpu::GpuLight>& lights = *f.lights;
    const uint32_t maxLights = f.settings.pointShadows.maxLights;
    const bool cubes = render::updatePointShadowMaps(f.ctx, scene, lights, f.settings.pointShadows, maps_);
    const bool maps = render::updateLightShadowMaps(f.ctx, scene, lights, maxLights, f.settings.lightShadows,
                                                    lightMaps_);
    if (!cubes && !maps) return;

    render::PointShadowFrame cubeFrame;
    if (cubes) {
        cubeFrame = maps_->beginFrame(f.graph, lights);
    } else {
        gpu::GpuPointShadow none{};
        none.cube = gpu::kNoShadow;
        cubeFrame.table.assign(lights.size(), none);
    }
    std::vector<gpu::GpuShadowMap> records;
    render::LightShadowFrame mapFrame;
    if (maps)
        mapFrame = lightMaps_->beginFrame(f.graph, lights, f.camera, float(f.width) / float(f.height),
                                          f.settings.lightShadows, cubeFrame.table, records);

    std::vector<uint8_t> bytes(cubeFrame.table.size() * sizeof(gpu::GpuPointShadow) +
                               records.size() * sizeof(gpu::GpuShadowMap));
    std::memcpy(bytes.data(), cubeFrame.table.data(), cubeFrame.table.size() * sizeof(gpu::GpuPointShadow));
    if (!records.empty())
        std::memcpy(bytes.data() + cubeFrame.table.size() * sizeof(gpu::GpuPointShadow), records.data(),
                    records.size() * sizeof(gpu::GpuShadowMap));
    f.pointShadows.table = passes::addShadowTablePass(f.graph, std::move(bytes));
    if (cubes) {
        const std::optional<passes::ShadowCulledDraws> culled = cull_.addPasses(f, scene, *maps_, cubeFrame);
        f.pointShadows.cubes = passes::addPointShadowPass(f.graph, f.ctx, f.shaders, f.scene, *maps_, cubeFrame,
                                                          &f.log, culled ? &*culled : nullptr);
    }
    if (maps) {
        std::vector<graph::TextureHandle> written =
            passes::addLightShadowMapPass(f.graph, f.ctx, f.shaders, f.scene, *lightMaps_, mapFrame, &f.log);
        f.pointShadows.cubes.insert(f.pointShadows.cubes.end(), written.begin(), written.end());
    }
}

}  // namespace idk::frame
