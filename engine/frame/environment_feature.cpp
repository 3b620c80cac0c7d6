// environment_feature.cpp: loads, swaps and imports the frame's environment map (see environment_feature.hpp).
#include "frame/environment_feature.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/log.hpp"
#include "frame/frame_inputs.hpp"
#include "render/atmosphere.hpp"
#include "vk/check.hpp"

namespace idk::frame {

EnvironmentFeature::~EnvironmentFeature() {
    if (environment_) render::destroyEnvironment(ctx_, *environment_);
}

const render::GpuEnvironment& EnvironmentFeature::current(const render::RenderSettings& settings) {
    // With intensity 0 nothing samples the map's contents: a 1x1 stand-in instead of the file (model only what
    // the frame needs); loaded for real once the intensity becomes nonzero.
    const bool needed = settings.environmentIntensity != 0.0f;
    if (environment_ && (!needed || (loaded_ && atmosphere_ == settings.atmosphere.enabled))) return *environment_;
    if (environment_) render::destroyEnvironment(ctx_, *environment_);
    loaded_ = needed;
    atmosphere_ = false;
    if (!needed) return *(environment_ = render::createEnvironment(ctx_, {}));
    std::filesystem::path file = settings.environment.value_or(render::defaultEnvironmentPath());
    try {
        environment_ = render::createEnvironment(ctx_, file);
    } catch (const vk::Error&) {
        throw;  // a device failure (lost, out of memory) is not a bad environment file
    } catch (const std::runtime_error& e) {
        core::logWarning("environment: ", e.what(), "; using a constant grey environment instead");
        environment_ = render::createEnvironment(ctx_, {});
    }
    return *environment_;
}

void EnvironmentFeature::bakeSky(FrameContext& f) {
    const render::AtmosphereSettings& a = f.settings.atmosphere;
    const glm::vec4 key(a.sunElevation, a.sunAzimuth, a.sunIntensity, float(a.width));
    if (environment_ && atmosphere_ && key == skyKey_) return;  // the sun has not moved
    core::ImageRgba32f sky = render::bakeSky(ctx_, f.shaders, a);
    if (environment_) render::destroyEnvironment(ctx_, *environment_);
    environment_ = render::createEnvironment(ctx_, std::move(sky), "atmosphere");
    loaded_ = atmosphere_ = true;
    skyKey_ = key;
    ++skyBakes_;
}

void EnvironmentFeature::addPasses(FrameContext& f) {
    if (f.settings.atmosphere.enabled && f.settings.environmentIntensity != 0.0f) bakeSky(f);
    graph::ResourceState sampled;
    sampled.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    f.environment = f.graph.importTexture("environment", render::physicalOf(current(f.settings).image), sampled,
                                          graph::FinalUse{graph::Access::SampledRead});
}

}  // namespace idk::frame
