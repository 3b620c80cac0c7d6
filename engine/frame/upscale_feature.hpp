// upscale_feature.hpp: the temporal upscaler (--aa taa --upscale S with S < 1; --aa upscale). beginFrame shrinks the frame to the
// render size (S x output, each dimension) before anything is recorded: the graph sizes its output-relative
// images and the frame's passes from it, and the temporal feature jitters the projection over a Halton sequence
// lengthened by 1 / S^2 (each output pixel then sees as many samples as with TAA). keepOpaque snapshots the lit
// image before transparency (the reactive term). addResolve reconstructs the output-size image from this frame's
// samples and the reprojected history (passes/upscale.cpp) and grows the frame back to the output size, so bloom
// and the tonemap run at output size. Nothing is allocated or dispatched unless the upscaler runs (frame::upscalerRuns). Plays the role of
// IDKEngine's FSR2 path (reference 2.5: FSR2 renders at a lower resolution and upscales before bloom/tonemap).
#pragma once
#include "frame/frame_context.hpp"

namespace idk::frame {

class UpscaleFeature {
public:
    static bool enabled(const render::RenderSettings& s);
    // The render size of an output of width x height at scale s.temporal.upscale (each at least 1 pixel).
    static VkExtent2D renderExtent(const render::RenderSettings& s, uint32_t width, uint32_t height);

    void beginFrame(FrameContext& f);                  // f.width, f.height = render size
    void keepOpaque(FrameContext& f, bool transparent);  // before transparency blends into f.hdr
    void addResolve(FrameContext& f);                  // f.hdr at output size; f.width, f.height = output size

private:
    VkExtent2D output_{};
    graph::TextureHandle opaque_;
};

}  // namespace idk::frame
