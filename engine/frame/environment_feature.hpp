// environment_feature.hpp: the frame's equirectangular environment (sky, ambient SH, split-sum specular): loaded
// from RenderSettings::environment when first needed, replaced by a 1x1 stand-in while the intensity is 0 (nothing
// samples it then), and imported into each frame's graph as FrameContext::environment.
#pragma once
#include <optional>

#include "frame/frame_context.hpp"
#include "render/environment.hpp"

namespace idk::frame {

class EnvironmentFeature {
public:
    explicit EnvironmentFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~EnvironmentFeature();
    EnvironmentFeature(const EnvironmentFeature&) = delete;
    EnvironmentFeature& operator=(const EnvironmentFeature&) = delete;

    // The environment the settings ask for (loads or swaps it as they change).
    const render::GpuEnvironment& current(const render::RenderSettings& settings);
    void addPasses(FrameContext& f);  // imports current() as f.environment

private:
    vk::Context& ctx_;
    std::optional<render::GpuEnvironment> environment_;
    bool loaded_ = false;  // environment_ holds the configured map (not the intensity-0 stand-in)
};

}  // namespace idk::frame
