// volumetrics_feature.cpp: the medium's settings into the march/upsample passes. See volumetrics_feature.hpp.
#include "frame/volumetrics_feature.hpp"

#include <algorithm>

#include "render/draw_bounds.hpp"

namespace idk::frame {

void VolumetricsFeature::addPasses(FrameContext& f, const render::GpuScene& scene) {
    const VolumetricSettings& s = f.settings.volumetrics;
    if (!s.enabled || f.lights->empty() || !f.gbuffer.depth.valid()) return;
    if (boundsOf_ != &scene) {  // once per scene: the background's rays end at the far side of the scene box
        sceneBox_ = render::sceneBounds(scene.data(), render::meshBounds(scene.data()));
        boundsOf_ = &scene;
    }
    float far = 1.0f;
    if (!sceneBox_.empty())
        for (int c = 0; c < 8; ++c) {
            glm::vec3 p((c & 1) ? sceneBox_.max.x : sceneBox_.min.x, (c & 2) ? sceneBox_.max.y : sceneBox_.min.y,
                        (c & 4) ? sceneBox_.max.z : sceneBox_.min.z);
            far = std::max(far, glm::distance(p, f.camera.position));
        }
    passes::VolumetricInputs in;
    in.frame = f.frameConstants;
    in.lights = f.scene.lights;
    in.depth = f.gbuffer.depth;
    in.shadows = f.pointShadows;
    in.width = f.width;
    in.height = f.height;
    in.push.scale = s.scale == 4 ? 4u : 2u;
    in.push.steps = std::max(s.steps, 1u);
    in.push.scattering = std::max(s.density, 0.0f);
    in.push.extinction = in.push.scattering;
    in.push.anisotropy = std::clamp(s.anisotropy, -0.99f, 0.99f);
    in.push.maxDistance = far;
    f.hdr = passes::addVolumetricPasses(f.graph, f.ctx, f.shaders, in, f.hdr);
}

}  // namespace idk::frame
