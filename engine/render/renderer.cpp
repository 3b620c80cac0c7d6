// renderer.cpp: runs frames: the deferred PBR frame (the recipe of frame/frame_recipe.cpp) and the foundation's
// Lambert frame, both into an imported target that the graph leaves ready for the readback copy (renderOffscreen)
// or that is blitted into the caller's image before the caller's own passes (renderFrame, the viewer's swapchain
// path). Ports the frame loop of IDKEngine's RasterPipeline.Render.
#include "render/renderer.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "vk/blit.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
Renderer::Renderer(vk::Context& ctx, vk::ShaderLibrary& shaders, RenderSettings settings)
    : ctx_(ctx),
      shaders_(shaders),
      settings_(std::move(settings)),
      backend_(ctx),
      pool_(backend_),
      frames_(ctx),
      features_(ctx) {}

Renderer::~Renderer() {
    ctx_.waitIdle();
    if (sceneImage_) ctx_.destroy(sceneImage_);
    if (hasLambertScene_) destroyLambertScene(ctx_, lambertScene_);
    gpuScene_.reset();
}

void Renderer::setScene(const scene::Scene& scene) {
    if (settings_.shading == Shading::Lambert) {
        if (hasLambertScene_) destroyLambertScene(ctx_, lambertScene_);
        lambertScene_ = uploadLambertScene(ctx_, packLambertScene(scene));
        hasLambertScene_ = true;
        return;
    }
    features_.pointShadows.reset();  // before the scene whose draws the cubes' resources copied
    gpuScene_.reset();
    gpuScene_ = std::make_unique<GpuScene>(ctx_, scene);
    features_.setScene(ctx_, *gpuScene_, frames_.framesInFlight());
    features_.setSourceScene(ctx_, scene, *gpuScene_, settings_);
}

void Renderer::prepareSourceScene(const scene::Scene& scene) {
    if (gpuScene_) features_.rtShadows.ensureGeometry(ctx_, scene, *gpuScene_, settings_);
}

void Renderer::setPose(const scene::Scene& scene) {
    if (gpuScene_ && gpuScene_->animation()) gpuScene_->animation()->setPose(scene);
}

frame::FrameContext Renderer::frameContext(graph::RenderGraph& graph, const scene::CameraView& camera, uint32_t width,
                                           uint32_t height, passes::IndirectDrawLog& log) {
    frame::FrameContext f{ctx_, shaders_, graph, log, settings_};
    f.camera = camera;
    f.width = width;
    f.height = height;
    f.slot = frames_.slotIndex();  // begin() has waited until the GPU finished the slot's previous frame
    f.framesInFlight = frames_.framesInFlight();
    f.viewProjection = scene::projectionMatrix(camera, float(width) / float(height)) * scene::viewMatrix(camera);
    return f;
}

graph::TextureHandle Renderer::renderPbr(graph::RenderGraph& graph, const scene::CameraView& camera, uint32_t width,
                                         uint32_t height, const vk::Image& target, passes::IndirectDrawLog& log) {
    frame::FrameContext f = frameContext(graph, camera, width, height, log);
    graph::PhysicalTexture output = physicalOf(target);
    output.storageIndex = outputStorage_.value;
    // Its first layout transition waits on every earlier stage: the validation layer counts each compute
    // dispatch that binds the bindless storage array (e.g. the Hi-Z pyramid of --culling hiz, before lighting) as
    // reading this storage image, and the transition must not race those reads.
    graph::ResourceState fresh;
    fresh.readStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    f.output = graph.importTexture("output", output, fresh, graph::FinalUse{graph::Access::TransferSrc});
    return frame::recordPbrFrame(f, *gpuScene_, features_);
}

