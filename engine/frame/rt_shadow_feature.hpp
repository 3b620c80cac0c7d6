// rt_shadow_feature.hpp: ray-traced shadows (`--shadows raytraced`): the path tracer's scene geometry uploaded for
// the raster frame (render/pt_geometry.hpp: our binary BVH, plus driver acceleration structures when the "ray
// traversal" ladder takes its native rung, VK_KHR_ray_query), and after the G-buffer one shadow ray per pixel and
// shadow-casting light (passes/rt_shadows.cpp); fills FrameContext::pointShadows with the mask and its table, in
// place of cubes and maps (frame/point_shadow_feature.cpp adds none in this mode). The geometry is built by
// setScene while the mode is on, or by ensureGeometry when the mode is switched on later (the viewer's shadow mode:
// Renderer::prepareSourceScene before each frame); without either a frame gets no ray-traced shadows (one warning). Static geometry: animated meshes keep their bind pose in the BVH. Ports IDKEngine's
// ShadowMode.RayTraced (reference 2.12).
#pragma once
#include <memory>
#include <optional>

#include "frame/frame_context.hpp"
#include "passes/vxgi_passes.hpp"
#include "render/gpu_scene.hpp"
#include "scene/scene.hpp"

namespace idk::frame {

class RtShadowFeature {
public:
    RtShadowFeature();
    ~RtShadowFeature();
    RtShadowFeature(const RtShadowFeature&) = delete;
    RtShadowFeature& operator=(const RtShadowFeature&) = delete;

    void setScene(vk::Context& ctx, const scene::Scene& source, const render::GpuScene& scene,
                  const render::RenderSettings& settings);
    // Builds the geometry if the mode is on and it is not built yet for this scene (a no-op otherwise).
    void ensureGeometry(vk::Context& ctx, const scene::Scene& source, const render::GpuScene& scene,
                        const render::RenderSettings& settings);
    void addPasses(FrameContext& f, const render::GpuScene& scene);
    bool rayQuery() const noexcept;  // the rung the geometry was built for (false: our BVH)
    // What the voxelization's shadow rays need this frame (--shadows raytraced with casters and the geometry
    // built), else nothing: VXGI voxelizes before the mask pass exists.
    std::optional<passes::VoxelShadowRays> voxelShadowRays(const FrameContext& f) const;

private:
    struct Geometry;
    std::unique_ptr<Geometry> geometry_;
    bool warned_ = false;
};

}  // namespace idk::frame
