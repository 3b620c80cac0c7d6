// renderer.cpp: the frame graphs: the deferred PBR frame (GPU scene + environment imported, G-buffer, point
// shadows, lighting, sky, transparency, tonemap) and the foundation's Lambert frame, both into an imported target
// that the graph leaves ready for the readback copy (renderOffscreen) or that is blitted into the caller's image
// before the caller's own passes (renderFrame, the viewer's swapchain path). Ports IDKEngine's
// RasterPipeline.Render frame order (reference 1.5, steps 6.6-6.13, 9).
#include "render/renderer.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "core/log.hpp"
#include "pathtrace/albedo_integrator.hpp"
#include "vk/check.hpp"
#include "shared/deferred_types.h"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

graph::PhysicalTexture physicalOf(const vk::Image& image) {
    graph::PhysicalTexture p;
    p.image = image.image;
    p.view = image.view;
    p.format = image.format;
    p.extent = image.extent;
    p.mips = image.mipLevels;
    p.layers = image.layers;
    return p;
}

graph::BufferHandle importBuffer(graph::RenderGraph& graph, const char* name, const vk::Buffer& buffer,
                                 const graph::ResourceState& state = {}) {
    if (!buffer) return {};
    graph::PhysicalBuffer p;
    p.buffer = buffer.buffer;
    p.size = buffer.size;
    p.address = buffer.address;
    return graph.importBuffer(name, p, state);
}

}  // namespace

Renderer::Renderer(vk::Context& ctx, vk::ShaderLibrary& shaders, RenderSettings settings)
    : ctx_(ctx), shaders_(shaders), settings_(std::move(settings)), backend_(ctx), pool_(backend_), frames_(ctx) {}

Renderer::~Renderer() {
    ctx_.waitIdle();
    if (sceneImage_) ctx_.destroy(sceneImage_);
    if (hasLambertScene_) destroyLambertScene(ctx_, lambertScene_);
    gpuScene_.reset();
    if (environment_) destroyEnvironment(ctx_, *environment_);
    for (vk::Buffer& b : frameConstants_) ctx_.destroy(b);
    if (albedoTables_) ctx_.destroy(albedoTables_);
    for (vk::Buffer& b : lightBuffers_)
        if (b) ctx_.destroy(b);
}

void Renderer::setScene(const scene::Scene& scene) {
    if (settings_.shading == Shading::Lambert) {
        if (hasLambertScene_) destroyLambertScene(ctx_, lambertScene_);
        lambertScene_ = uploadLambertScene(ctx_, packLambertScene(scene));
        hasLambertScene_ = true;
        return;
    }
    pointShadows_.reset();
    blendDraws_.reset();
    gpuScene_.reset();
    gpuScene_ = std::make_unique<GpuScene>(ctx_, scene);
    if (blendDrawCount(gpuScene_->data()) > 0)
        blendDraws_ = std::make_unique<BlendDraws>(ctx_, gpuScene_->data(), frames_.framesInFlight());
}

void Renderer::setPose(const scene::Scene& scene) {
    if (gpuScene_ && gpuScene_->animation()) gpuScene_->animation()->setPose(scene);
}

const GpuEnvironment& Renderer::environment() {
    // With intensity 0 nothing samples the map's contents: a 1x1 stand-in instead of the file (model only what
    // the frame needs); loaded for real once the intensity becomes nonzero.
    const bool needed = settings_.environmentIntensity != 0.0f;
    if (environment_ && (!needed || environmentLoaded_)) return *environment_;
    if (environment_) destroyEnvironment(ctx_, *environment_);
    environmentLoaded_ = needed;
    if (!needed) return *(environment_ = createEnvironment(ctx_, {}));
    std::filesystem::path file = settings_.environment.value_or(defaultEnvironmentPath());
    try {
        environment_ = createEnvironment(ctx_, file);
    } catch (const vk::Error&) {
        throw;  // a device failure (lost, out of memory) is not a bad environment file
    } catch (const std::runtime_error& e) {
        core::logWarning("environment: ", e.what(), "; using a constant grey environment instead");
        environment_ = createEnvironment(ctx_, {});
    }
    return *environment_;
}

// updatePointShadowMaps for the frame's light list (the scene's plus the extra lights).
bool Renderer::updateShadowMaps(const std::vector<gpu::GpuLight>& lights) {
    if (extraLights_.empty()) return updatePointShadowMaps(ctx_, *gpuScene_, settings_.pointShadows, pointShadows_);
    std::vector<uint32_t> casters = pointShadowCasters(lights, settings_.pointShadows.maxLights);
    if (casters.empty() || gpuScene_->drawCount() == 0 || settings_.pointShadows.resolution == 0) {
        pointShadows_.reset();
        return false;
    }
    const bool layered = ctx_.ladder("point-shadow cube faces").chosen == vk::Rung::Native;
    if (!pointShadows_ || !pointShadows_->matches(casters, settings_.pointShadows.resolution, layered)) {
        pointShadows_.reset();
        pointShadows_ = std::make_unique<PointShadowMaps>(ctx_, gpuScene_->data(), std::move(casters),
                                                          settings_.pointShadows.resolution, layered);
    }
    return true;
}