FrameResult Renderer::renderOffscreen(const scene::CameraView& camera, uint32_t width, uint32_t height) {
    const bool pbr = settings_.shading == Shading::Pbr;
    if (pbr ? !gpuScene_ : !hasLambertScene_) throw std::logic_error("Renderer::renderOffscreen: call setScene first");
    const bool display = pbr && settings_.output == OutputKind::Display;

    vk::ImageDesc desc;
    desc.format = display ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.extent = {width, height, 1};
    // Display: the tonemap pass's colour attachment. Hdr: the lighting and sky passes' storage image.
    desc.usage = pbr && !display ? VK_IMAGE_USAGE_STORAGE_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if (pbr && features_.transparency.enabled()) desc.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;  // Hdr: transparency blends into it
    if (pbr && features_.transmission.enabled()) desc.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;  // and transmission
    if (pbr && frame::VrsFeature::usesHardwareRung(ctx_, settings_.vrs))
        desc.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;  // Hdr: the hardware-VRS lighting pass renders into it
    desc.name = "offscreen output";
    desc.category = "render targets";
    vk::Image target = ctx_.createImage(desc);
    if (pbr && !display) outputStorage_ = ctx_.bindless().addStorage(target.view);
    struct ReleaseOnExit {
        Renderer& r;
        vk::Image& image;
        ~ReleaseOnExit() {
            if (r.outputStorage_.value != UINT32_MAX) r.ctx_.bindless().release(r.outputStorage_);
            r.outputStorage_ = {};
            r.ctx_.destroyDeferred(image);
        }
    } guard{*this, target};

    hasTimings_ = false;  // this frame's timestamps replace renderFrame's
    VkCommandBuffer cmd = frames_.begin();
    graph::RenderGraph graph(pool_, {width, height});
    passes::IndirectDrawLog log;
    FrameResult result;
    try {
        if (beforeFrame_) beforeFrame_(cmd);  // e.g. TextureStreamer::pump: ready textures patch this frame
        if (pbr) {
            renderPbr(graph, camera, width, height, target, log);
        } else {
            graph::TextureHandle output = graph.importTexture("output", physicalOf(target), graph::ResourceState{},
                                                              graph::FinalUse{graph::Access::TransferSrc});
            passes::LambertSettings settings;
            settings.colorFormat = desc.format;
            float aspect = float(width) / float(height);
            settings.viewProjection = scene::projectionMatrix(camera, aspect) * scene::viewMatrix(camera);
            graph.markOutput(passes::addLambertPass(graph, ctx_, shaders_, lambertScene_, output, settings).color);
        }
        graph.compile();
        result.passesRun = graph.executionOrder();
        result.graphText = graph.toText();
        result.graphDot = graph.toGraphviz();
        graph.execute(cmd);
    } catch (...) {
        // Submit what was recorded so the frame slot stays usable (not after a device loss: the original error
        // is the one to report, and the context is being torn down).
        if (!ctx_.deviceLost()) ctx_.waitFor(frames_.end());
        throw;
    }
    ctx_.waitFor(frames_.end());
    result.passTimes = backend_.passTimings();
    result.indirectDraws = log.entries;
    if (pbr) result.shadingInvocations = features_.vrs.lastShadingInvocations();
    if (pbr) result.culling = cullingStats();
    if (pbr) result.geometryPath = features_.culling.lastGeometryPath();
    if (pbr) result.skyBakes = features_.environment.skyBakes();

    std::vector<uint8_t> bytes = vk::readbackImage(ctx_, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    result.image.width = width;
    result.image.height = height;
    result.image.pixels.resize(size_t(width) * height * 4);
    if (display) {
        for (size_t i = 0; i < result.image.pixels.size(); ++i) {
            float v = float(bytes[i]) / 255.0f;
            result.image.pixels[i] = i % 4 == 3 ? v : core::srgbToLinear(v);
        }
        result.display = std::move(bytes);
    } else {
        const auto* halves = reinterpret_cast<const uint16_t*>(bytes.data());
        for (size_t i = 0; i < result.image.pixels.size(); ++i) result.image.pixels[i] = glm::unpackHalf1x16(halves[i]);
    }
    return result;
}

std::vector<passes::CullingViewStats> Renderer::cullingStats() const {
    std::vector<passes::CullingViewStats> views = features_.culling.lastStats();
    // then each point-shadow cube face's counters (frame/shadow_culling.hpp)
    for (passes::CullingViewStats& v : features_.pointShadows.cullStats()) views.push_back(std::move(v));
    return views;
}

FrameResult Renderer::renderStill(const scene::CameraView& camera, uint32_t width, uint32_t height) {
    uint32_t frames = settings_.shading == Shading::Pbr ? frame::TemporalFeature::stillFrames(settings_) : 1;
    // VRS shades at the rates the previous frame classified: a first frame classifies, as the viewer's would.
    if (settings_.shading == Shading::Pbr && settings_.vrs.enabled) frames = std::max(frames, 2u);
    // SSR reflects the previous frame's lit image (frame/ssr_feature.hpp): a first frame lights the scene.
    if (settings_.shading == Shading::Pbr && settings_.ssr.enabled) frames = std::max(frames, 2u);
    // The passes of the still's earlier frames (uploads and skinning run in the first only): --stats lists them too.
    std::vector<std::string> earlier;
    auto note = [&](const std::vector<std::string>& passes) {
        for (const std::string& p : passes)
            if (std::find(earlier.begin(), earlier.end(), p) == earlier.end()) earlier.push_back(p);
    };
    // Two-phase occlusion draws early what the frame before found visible. From cold it takes two frames: the
    // first one's early phase draws nothing, so its late phase tests against an empty pyramid and marks everything
    // in the frustum visible; the second draws all that early, and its late phase marks only what is really
    // visible, which the next draws early. The features' frames below count towards the two; the G-buffer-only
    // warm-ups come first, so those frames' histories (SSR's lit image, TAA, VRS rates) chain without a gap.
    if (settings_.shading == Shading::Pbr && settings_.culling.mode == frame::CullingMode::Hiz && !settings_.culling.freeze)
        for (uint32_t i = frames - 1; i < 2; ++i) note(warmUpCulling(camera, width, height));
    if (frames > 1) features_.temporal.resetHistory();
    for (uint32_t i = 1; i < frames; ++i) note(renderOffscreen(camera, width, height).passesRun);
    FrameResult result = renderOffscreen(camera, width, height);
    // VXGI's gl-interop rung drops the fragments past its record buffer in a frame that overflows it and grows the
    // buffer to hold them (passes/vxgi_gl_accumulate.hpp): a still renders that frame again, whole.
    if (const passes::VxgiGlAccumulator* gl = features_.vxgi.glAccumulator(); gl && gl->lastStats().dropped) {
        note(result.passesRun);
        result = renderOffscreen(camera, width, height);
    }
    // The returned frame's passes, after those that ran only in earlier frames of the still.
    std::vector<std::string> passes;
    for (const std::string& p : earlier)
        if (std::find(result.passesRun.begin(), result.passesRun.end(), p) == result.passesRun.end()) passes.push_back(p);
    passes.insert(passes.end(), result.passesRun.begin(), result.passesRun.end());
    result.passesRun = std::move(passes);
    return result;
}

std::vector<glm::uvec2> Renderer::renderSurfaceIds(const scene::CameraView& camera, uint32_t width, uint32_t height) {
    if (settings_.shading != Shading::Pbr || !gpuScene_)
        throw std::logic_error("Renderer::renderSurfaceIds: needs PBR shading and a scene");
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R32G32_UINT;
    desc.extent = {width, height, 1};
    desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;  // readback source (TRANSFER_SRC is implied)
    desc.name = "surface ids";
    desc.category = "render targets";
    vk::Image target = ctx_.createImage(desc);
    struct DestroyOnExit {
        vk::Context& ctx;
        vk::Image& image;
        ~DestroyOnExit() { ctx.destroyDeferred(image); }
    } guard{ctx_, target};
    runPartialFrame(camera, width, height, [&](frame::FrameContext& f) {
        graph::TextureHandle ids = f.graph.importTexture("surface ids", physicalOf(target), graph::ResourceState{},
                                                         graph::FinalUse{graph::Access::TransferSrc});
        frame::recordSurfaceIds(f, *gpuScene_, features_, ids);
    });
    const std::vector<uint8_t> bytes = vk::readbackImage(ctx_, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    std::vector<glm::uvec2> ids(size_t(width) * height);
    std::memcpy(ids.data(), bytes.data(), std::min(bytes.size(), ids.size() * sizeof(glm::uvec2)));
    return ids;
}

std::vector<std::string> Renderer::warmUpCulling(const scene::CameraView& camera, uint32_t width, uint32_t height) {
    if (!gpuScene_) throw std::logic_error("Renderer::renderStill: call setScene first");
    return runPartialFrame(camera, width, height, [&](frame::FrameContext& f) { frame::recordCullingWarmup(f, *gpuScene_, features_); });
}

// One graph of part of the frame (what `record` declares), in a frame slot, waited for; returns the passes that
// ran. Its timestamps are not reported (the next full frame's replace them).
std::vector<std::string> Renderer::runPartialFrame(const scene::CameraView& camera, uint32_t width, uint32_t height,
                               const std::function<void(frame::FrameContext&)>& record) {
    std::vector<std::string> passes;
    VkCommandBuffer cmd = frames_.begin();
    graph::RenderGraph graph(pool_, {width, height});
    passes::IndirectDrawLog log;
    try {
        if (beforeFrame_) beforeFrame_(cmd);
        frame::FrameContext f = frameContext(graph, camera, width, height, log);
        record(f);
        graph.compile();
        graph.execute(cmd);
        passes = graph.executionOrder();
    } catch (...) {
        if (!ctx_.deviceLost()) ctx_.waitFor(frames_.end());  // the frame slot stays usable (see renderOffscreen)
        throw;
    }
    ctx_.waitFor(frames_.end());
    hasTimings_ = false;
    return passes;
}

// ---- renderFrame: the viewer's path (same frame graph, no readback, caller's passes after it) ----

FrameInfo Renderer::renderFrame(const scene::CameraView& camera, const FrameTarget& target) {
    if (settings_.shading != Shading::Pbr || settings_.output != OutputKind::Display)
        throw std::logic_error("Renderer::renderFrame: needs PBR shading with Display output");
    if (!gpuScene_) throw std::logic_error("Renderer::renderFrame: call setScene first");
    const uint32_t width = target.image.extent.width, height = target.image.extent.height;
    if (width == 0 || height == 0) throw std::logic_error("Renderer::renderFrame: the target has no pixels");

    // The backend keeps one set of timestamp queries: wait for the previous frame so its timings can be read
    // before this frame resets them (the viewer trades CPU/GPU overlap for per-pass timings every frame).
    FrameInfo info;
    ctx_.waitFor(lastFrameValue_);
    if (hasTimings_) {
        info.passTimes = backend_.passTimings();
        info.culling = cullingStats();  // read before this frame's culling passes are recorded
        info.geometryPath = features_.culling.lastGeometryPath();
    }

    if (!sceneImage_ || sceneImage_.extent.width != width || sceneImage_.extent.height != height) {
        if (sceneImage_) ctx_.destroyDeferred(sceneImage_);
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_R8G8B8A8_UNORM;  // what renderOffscreen's Display path renders into
        desc.extent = {width, height, 1};
        desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;  // tonemap target; blit source (TRANSFER_SRC is implied)
        desc.name = "viewer scene image";
        desc.category = "render targets";
        sceneImage_ = ctx_.createImage(desc);
    }

    VkCommandBuffer cmd = frames_.begin();
    graph::RenderGraph graph(pool_, {width, height});
    passes::IndirectDrawLog log;
    try {
        if (beforeFrame_) beforeFrame_(cmd);
        graph::TextureHandle scene = renderPbr(graph, camera, width, height, sceneImage_, log);
        graph::TextureHandle out = graph.importTexture("frame target", target.image, target.initial, target.finalUse);
        auto blitted = std::make_shared<graph::TextureHandle>();
        graph.addPass(
            "present_blit",
            [&](graph::PassBuilder& b) {
                b.read(scene, graph::Access::TransferSrc);
                *blitted = b.write(out, graph::Access::TransferDst);
            },
            [scene, blitted, width, height](graph::PassContext& pc) {
                vk::blitSameSize(pc.commandBuffer(), pc.image(scene), pc.image(*blitted), width, height);
            });
        graph::TextureHandle last = *blitted;
        if (target.addPasses) last = target.addPasses(graph, last);
        graph.markOutput(last);
        graph.compile();
        info.passesRun = graph.executionOrder();
        graph.execute(cmd);
    } catch (...) {
        if (!ctx_.deviceLost()) lastFrameValue_ = frames_.end();  // the frame slot stays usable (see above)
        hasTimings_ = false;
        throw;
    }
    lastFrameValue_ = frames_.end(target.waits, target.signals);
    info.timelineValue = lastFrameValue_;
    hasTimings_ = true;
    return info;
}

std::vector<uint8_t> Renderer::readLastFrame(uint32_t& width, uint32_t& height) {
    width = height = 0;
    if (!sceneImage_ || lastFrameValue_ == 0) return {};
    ctx_.waitFor(lastFrameValue_);
    width = sceneImage_.extent.width;
    height = sceneImage_.extent.height;
    return vk::readbackImage(ctx_, sceneImage_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

}  // namespace idk::render
