// transparency_feature.hpp: BLEND surfaces, sorted back to front on the CPU each frame (render/blend_draws.hpp)
// and forward-shaded over the lit image (passes/transparency.cpp). Exists only for scenes with BLEND draws.
#pragma once
#include <memory>

#include "frame/frame_context.hpp"
#include "render/blend_draws.hpp"
#include "render/gpu_scene.hpp"

namespace idk::frame {

class TransparencyFeature {
public:
    void setScene(vk::Context& ctx, const render::GpuScene& scene, uint32_t framesInFlight);
    bool enabled() const noexcept { return draws_ != nullptr; }
    void addPasses(FrameContext& f, const render::GpuScene& scene);  // blends into f.hdr

private:
    std::unique_ptr<render::BlendDraws> draws_;
};

}  // namespace idk::frame