graph::TextureHandle Renderer::renderPbr(graph::RenderGraph& graph, const scene::CameraView& camera, uint32_t width,
                                         uint32_t height, const vk::Image& target, passes::IndirectDrawLog& log) {
    const GpuEnvironment& env = environment();
    GpuScene& s = *gpuScene_;
    if (frameConstants_.empty()) {
        for (uint32_t i = 0; i < frames_.framesInFlight(); ++i) {
            vk::BufferDesc desc;
            desc.size = sizeof(gpu::GpuFrame);
            desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
            desc.memory = vk::MemoryUsage::Upload;
            desc.name = "frame constants " + std::to_string(i);
            desc.category = "frame constants";
            frameConstants_.push_back(ctx_.createBuffer(desc));
        }
    }
    if (!albedoTables_) {  // static: written once (the upload waits for its copy) and only read after
        const std::vector<float> tables = pathtrace::albedoTableData();
        vk::BufferDesc desc;
        desc.size = tables.size() * sizeof(float);
        desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        desc.name = "albedo tables";
        desc.category = "frame constants";
        albedoTables_ = ctx_.createBuffer(desc);
        vk::uploadBuffer(ctx_, albedoTables_, tables.data(), desc.size);
    }
    // This frame's slot: begin() has waited until the GPU finished the slot's previous frame.
    const vk::Buffer& frameBuffer = frameConstants_[frames_.slotIndex()];

    gpu::GpuFrame f{};
    float aspect = float(width) / float(height);
    f.viewProjection = scene::projectionMatrix(camera, aspect) * scene::viewMatrix(camera);
    f.inverseViewProjection = glm::inverse(f.viewProjection);
    f.cameraPosition = camera.position;
    f.albedoTables = albedoTables_.address;
    // Extra lights (the viewer's shot lights) join the scene's in a per-slot host-visible copy of the list.
    const std::vector<gpu::GpuLight>& lights = extraLights_.empty() ? s.data().lights : combinedLights_;
    if (!extraLights_.empty()) {
        combinedLights_ = s.data().lights;
        combinedLights_.insert(combinedLights_.end(), extraLights_.begin(), extraLights_.end());
        if (lightBuffers_.size() < frames_.framesInFlight()) lightBuffers_.resize(frames_.framesInFlight());
        vk::Buffer& buffer = lightBuffers_[frames_.slotIndex()];
        const VkDeviceSize bytes = combinedLights_.size() * sizeof(gpu::GpuLight);
        if (!buffer || buffer.size < bytes) {
            if (buffer) ctx_.destroyDeferred(buffer);
            vk::BufferDesc desc;
            desc.size = std::max<VkDeviceSize>(bytes, 64 * sizeof(gpu::GpuLight));
            desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
            desc.memory = vk::MemoryUsage::Upload;
            desc.name = "frame lights " + std::to_string(frames_.slotIndex());
            desc.category = "frame constants";
            buffer = ctx_.createBuffer(desc);
        }
        vk::uploadBuffer(ctx_, buffer, combinedLights_.data(), bytes);
    }
    const vk::Buffer& lightBuffer = extraLights_.empty() ? s.lights() : lightBuffers_[frames_.slotIndex()];
    f.lightCount = uint32_t(lights.size());
    f.lights = lightBuffer ? lightBuffer.address : 0;
    f.extent = glm::uvec2(width, height);
    for (uint32_t k = 0; k < gpu::kShCoefficients; ++k)
        f.irradianceSh[k] = env.irradianceSh[k] * settings_.environmentIntensity;
    f.environmentTexture = env.texture.value;
    f.environmentSampler = env.sampler.value;
    f.environmentMaxLod = env.maxLod;
    f.environmentIntensity = settings_.environmentIntensity;
    f.environmentWidth = env.width;
    f.environmentHeight = env.height;
    vk::uploadBuffer(ctx_, frameBuffer, &f, sizeof(f));  // host-visible: a memcpy, read by this frame's passes

    // Scene buffers: written once at load (their upload ends with a full barrier), except the materials, which
    // scene_update may overwrite: that write must wait for earlier frames' G-buffer reads (WAR).
    passes::SceneBuffers sb;
    const auto readByGBuffer = graph::stateAfterAccess(
        graph::Access::StorageRead, graph::ResourceKind::Buffer,
        VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    // Vertices and instances are rewritten by skinning / pose_upload in animated frames: WAR as for materials.
    sb.vertices = importBuffer(graph, "scene vertices", s.vertices(), readByGBuffer);
    sb.indices = importBuffer(graph, "scene indices", s.indices());
    sb.meshes = importBuffer(graph, "scene meshes", s.meshes());
    sb.instances = importBuffer(graph, "scene instances", s.instances(), readByGBuffer);
    sb.drawCommands = importBuffer(graph, "scene draw commands", s.drawCommands());
    // The deferred lighting pass (compute) reads the materials too: the factors of the BSDF extensions.
    const auto readByGBufferAndLighting = graph::stateAfterAccess(
        graph::Access::StorageRead, graph::ResourceKind::Buffer,
        VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    sb.materials = importBuffer(graph, "scene materials", s.materialBuffer(), readByGBufferAndLighting);
    sb.lights = importBuffer(graph, "scene lights", lightBuffer);
    sb.colors = importBuffer(graph, "scene vertex colors", s.colors());
    sb.uv1 = importBuffer(graph, "scene uv1", s.uv1());
    sb.drawCount = s.drawCount();
    if (s.materialsDirty() && sb.materials.valid()) {
        sb.materials = passes::addSceneUpdatePass(graph, sb.materials, s.materials());
        s.clearMaterialsDirty();
    }
    if (GpuAnimation* animation = s.animation())
        animation->addPasses(graph, shaders_, frames_.slotIndex(), frames_.framesInFlight(), sb);
    graph::BufferHandle frame = importBuffer(graph, "frame constants", frameBuffer);
    graph::ResourceState sampled;
    sampled.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    graph::TextureHandle environmentTexture = graph.importTexture(
        "environment", physicalOf(env.image), sampled, graph::FinalUse{graph::Access::SampledRead});

    // Shadows before the G-buffer: the installed validation layer counts every draw that uses the bindless
    // sampled array (the G-buffer's) as reading the cubes, so their write must not follow such a draw in the frame.
    passes::PointShadowOutputs shadows;
    if (updateShadowMaps(lights))
        shadows = passes::addPointShadowPass(graph, ctx_, shaders_, sb, *pointShadows_, lights, &log);
    passes::GBufferOutputs g = passes::addGBufferPass(graph, ctx_, shaders_, sb, frame, &log);
    graph::PhysicalTexture output = physicalOf(target);
    output.storageIndex = outputStorage_.value;
    graph::TextureHandle out =
        graph.importTexture("output", output, graph::ResourceState{}, graph::FinalUse{graph::Access::TransferSrc});
    bool display = settings_.output == OutputKind::Display;
    graph::TextureHandle hdr = out;
    if (display) {
        graph::TextureDesc desc;
        desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        hdr = graph.createTexture("hdr radiance", desc);
    }
    hdr = passes::addDeferredLightingPass(graph, ctx_, shaders_, g, frame, sb.lights, environmentTexture, hdr, shadows,
                                          sb.materials);
    hdr = passes::addSkyPass(graph, ctx_, shaders_, g.depth, frame, environmentTexture, hdr);
    if (blendDraws_) {  // sorted for this frame's eye into this slot's host-visible indirect buffer
        const vk::Buffer& sorted = blendDraws_->sort(frames_.slotIndex(), s.data(), camera.position);
        passes::TransparencyInputs t{sb, importBuffer(graph, "sorted blend draws", sorted), blendDraws_->count(),
                                     frame, g.depth, environmentTexture, shadows};
        hdr = passes::addTransparencyPass(graph, ctx_, shaders_, t, hdr, &log);
    }
    graph::TextureHandle last = display ? passes::addTonemapPass(graph, ctx_, shaders_, hdr, out, settings_.exposure) : hdr;
    graph.markOutput(last);
    return last;
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
    if (pbr && blendDraws_) desc.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;  // Hdr: transparency blends into it
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
    if (hasTimings_) info.passTimes = backend_.passTimings();

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
                // A blit, not a copy: it converts RGBA8 into the target's format (swapchains are often BGRA8).
                VkImageBlit2 region{VK_STRUCTURE_TYPE_IMAGE_BLIT_2};
                region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.srcOffsets[1] = {int32_t(width), int32_t(height), 1};
                region.dstOffsets[1] = {int32_t(width), int32_t(height), 1};
                VkBlitImageInfo2 blit{VK_STRUCTURE_TYPE_BLIT_IMAGE_INFO_2};
                blit.srcImage = pc.image(scene);
                blit.srcImageLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
                blit.dstImage = pc.image(*blitted);
                blit.dstImageLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
                blit.regionCount = 1;
                blit.pRegions = &region;
                blit.filter = VK_FILTER_NEAREST;
                vkCmdBlitImage2(pc.commandBuffer(), &blit);
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
