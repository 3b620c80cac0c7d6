// renderer.cpp: the frame graphs: the deferred PBR frame (GPU scene + environment imported, G-buffer, point
// shadows, lighting, sky, transparency, tonemap) and the foundation's Lambert frame, both into an imported target
// that the graph leaves ready for the readback copy. Ports IDKEngine's RasterPipeline.Render frame order
// (reference 1.5, steps 6.6-6.13, 9).
#include "render/renderer.hpp"

#include <glm/gtc/packing.hpp>

#include <cstring>
#include <stdexcept>

#include "core/log.hpp"
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
    if (hasLambertScene_) destroyLambertScene(ctx_, lambertScene_);
    gpuScene_.reset();
    if (environment_) destroyEnvironment(ctx_, *environment_);
    for (vk::Buffer& b : frameConstants_) ctx_.destroy(b);
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
    } catch (const std::runtime_error& e) {
        core::logWarning("environment: ", e.what(), "; using a constant grey environment instead");
        environment_ = createEnvironment(ctx_, {});
    }
    return *environment_;
}

void Renderer::renderPbr(graph::RenderGraph& graph, const scene::CameraView& camera, uint32_t width, uint32_t height,
                         const vk::Image& target, passes::IndirectDrawLog& log) {
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
    // This frame's slot: begin() has waited until the GPU finished the slot's previous frame.
    const vk::Buffer& frameBuffer = frameConstants_[frames_.slotIndex()];

    gpu::GpuFrame f{};
    float aspect = float(width) / float(height);
    f.viewProjection = scene::projectionMatrix(camera, aspect) * scene::viewMatrix(camera);
    f.inverseViewProjection = glm::inverse(f.viewProjection);
    f.cameraPosition = camera.position;
    f.lightCount = s.lightCount();
    f.lights = s.lights() ? s.lights().address : 0;
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
    sb.materials = importBuffer(graph, "scene materials", s.materialBuffer(), readByGBuffer);
    sb.lights = importBuffer(graph, "scene lights", s.lights());
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
    if (updatePointShadowMaps(ctx_, s, settings_.pointShadows, pointShadows_))
        shadows = passes::addPointShadowPass(graph, ctx_, shaders_, sb, *pointShadows_, s.data().lights, &log);
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
    hdr = passes::addDeferredLightingPass(graph, ctx_, shaders_, g, frame, sb.lights, environmentTexture, hdr, shadows);
    hdr = passes::addSkyPass(graph, ctx_, shaders_, g.depth, frame, environmentTexture, hdr);
    if (blendDraws_) {  // sorted for this frame's eye into this slot's host-visible indirect buffer
        const vk::Buffer& sorted = blendDraws_->sort(frames_.slotIndex(), s.data(), camera.position);
        passes::TransparencyInputs t{sb, importBuffer(graph, "sorted blend draws", sorted), blendDraws_->count(),
                                     frame, g.depth, environmentTexture, shadows};
        hdr = passes::addTransparencyPass(graph, ctx_, shaders_, t, hdr, &log);
    }
    if (display) {
        graph.markOutput(passes::addTonemapPass(graph, ctx_, shaders_, hdr, out, settings_.exposure));
    } else {
        graph.markOutput(hdr);
    }
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
        ctx_.waitFor(frames_.end());  // submit what was recorded so the frame slot stays usable
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

}  // namespace idk::render
