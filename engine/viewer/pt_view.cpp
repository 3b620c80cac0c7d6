// pt_view.cpp: the viewer's path-traced mode (pt_view.hpp): restart rules, progressive accumulation through
// PathTracer::beginProgressive / accumulate / resolveProgressive, and the displayed image.
#include "viewer/pt_view.hpp"

#include <memory>
#include <stdexcept>

#include "app/render_pathtrace.hpp"
#include "render/vk_graph_backend.hpp"
#include "vk/blit.hpp"
#include "vk/transfer.hpp"

namespace idk::viewer {

PtView::~PtView() {
    if (image_) ctx_.destroyDeferred(image_);  // the last frame may still copy from it
}

bool PtView::same(const TracerKey& a, const TracerKey& b) {
    const render::AtmosphereSettings &x = a.atmosphere, &y = b.atmosphere;
    return a.denoise == b.denoise && a.environment == b.environment && a.environmentIntensity == b.environmentIntensity &&
           x.enabled == y.enabled && x.sunElevation == y.sunElevation && x.sunAzimuth == y.sunAzimuth &&
           x.sunIntensity == y.sunIntensity && x.width == y.width;
}

bool PtView::same(const ImageKey& a, const ImageKey& b) {
    // Exact comparisons: any change of the camera, however small, is another image.
    const scene::CameraView &c = a.camera, &d = b.camera;
    return c.position == d.position && c.forward == d.forward && c.up == d.up && c.type == d.type && c.yfov == d.yfov &&
           c.aspectRatio == d.aspectRatio && c.znear == d.znear && c.zfar == d.zfar && c.xmag == d.xmag &&
           c.ymag == d.ymag && a.width == b.width && a.height == b.height && a.sceneTime == b.sceneTime &&
           a.maxDepth == b.maxDepth && a.seed == b.seed;
}

void PtView::update(const scene::Scene& scene, double sceneTime, const scene::CameraView& camera, uint32_t width,
                    uint32_t height, const PtViewSettings& settings, const render::RenderSettings& raster,
                    uint64_t previousFrame) {
    const TracerKey tracerKey{settings.denoise, raster.environment, raster.environmentIntensity, raster.atmosphere};
    if (!tracer_ || !same(tracerKey, tracerKey_)) {
        tracer_.reset();
        imageKey_.reset();
        render::PathTracerOptions options;  // as `idk render --pathtrace` builds them (app::pathTraceFromCli)
        options.denoise = settings.denoise;
        options.environment = raster.environment;
        options.environmentIntensity = raster.environmentIntensity;
        options.atmosphere = raster.atmosphere;
        options.samplesPerBatch = 1;  // one submission per sample: a frame never waits for more than it asked for
        tracer_ = std::make_unique<render::PathTracer>(ctx_, shaders_, scene, options);
        tracerKey_ = tracerKey;
    }
    // The time only matters to a scene that moves with it.
    const ImageKey key{camera, width, height, scene.animations.empty() ? 0.0 : sceneTime, settings.maxDepth, settings.seed};
    if (!imageKey_ || !same(key, *imageKey_)) {
        if (imageKey_ && !scene.animations.empty() && key.sceneTime != imageKey_->sceneTime && error_.empty()) {
            try {
                tracer_->setPose(scene);
            } catch (const std::invalid_argument& e) {
                // e.g. a moving emissive mesh (its light entries are world-space triangles): keep the pose the
                // tracer has and say why in the panel.
                error_ = e.what();
            }
        }
        render::PathTraceSettings pt;
        pt.maxDepth = settings.maxDepth;
        pt.seed = settings.seed;
        tracer_->beginProgressive(camera, width, height, pt);
        imageKey_ = key;
        ++restarts_;
    }
    samples_ = tracer_->accumulate(settings.samplesPerFrame);
    const render::PathTraceResult result = tracer_->resolveProgressive();
    // Linear radiance -> the bytes `idk render --pathtrace --out F.png` writes (exposure, AgX, sRGB). On a real GPU
    // this read-back and upload would be a tonemap pass on the tracer's own image; at the viewer's sizes the
    // round trip costs little next to the samples (and the raster frame under it still renders: its timings
    // stay in the Frame panel).
    bytes_ = app::displayBytes(result.didDenoise ? result.denoised : result.image, raster.exposure);

    ctx_.waitFor(previousFrame);  // that frame's copy from image_ has finished: overwriting it is safe
    if (!image_ || image_.extent.width != width || image_.extent.height != height) {
        if (image_) ctx_.destroy(image_);
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_R8G8B8A8_UNORM;  // the bytes are sRGB codes; the copy is a blit, no conversion
        desc.extent = {width, height, 1};
        desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;  // only copied from, but createImage makes a view, which needs one
        desc.name = "viewer path-traced image";
        desc.category = "render targets";
        image_ = ctx_.createImage(desc);
    }
    vk::uploadImage(ctx_, image_, bytes_.data(), bytes_.size(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

graph::TextureHandle PtView::addPass(graph::RenderGraph& graph, graph::TextureHandle target) const {
    if (!image_) throw std::logic_error("PtView::addPass before update");
    // uploadImage waited for its submission: the contents are visible, nothing to wait on.
    graph::ResourceState uploaded;
    uploaded.layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const graph::TextureHandle source = graph.importTexture("path-traced image", render::physicalOf(image_), uploaded);
    auto written = std::make_shared<graph::TextureHandle>();
    const VkExtent3D extent = image_.extent;
    graph.addPass(
        "pathtrace_blit",
        [&](graph::PassBuilder& b) {
            b.read(source, graph::Access::TransferSrc);
            *written = b.write(target, graph::Access::TransferDst);
        },
        [source, written, extent](graph::PassContext& pc) {
            vk::blitSameSize(pc.commandBuffer(), pc.image(source), pc.image(*written), extent.width, extent.height);
        });
    return *written;
}

const std::vector<uint8_t>& PtView::displayed(uint32_t& width, uint32_t& height) const {
    width = image_ ? image_.extent.width : 0;
    height = image_ ? image_.extent.height : 0;
    return bytes_;
}

}  // namespace idk::viewer
