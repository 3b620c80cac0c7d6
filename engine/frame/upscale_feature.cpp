// upscale_feature.cpp: render-size frames and the output-size reconstruction of the temporal upscaler (see
// upscale_feature.hpp).
#include "frame/upscale_feature.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "passes/temporal_passes.hpp"

namespace idk::frame {
namespace {

// The Gaussian sample kernel's standard deviation, in output pixels: about the 1-pixel box's (0.29), the filter of
// TAA and of the supersampled reference. Chosen on tests/gpu/temporal/upscale_test.cpp's Cornell box (still RMSE
// at S = 0.5 / S = 1): sigma 0.25: 0.0095 / 0.0102, 0.3: 0.0094 / 0.0096, 0.35: 0.0119 / 0.0109, 0.4: 0.0153 / 0.0135.
constexpr float kSampleSigma = 0.3f;

}  // namespace

bool UpscaleFeature::enabled(const render::RenderSettings& s) { return upscalerRuns(s.temporal); }

VkExtent2D UpscaleFeature::renderExtent(const render::RenderSettings& s, uint32_t width, uint32_t height) {
    const float scale = std::clamp(s.temporal.upscale, 0.5f, 1.0f);
    const auto scaled = [scale](uint32_t n) { return std::max(1u, uint32_t(std::lround(double(n) * scale))); };
    return {scaled(width), scaled(height)};
}

void UpscaleFeature::beginFrame(FrameContext& f) {
    opaque_ = {};
    if (!enabled(f.settings)) return;
    output_ = {f.width, f.height};
    const VkExtent2D render = renderExtent(f.settings, f.width, f.height);
    f.width = render.width;
    f.height = render.height;
    f.graph.setRelativeExtent(render);
}

void UpscaleFeature::keepOpaque(FrameContext& f, bool transparent) {
    if (!enabled(f.settings) || !transparent) return;
    graph::TextureDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    const graph::TextureHandle source = f.hdr;
    auto target = std::make_shared<graph::TextureHandle>();
    f.graph.addPass(
        "upscale_keep_opaque",
        [&](graph::PassBuilder& b) {
            b.read(source, graph::Access::TransferSrc);
            *target = b.write(b.create("upscale opaque", desc), graph::Access::TransferDst);
        },
        [source, target](graph::PassContext& pc) {
            const VkExtent3D extent = pc.texture(source).extent;
            VkImageCopy region{};
            region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.dstSubresource = region.srcSubresource;
            region.extent = extent;
            vkCmdCopyImage(pc.commandBuffer(), pc.image(source), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           pc.image(*target), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        });
    opaque_ = *target;
}

void UpscaleFeature::addResolve(FrameContext& f) {
    if (!enabled(f.settings)) return;
    passes::UpscaleInputs in;
    in.temporal = f.temporalConstants;
    in.color = f.hdr;
    in.depth = f.gbuffer.depth;
    in.motion = f.motionVectors;
    in.opaque = opaque_;
    in.outputExtent = output_;
    in.reset = f.temporalReset;
    in.frameStatic = f.temporalStatic;
    // The accumulated weight counts samples by their proximity (about S^2 per frame on average), so TAA's cap of
    // `frames` full samples also spans the 1 / S^2 longer jitter sequence.
    in.maxWeight = float(std::max(f.settings.temporal.frames, 1u));
    in.clipGamma = f.settings.temporal.clipGamma;
    in.sigma = kSampleSigma;
    // Back to the output size: the target, bloom and the tonemap are output-sized.
    f.graph.setRelativeExtent(output_);
    f.width = output_.width;
    f.height = output_.height;
    if (f.settings.output == render::OutputKind::Display) {
        graph::TextureDesc desc;
        desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        in.target = f.graph.createTexture("upscaled radiance", desc);
    } else {
        in.target = f.output;  // Hdr: the lit image was a render-size transient (frame_recipe.cpp hdrTarget)
    }
    f.hdr = passes::addUpscalePasses(f.graph, f.ctx, f.shaders, in);
}

}  // namespace idk::frame
