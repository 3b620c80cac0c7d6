// transmission_feature.cpp: sorts the transmissive draws for this frame's eye and adds the transmission passes.
#include "frame/transmission_feature.hpp"

#include "frame/frame_inputs.hpp"

namespace idk::frame {

void TransmissionFeature::setScene(vk::Context& ctx, const render::GpuScene& scene, uint32_t framesInFlight) {
    draws_.reset();
    if (render::blendDrawCount(scene.data(), render::ForwardDraws::Transmission) > 0)
        draws_ = std::make_unique<render::BlendDraws>(ctx, scene.data(), framesInFlight,
                                                      render::ForwardDraws::Transmission);
}

void TransmissionFeature::addPasses(FrameContext& f, const render::GpuScene& scene) {
    if (!draws_) return;
    const vk::Buffer& sorted = draws_->sort(f.slot, scene.data(), f.camera.position);
    const passes::TransparencyInputs t{f.scene,    importBuffer(f.graph, "sorted transmissive draws", sorted),
                                       draws_->count(), f.frameConstants, f.gbuffer.depth, f.environment,
                                       f.pointShadows, {}};
    f.hdr = passes::addTransmissionPasses(f.graph, f.ctx, f.shaders, t, f.hdr, {f.width, f.height},
                                          f.settings.transmission == render::TransmissionMode::Screen, &f.log);
}

}  // namespace idk::frame
