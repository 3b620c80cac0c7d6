// environment_feature.hpp: the frame's equirectangular environment (sky, ambient SH, split-sum specular): loaded
// from RenderSettings::environment when first needed, replaced by a 1x1 stand-in while the intensity is 0 (nothing
// samples it then), or with `--sky atmosphere` the single-scattering sky baked on the GPU (render/atmosphere.hpp)
// whenever the sun settings change (not every frame); imported into each frame's graph as
// FrameContext::environment.
#pragma once
#include <optional>

#include "frame/frame_context.hpp"
#include "render/environment.hpp"
#include <glm/glm.hpp>

namespace idk::frame {

class EnvironmentFeature {
public:
    explicit EnvironmentFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~EnvironmentFeature();
    EnvironmentFeature(const EnvironmentFeature&) = delete;
    EnvironmentFeature& operator=(const EnvironmentFeature&) = delete;

    // The environment the settings ask for (loads or swaps it as they change).
    const render::GpuEnvironment& current(const render::RenderSettings& settings);
    void addPasses(FrameContext& f);  // bakes the sky if it is asked for and stale; imports current() as f.environment
    uint32_t skyBakes() const noexcept { return skyBakes_; }  // atmosphere bakes so far (tests: once per sun move)

private:
    vk::Context& ctx_;
    std::optional<render::GpuEnvironment> environment_;
    bool loaded_ = false;  // environment_ holds the configured map (not the intensity-0 stand-in)
    bool atmosphere_ = false;  // environment_ is a baked sky, for skyKey_ (sun elevation, azimuth, intensity, size)
    glm::vec4 skyKey_{0.0f};
    uint32_t skyBakes_ = 0;
    void bakeSky(FrameContext& f);
};

}  // namespace idk::frame
