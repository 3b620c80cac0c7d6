// volumetrics_feature.hpp: volumetric lighting (`--volumetrics`): a homogeneous medium lit by every punctual light
// with its shadows, ray-marched at half or quarter resolution and composited by a depth-aware upsample
// (passes/volumetrics.cpp). Nothing is created or dispatched while it is off; the low-resolution image is a
// transient of the frame's graph. Ports IDKEngine's VolumetricLighting (reference 1.5 step 8).
#pragma once
#include "frame/frame_context.hpp"
#include "frame/volumetric_settings.hpp"
#include "render/gpu_scene.hpp"

namespace idk::frame {

class VolumetricsFeature {
public:
    void addPasses(FrameContext& f, const render::GpuScene& scene);

private:
    const render::GpuScene* boundsOf_ = nullptr;  // the scene whose box sceneBox_ holds
    scene::Aabb sceneBox_;
};

}  // namespace idk::frame
