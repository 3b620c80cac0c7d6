// transparency_feature.cpp: sorts the BLEND draws for this frame's eye and adds the transparency pass.
#include "frame/transparency_feature.hpp"

#include "frame/frame_inputs.hpp"

namespace idk::frame {

void TransparencyFeature::setScene(vk::Context& ctx, const render::GpuScene& scene, uint32_t framesInFlight) {
    draws_.reset();
    if (render::blendDrawCount(scene.data()) > 0)
        draws_ = std::make_unique<render::BlendDraws>(ctx, scene.data(), framesInFlight);
}

void TransparencyFeature::addPasses(FrameContext& f, const render::GpuScene& scene) {
    if (!draws_) return;
    // Sorted for this frame's eye into this slot's host-visible indirect buffer.
    const vk::Buffer& sorted = draws_->sort(f.slot, scene.data(), f.camera.position);
    passes::TransparencyInputs t{f.scene,    importBuffer(f.graph, "sorted blend draws", sorted),
                                 draws_->count(), f.frameConstants, f.gbuffer.depth, f.environment,
                                 f.pointShadows, {}};
    switch (f.settings.oit) {
        case render::OitMode::Weighted:
            f.hdr = passes::addWeightedOitPasses(f.graph, f.ctx, f.shaders, t, f.hdr, &f.log);
            break;
        case render::OitMode::Layers:
            f.hdr = passes::addLayeredOitPasses(f.graph, f.ctx, f.shaders, t, f.hdr, &f.log);
            break;
        case render::OitMode::Sorted:
            // --gi vxgi: the fragments inside the grid trace cones (the OIT rungs keep the SH ambient, see
            // transparency/forward_body.h).
            t.vxgi = f.vxgiCones;
            f.hdr = passes::addTransparencyPass(f.graph, f.ctx, f.shaders, t, f.hdr, &f.log);
            break;
    }
}

}  // namespace idk::frame
