// transmission_feature.hpp: KHR_materials_transmission (+ _ior, _volume, _dispersion) in the rasterizer. Transmissive
// primitives that are not BLEND leave the G-buffer (render/gpu_scene.hpp, drawnForward) and are drawn after the
// opaque frame and the sky by the screen-space transmission pass (passes/transmission.cpp), sorted back to front on
// the CPU each frame (render/blend_draws.hpp). `--transmission off` draws them opaque (no opaque-colour chain).
// Exists only for scenes with such draws: nothing is allocated or dispatched otherwise.
#pragma once
#include <memory>

#include "frame/frame_context.hpp"
#include "render/blend_draws.hpp"
#include "render/gpu_scene.hpp"

namespace idk::frame {

class TransmissionFeature {
public:
    void setScene(vk::Context& ctx, const render::GpuScene& scene, uint32_t framesInFlight);
    bool enabled() const noexcept { return draws_ != nullptr; }
    void addPasses(FrameContext& f, const render::GpuScene& scene);  // draws over f.hdr

private:
    std::unique_ptr<render::BlendDraws> draws_;
};

}  // namespace idk::frame
