// rt_shadow_feature.cpp: the ray-traced shadow geometry (path tracer's BVH / acceleration structures, scene
// description) and the per-frame mask passes. See rt_shadow_feature.hpp.
#include "frame/rt_shadow_feature.hpp"

#include <algorithm>

#include "core/log.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/light_shadow_maps.hpp"
#include "render/point_shadow_maps.hpp"
#include "render/pt_geometry.hpp"
#include "render/pt_tables.hpp"
#include "shared/rt_shadow_types.h"
#include "vk/acceleration_structure.hpp"
#include "vk/context.hpp"
#include "vk/features.hpp"

namespace idk::frame {

struct RtShadowFeature::Geometry {
    vk::Context& ctx;
    render::PtGpuGeometry geometry;
    render::PtTables tables;
    std::unique_ptr<vk::AccelerationStructures> accel;
    vk::Buffer desc;
    bool rayQuery = false;
    bool hasAlpha = false;

    explicit Geometry(vk::Context& c) : ctx(c) {}
    ~Geometry() {
        accel.reset();
        render::destroyPtGeometry(ctx, geometry);
        render::destroyPtTables(ctx, tables);
        if (desc) ctx.destroyDeferred(desc);
    }
};

RtShadowFeature::RtShadowFeature() = default;
RtShadowFeature::~RtShadowFeature() = default;

bool RtShadowFeature::rayQuery() const noexcept { return geometry_ && geometry_->rayQuery; }

void RtShadowFeature::setScene(vk::Context& ctx, const scene::Scene& source, const render::GpuScene& scene,
                               const render::RenderSettings& settings) {
    geometry_.reset();
    warned_ = false;
    ensureGeometry(ctx, source, scene, settings);
}

void RtShadowFeature::ensureGeometry(vk::Context& ctx, const scene::Scene& source, const render::GpuScene& scene,
                                     const render::RenderSettings& settings) {
    // Built once per scene, only while the mode is on (nothing is allocated for it otherwise): a switch to ray-traced
    // shadows after setScene builds it here, before the frame that needs it. The uploads are immediate submissions
    // that only create resources, so frames in flight are unaffected.
    if (geometry_ || !settings.lightShadows.rayTraced || source.lights.empty() || scene.drawCount() == 0) return;
    // Lights are not needed for visibility: no environment, no light tables worth the name.
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(source, nullptr, 0.0f);
    auto g = std::make_unique<Geometry>(ctx);
    g->rayQuery = ctx.ladder("ray traversal").chosen == vk::Rung::Native;
    g->hasAlpha = pts.alphaTesting;
    g->geometry = render::uploadPtGeometry(ctx, pts, false);
    if (g->rayQuery) {
        std::vector<vk::AccelMesh> meshes;
        for (const pathtrace::PtGeometry& m : pts.geometries) meshes.push_back({m.positions, m.triangles});
        std::vector<vk::AccelInstance> instances;
        for (uint32_t i = 0; i < pts.instances.size(); ++i)
            instances.push_back({pts.instances[i].objectToWorld, pts.instances[i].blasIndex, i});
        g->accel = std::make_unique<vk::AccelerationStructures>(ctx, meshes, instances);
    }
    g->tables = render::uploadPtTables(ctx, pts, std::vector<render::PtTextureBinding>(source.textures.size()),
                                       render::PtTextureBinding{});
    gpu::GpuPtSceneDesc d = g->tables.desc;
    d.tlas = g->geometry.tlas->descAddress();
    d.accel = g->accel ? g->accel->tlasAddress() : 0;
    d.geometries = g->geometry.geometryTable.address;
    d.instances = g->geometry.instanceTable.address;
    d.materials = scene.materialBuffer().address;  // the raster's materials, with their bindless texture slots
    d.instanceCount = uint32_t(g->geometry.instances.size());
    g->desc = render::uploadPtBuffer(ctx, &d, sizeof(d), "rt shadow scene");
    geometry_ = std::move(g);
}

std::optional<passes::VoxelShadowRays> RtShadowFeature::voxelShadowRays(const FrameContext& f) const {
    if (!f.settings.lightShadows.rayTraced || !geometry_ || !f.lights) return std::nullopt;
    const size_t casters = render::shadowCasters(*f.lights, f.settings.pointShadows.maxLights).size();
    if (casters == 0) return std::nullopt;
    passes::VoxelShadowRays r;
    r.sceneDesc = geometry_->desc.address;
    r.casters = uint32_t(std::min<size_t>(casters, gpu::kRtShadowMaxLights));  // as the mask pass's
    r.blasStack = geometry_->geometry.blasStackSize;
    r.tlasStack = geometry_->geometry.tlasStackSize;
    r.hasAlpha = geometry_->hasAlpha;
    return r;
}

void RtShadowFeature::addPasses(FrameContext& f, const render::GpuScene&) {
    if (!f.settings.lightShadows.rayTraced) return;
    std::vector<uint32_t> casters = render::shadowCasters(*f.lights, f.settings.pointShadows.maxLights);
    if (casters.size() > gpu::kRtShadowMaxLights) casters.resize(gpu::kRtShadowMaxLights);
    if (casters.empty()) return;
    if (!geometry_) {
        if (!warned_)
            core::logWarning("ray-traced shadows: switched on after the scene was loaded, and the geometry was not built "
                             "(Renderer::prepareSourceScene)");
        warned_ = true;
        return;
    }
    passes::RtShadowInputs in;
    in.frame = f.frameConstants;
    in.lights = f.scene.lights;
    in.depth = f.gbuffer.depth;
    in.normal = f.gbuffer.normal;
    in.sceneDesc = geometry_->desc.address;
    in.rayQuery = geometry_->rayQuery;
    in.hasAlpha = geometry_->hasAlpha;
    in.blasStack = geometry_->geometry.blasStackSize;
    in.tlasStack = geometry_->geometry.tlasStackSize;
    in.casters = std::move(casters);
    in.lightCount = uint32_t(f.lights->size());
    in.lightRadius = f.settings.lightShadows.lightRadius;
    in.softRays = std::max(f.settings.lightShadows.softShadowRays, 1u);
    f.pointShadows = passes::addRtShadowPasses(f.graph, f.ctx, f.shaders, in, f.width, f.height);
}

}  // namespace idk::frame
