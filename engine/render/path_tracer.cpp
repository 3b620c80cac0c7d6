// path_tracer.cpp: PathTracer: scene upload for tracing (GpuScene buffers and bindless textures, BLAS/TLAS for our
// BVH, driver acceleration structures for ray query, the path-tracing tables), the per-batch render graphs of
// pt_stages.cpp, progress, timings and readback.
#include "render/path_tracer.hpp"

#include <glm/gtc/packing.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

#include "graph/render_graph.hpp"
#include "core/log.hpp"
#include "pathtrace/cpu_path_tracer.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/environment.hpp"
#include "render/gpu_scene.hpp"
#include "render/pt_frame.hpp"
#include "render/pt_geometry.hpp"
#include "render/pt_pose.hpp"
#include "render/pt_stages.hpp"
#include "render/pt_tables.hpp"
#include "render/texture_streamer.hpp"
#include "render/vk_graph_backend.hpp"
#include "vk/acceleration_structure.hpp"
#include "vk/context.hpp"
#include "vk/frames.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::render {

const char* traversalName(PtTraversal t) {
    switch (t) {
        case PtTraversal::Auto: return "auto";
        case PtTraversal::Bvh: return "bvh";
        case PtTraversal::Bvh2: return "bvh2";
        case PtTraversal::RayQuery: return "rayquery";
    }
    return "?";
}

namespace {

vk::Buffer hostBuffer(vk::Context& ctx, size_t bytes, const std::string& name) {
    vk::BufferDesc desc;
    desc.size = bytes;
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    desc.memory = vk::MemoryUsage::Upload;
    desc.name = name;
    desc.category = "path tracer";
    return ctx.createBuffer(desc);
}

PtTraversal resolveTraversal(const vk::Context& ctx, PtTraversal requested) {
    if (requested == PtTraversal::RayQuery && !vk::rayQuerySupported(ctx))
        throw std::runtime_error("--traversal rayquery: " + ctx.info().name + " lacks VK_KHR_ray_query");
    // The ladder carries the CPU-device preference (lavapipe's software ray query yields to our BVH) and --rung;
    // it is consulted whatever was requested, so it reports itself as a rung that ran.
    const vk::Rung rung = ctx.ladder("ray traversal").chosen;
    if (requested != PtTraversal::Auto) return requested;
    return rung == vk::Rung::Native ? PtTraversal::RayQuery : PtTraversal::Bvh;
}

core::ImageRgba32f toImage(const std::vector<uint8_t>& bytes, VkFormat format, uint32_t w, uint32_t h) {
    core::ImageRgba32f img;
    img.width = w;
    img.height = h;
    img.pixels.assign(size_t(w) * h * 4, 0.0f);
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        if (format == VK_FORMAT_R32G32B32A32_SFLOAT) {
            std::memcpy(&img.pixels[4 * i], bytes.data() + 16 * i, 16);
        } else if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
            const auto* halves = reinterpret_cast<const uint16_t*>(bytes.data()) + 4 * i;
            for (int c = 0; c < 4; ++c) img.pixels[4 * i + c] = glm::unpackHalf1x16(halves[c]);
        } else {  // R32_SFLOAT
            std::memcpy(&img.pixels[4 * i], bytes.data() + 4 * i, 4);
            img.pixels[4 * i + 3] = 1.0f;
        }
    }
    return img;
}

// "pt_trace s3 b1" -> "trace"; the denoiser's own passes ("denoise_atrous_2", ...) -> "denoise".
std::string stageOf(const std::string& passName) {
    if (passName.rfind("pt_", 0) != 0) return passName.substr(0, passName.find('_'));
    return passName.substr(3, passName.find(' ') - 3);
}

}  // namespace

struct PathTracer::Impl {
    Impl(vk::Context& c, vk::ShaderLibrary& s, const PathTracerOptions& o)
        : ctx(c), shaders(s), options(o), backend(c), pool(backend), frames(c, 1) {}

    vk::Context& ctx;
    vk::ShaderLibrary& shaders;
    PathTracerOptions options;
    PtTraversal traversal = PtTraversal::Bvh;
    std::unique_ptr<GpuScene> gpuScene;
    // Owns the textures' images and bindless slots: its destructor releases them, so it lives as long as the
    // tracer (a streamer local to the constructor freed them before the first trace, which then sampled released
    // slots: unnoticed while nothing reused them, grey in a viewer whose own textures had loaded first).
    std::unique_ptr<TextureStreamer> textures;
    PtGpuGeometry geometry;
    std::unique_ptr<vk::AccelerationStructures> accel;
    PtTables tables;
    std::vector<PtPoseRange> poseRanges;               // GPU-posed geometry (pt_pose.hpp)
    std::vector<std::vector<glm::uvec3>> triangles;    // ray query: per geometry, to rebuild after a pose
    bool cpuPosedDeformation = false;                  // the scene has CPU-posed copies (setPose cannot move them)
    gpu::GpuPtSceneDesc desc{};
    struct Progressive {
        bool active = false;  // begun and not ended by render() or capture() (they reuse the accumulation)
        PathTraceSettings settings;
        uint32_t samples = 0;
    } progressive;
    bool hasAlpha = false;
    vk::Buffer sceneDesc, camera, accumDesc;
    VkGraphBackend backend;
    graph::ResourcePool pool;
    vk::FrameRing frames;
    PtFrameResources frame;
    std::map<const void*, graph::ResourceState> states;

    ~Impl() {
        ctx.waitIdle();
        destroyPtFrame(ctx, frame);
        destroyPtTables(ctx, tables);
        destroyPtGeometry(ctx, geometry);
        for (vk::Buffer* b : {&sceneDesc, &camera, &accumDesc})
            if (b->buffer) ctx.destroy(*b);
    }

    void ensureFrame(uint32_t w, uint32_t h) {
        if (frame.width == w && frame.height == h && (!options.sortRays || frame.keys.buffer)) return;
        ctx.waitIdle();
        destroyPtFrame(ctx, frame);
        states.clear();
        frame = createPtFrame(ctx, w, h, options.sortRays);
        gpu::GpuPtAccum a{};
        a.color = frame.accumColor.address;
        a.albedo = frame.accumAlbedo.address;
        a.normal = frame.accumNormal.address;
        a.depth = frame.accumDepth.address;
        a.moment = frame.accumMoment.address;
        a.guides = frame.guides.address;
        a.colorImage = frame.colorStorage.value;
        a.albedoImage = frame.albedoStorage.value;
        a.normalImage = frame.normalStorage.value;
        a.depthImage = frame.depthStorage.value;
        a.varianceImage = frame.varianceStorage.value;
        vk::uploadBuffer(ctx, accumDesc, &a, sizeof(a));
    }

    PtStageConfig config(const PathTraceSettings& settings) const {
        PtStageConfig c;
        c.rayQuery = traversal == PtTraversal::RayQuery;
        c.wideBvh = traversal == PtTraversal::Bvh;
        c.sort = options.sortRays;
        c.hasAlpha = hasAlpha;
        c.nee = settings.nee;
        c.sobol = settings.sampler == pathtrace::PtSampler::Sobol;
        c.blasStack = traversal == PtTraversal::Bvh ? geometry.wideStackSize : geometry.blasStackSize;
        c.tlasStack = geometry.tlasStackSize;
        c.scene = sceneDesc.address;
        c.camera = camera.address;
        c.accum = accumDesc.address;
        c.maxDepth = std::max(settings.maxDepth, 1u);
        c.rouletteDepth = settings.rouletteDepth;
        c.seed = settings.seed;
        return c;
    }

    void setCamera(const scene::CameraView& view, uint32_t w, uint32_t h) {
        gpu::GpuPtCamera cam{};
        cam.inverseViewProjection = pathtrace::inverseViewProjection(view, w, h);  // the CPU reference's matrix
        cam.position = view.position;
        vk::uploadBuffer(ctx, camera, &cam, sizeof(cam));
    }

    // Driver acceleration structures over the current vertex positions (the ray-query rung). A posed BLAS's
    // positions are read back from the GPU: a real-GPU renderer would instead run an update build
    // (VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR) from the posed buffer.
    void buildAccel() {
        std::vector<std::vector<glm::vec3>> positions(triangles.size());
        std::vector<vk::AccelMesh> meshes;
        for (size_t i = 0; i < triangles.size(); ++i) {
            if (geometry.geometryBlas[i] >= 0) {
                const GpuBlas& blas = *geometry.blases[size_t(geometry.geometryBlas[i])];
                positions[i] = vk::downloadBuffer<glm::vec3>(ctx, blas.positionBuffer(), blas.vertexCount());
            }
            meshes.push_back({positions[i], triangles[i]});
        }
        std::vector<vk::AccelInstance> instances;
        for (uint32_t i = 0; i < geometry.placed.size(); ++i)
            instances.push_back({geometry.placed[i].objectToWorld, geometry.placed[i].blasIndex, i});
        accel.reset();
        accel = std::make_unique<vk::AccelerationStructures>(ctx, meshes, instances);
    }

    // The GpuAnimation's pose onto the GPU-posed geometry, refit, TLAS rebuilt, scene descriptor re-pointed.
    void applyPose() {
        posePtGeometry(ctx, shaders, *gpuScene, poseRanges, geometry);
        rebuildPtTlas(ctx, geometry);
        if (traversal == PtTraversal::RayQuery) buildAccel();
        desc.tlas = geometry.wideTlas ? geometry.wideTlas->descAddress() : geometry.tlas->descAddress();
        desc.accel = accel ? accel->tlasAddress() : 0;
        vk::uploadBuffer(ctx, sceneDesc, &desc, sizeof(desc));
    }

    // The resolved images of the current accumulation (after addPtResolve [+ addPtDenoise] ran), as options ask.
    void readResult(PathTraceResult& result) {
        const PtFrameResources& f = frame;
        const uint32_t width = f.width, height = f.height;
        result.image = toImage(vk::readbackImage(ctx, f.colorImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL),
                               VK_FORMAT_R32G32B32A32_SFLOAT, width, height);
        if (options.readGuides || options.denoise) {
            result.albedo = toImage(vk::readbackImage(ctx, f.albedoImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL),
                                    VK_FORMAT_R16G16B16A16_SFLOAT, width, height);
            result.normal = toImage(vk::readbackImage(ctx, f.normalImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL),
                                    VK_FORMAT_R16G16B16A16_SFLOAT, width, height);
            result.depth = toImage(vk::readbackImage(ctx, f.depthImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL),
                                   VK_FORMAT_R32_SFLOAT, width, height);
        }
        if (options.readSum) {
            result.sum.width = width;
            result.sum.height = height;
            result.sum.pixels.resize(size_t(width) * height * 4);
            vk::downloadBuffer(ctx, f.accumColor, result.sum.pixels.data(), result.sum.pixels.size() * sizeof(float));
        }
        if (options.denoise) {
            result.denoised = toImage(vk::readbackImage(ctx, f.denoisedImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL),
                                      VK_FORMAT_R32G32B32A32_SFLOAT, width, height);
            result.didDenoise = true;
        }
    }

    // Records `build` into one graph, submits it and waits; returns the graph's pass timings.
    std::vector<vk::ScopeTiming> runGraph(const std::function<void(const PtStageContext&)>& build,
                                          const PtStageConfig& cfg) {
        VkCommandBuffer cmd = frames.begin();
        graph::RenderGraph graph(pool, {frame.width, frame.height});
        PtGraphResources res(graph, states);
        try {
            PtStageContext sc{ctx, shaders, graph, res, frame, cfg};
            build(sc);
            graph.compile();
            res.saveStates();
            graph.execute(cmd);
        } catch (...) {
            ctx.waitFor(frames.end());
            throw;
        }
        ctx.waitFor(frames.end());
        return backend.passTimings();
    }
};

namespace {

// PT-A's scene for options.environment: the HDR file (default: the raster's), or a constant grey 0.5 for an empty
// path; a file that cannot be read falls back to the constant with a warning, as the raster does. With
// options.atmosphere.enabled the baked sky instead (black at intensity 0, where the raster bakes nothing either).
// Skins and morphs are posed by the GPU (pt_pose.hpp); the CPU reference poses them itself (PtPosing::Cpu).
constexpr pathtrace::PtPosing kPosing = pathtrace::PtPosing::Gpu;

pathtrace::PathTraceScene buildScene(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                                     const PathTracerOptions& options) {
    if (options.atmosphere.enabled) {
        if (options.environmentIntensity == 0.0f)
            return pathtrace::buildPathTraceScene(scene, nullptr, 0.0f, glm::vec3(0.0f), kPosing);
        const core::ImageRgba32f sky = bakeSky(ctx, shaders, options.atmosphere);
        return pathtrace::buildPathTraceScene(scene, &sky, options.environmentIntensity, glm::vec3(0.0f), kPosing);
    }
    const std::filesystem::path file = options.environment.value_or(defaultEnvironmentPath());
    if (!file.empty()) {
        try {
            const core::ImageRgba32f image = core::readImage(file);
            return pathtrace::buildPathTraceScene(scene, &image, options.environmentIntensity, glm::vec3(0.0f), kPosing);
        } catch (const std::runtime_error& e) {
            core::logWarning("environment: ", e.what(), "; using a constant grey environment instead");
        }
    }
    return pathtrace::buildPathTraceScene(scene, nullptr, options.environmentIntensity,
                                          glm::vec3(0.5f * options.environmentIntensity), kPosing);
}

}  // namespace

PathTracer::PathTracer(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene, PathTracerOptions options)
    : PathTracer(ctx, shaders, scene, buildScene(ctx, shaders, scene, options), options) {}

PathTracer::PathTracer(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                       const pathtrace::PathTraceScene& pts, PathTracerOptions options)
    : impl_(std::make_unique<Impl>(ctx, shaders, options)) {
    Impl& m = *impl_;
    m.traversal = resolveTraversal(ctx, options.traversal);
    if (options.denoise && !denoiserAvailable())
        throw std::runtime_error("path tracer: --denoise needs engine/passes/denoise.hpp, which this build lacks");
    // Materials with bindless texture slots come from GpuScene; the geometry is PT-A's (uploaded below). GPU-posed
    // instances also need its vertices and animation state: the rasterizer's skinning poses them.
    const bool gpuPosed = !pts.gpuPosedInstances.empty();
    m.gpuScene = std::make_unique<GpuScene>(ctx, scene, gpuPosed ? GpuSceneContents::Everything
                                                                  : GpuSceneContents::MaterialsOnly);
    std::vector<PtTextureBinding> textures(scene.textures.size());
    if (m.gpuScene->features().hasTextures) {
        // onReady runs only inside finishSynchronously (no frame pumps this streamer), while `textures` lives.
        m.textures = std::make_unique<TextureStreamer>(
            ctx, scene, [&](uint32_t texture, vk::SampledIndex image, vk::SamplerIndex sampler) {
                m.gpuScene->setTexture(texture, image, sampler);
                if (texture < textures.size()) textures[texture] = {image.value, sampler.value};
            });
        m.textures->finishSynchronously();
    }
    // The patched material slots reach the GPU before any trace reads them (nothing is in flight yet).
    if (m.gpuScene->materialBuffer())
        vk::uploadBuffer(ctx, m.gpuScene->materialBuffer(), std::span<const gpu::GpuMaterial>(m.gpuScene->materials()));
    m.gpuScene->clearMaterialsDirty();
    m.hasAlpha = pts.alphaTesting;

    m.geometry = uploadPtGeometry(ctx, pts, m.traversal == PtTraversal::Bvh);
    m.cpuPosedDeformation = pts.cpuPosedDeformation;
    if (m.traversal == PtTraversal::RayQuery)
        for (const pathtrace::PtGeometry& g : pts.geometries) m.triangles.push_back(g.triangles);
    m.tables = uploadPtTables(ctx, pts, textures, PtTextureBinding{});
    m.desc = m.tables.desc;
    m.desc.geometries = m.geometry.geometryTable.address;
    m.desc.instances = m.geometry.instanceTable.address;
    m.desc.materials = m.gpuScene->materialBuffer().address;
    m.desc.instanceCount = uint32_t(m.geometry.instances.size());
    if (gpuPosed) {
        m.sceneDesc = uploadPtBuffer(ctx, &m.desc, sizeof(m.desc), "pt scene");
        m.poseRanges = ptPoseRanges(scene, pts, m.gpuScene->data());
        m.applyPose();  // the scene's current pose (GpuAnimation took it at construction); fills tlas and accel
    } else {
        if (m.traversal == PtTraversal::RayQuery) m.buildAccel();
        m.desc.tlas = m.geometry.wideTlas ? m.geometry.wideTlas->descAddress() : m.geometry.tlas->descAddress();
        m.desc.accel = m.accel ? m.accel->tlasAddress() : 0;
        m.sceneDesc = uploadPtBuffer(ctx, &m.desc, sizeof(m.desc), "pt scene");
    }
    m.camera = hostBuffer(ctx, sizeof(gpu::GpuPtCamera), "pt camera");
    m.accumDesc = hostBuffer(ctx, sizeof(gpu::GpuPtAccum), "pt accumulation");
}

PathTracer::~PathTracer() = default;

void PathTracer::setPose(const scene::Scene& scene) {
    Impl& m = *impl_;
    if (scene.instances.size() != m.geometry.placed.size())
        throw std::invalid_argument("PathTracer::setPose: the scene is not the one the path tracer was built from");
    if (m.cpuPosedDeformation)
        throw std::invalid_argument("PathTracer::setPose: the scene's skinned or morphed instances were posed on the "
                                    "CPU (PtPosing::Cpu, or an emissive one): build a new PathTracer for a new pose");
    bool moved = false;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        bvh::BlasInstance& placed = m.geometry.placed[i];
        gpu::GpuPtTraceInstance& ti = m.geometry.instances[i];
        const glm::mat4& world = scene.instances[i].world;
        if (placed.objectToWorld == world) continue;
        // Triangle lights hold world-space vertices (pathtrace::buildLights): an emitter that moves needs a new
        // light list, i.e. a new PathTracer.
        if (ti.firstLight != gpu::kPtNoLight)
            throw std::invalid_argument("PathTracer::setPose: emissive instance " + std::to_string(i) +
                                        " moved; build a new PathTracer for it");
        placed.objectToWorld = world;
        const glm::mat3 m3(world);
        const glm::mat3 normal = std::abs(glm::determinant(m3)) > 0.0f ? glm::transpose(glm::inverse(m3)) : glm::mat3(1.0f);
        for (int c = 0; c < 4; ++c) ti.objectToWorld[c] = glm::vec3(world[c]);
        for (int c = 0; c < 3; ++c) ti.normalToWorld[c] = normal[c];
        ti.flags = glm::determinant(m3) < 0.0f ? (ti.flags | gpu::kPtInstanceMirrored) : (ti.flags & ~gpu::kPtInstanceMirrored);
        moved = true;
    }
    if (moved)
        vk::uploadBuffer(m.ctx, m.geometry.instanceTable, m.geometry.instances.data(),
                         m.geometry.instances.size() * sizeof(gpu::GpuPtTraceInstance));
    if (m.gpuScene->animation()) m.gpuScene->animation()->setPose(scene);
    if (moved || !m.poseRanges.empty()) m.applyPose();
}

PtTraversal PathTracer::traversal() const noexcept { return impl_->traversal; }

PathTraceResult PathTracer::render(const scene::CameraView& camera, uint32_t width, uint32_t height,
                                   const PathTraceSettings& settings, const Progress& progress) {
    if (width == 0 || height == 0) throw std::invalid_argument("PathTracer::render: empty image size");
    Impl& m = *impl_;
    const auto start = std::chrono::steady_clock::now();
    m.progressive.active = false;
    m.ensureFrame(width, height);
    m.setCamera(camera, width, height);
    const PtStageConfig cfg = m.config(settings);
    PathTraceResult result;
    result.traversal = m.traversal;
    std::map<std::string, double> stageMs;
    auto addTimes = [&](const std::vector<vk::ScopeTiming>& times) {
        for (const vk::ScopeTiming& t : times) {
            stageMs[stageOf(t.name)] += t.milliseconds;
            result.gpuMilliseconds += t.milliseconds;
        }
    };
    const uint32_t spp = std::max(settings.spp, 1u);
    const uint32_t batch = std::max(m.options.samplesPerBatch, 1u);
    for (uint32_t done = 0; done < spp;) {
        const uint32_t count = std::min(batch, spp - done);
        const bool last = done + count == spp;
        addTimes(m.runGraph(
            [&](const PtStageContext& sc) {
                if (done == 0) addPtClear(sc);
                for (uint32_t k = 0; k < count; ++k) addPtSample(sc, settings.firstSample + done + k);
                if (last) addPtResolve(sc);
                if (last && m.options.denoise) addPtDenoise(sc);
            },
            cfg));
        done += count;
        if (progress) progress(done, spp);
    }
    result.samples = spp;
    m.readResult(result);
    for (const auto& [stage, ms] : stageMs) result.stageTimes.push_back({stage, ms});
    result.wallMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

void PathTracer::beginProgressive(const scene::CameraView& camera, uint32_t width, uint32_t height,
                                  const PathTraceSettings& settings) {
    if (width == 0 || height == 0) throw std::invalid_argument("PathTracer::beginProgressive: empty image size");
    Impl& m = *impl_;
    m.ensureFrame(width, height);
    m.setCamera(camera, width, height);
    m.progressive = {true, settings, 0};
    m.runGraph([&](const PtStageContext& sc) { addPtClear(sc); }, m.config(settings));
}

uint32_t PathTracer::accumulate(uint32_t samples) {
    Impl& m = *impl_;
    if (!m.progressive.active)
        throw std::logic_error("PathTracer::accumulate: no progressive image (call beginProgressive after render)");
    const PtStageConfig cfg = m.config(m.progressive.settings);
    const uint32_t batch = std::max(m.options.samplesPerBatch, 1u);
    for (uint32_t done = 0; done < samples;) {
        const uint32_t count = std::min(batch, samples - done);
        const uint32_t first = m.progressive.settings.firstSample + m.progressive.samples;
        m.runGraph(
            [&](const PtStageContext& sc) {
                for (uint32_t k = 0; k < count; ++k) addPtSample(sc, first + k);
            },
            cfg);
        done += count;
        m.progressive.samples += count;
    }
    return m.progressive.samples;
}

uint32_t PathTracer::accumulatedSamples() const noexcept {
    return impl_->progressive.active ? impl_->progressive.samples : 0;
}

PathTraceResult PathTracer::resolveProgressive() {
    Impl& m = *impl_;
    if (!m.progressive.active)
        throw std::logic_error("PathTracer::resolveProgressive: no progressive image (call beginProgressive)");
    PathTraceResult result;
    result.traversal = m.traversal;
    m.runGraph(
        [&](const PtStageContext& sc) {
            addPtResolve(sc);
            if (m.options.denoise) addPtDenoise(sc);
        },
        m.config(m.progressive.settings));
    result.samples = m.progressive.samples;
    m.readResult(result);
    return result;
}

PtCapture PathTracer::capture(const scene::CameraView& camera, uint32_t width, uint32_t height,
                              const PathTraceSettings& settings, uint32_t bounce) {
    Impl& m = *impl_;
    m.progressive.active = false;
    m.ensureFrame(width, height);
    m.setCamera(camera, width, height);
    PathTraceSettings s = settings;
    s.maxDepth = std::max(s.maxDepth, bounce + 1);
    const PtStageConfig cfg = m.config(s);
    const PtFrameResources& f = m.frame;
    const size_t pixels = size_t(width) * height;
    PtCapture c;
    // Three deterministic replays of sample 0 (paths and hits are per pixel and seeded; only the order of
    // appended queue entries may differ between replays): the rays of `bounce`, the state after its shade stage,
    // and the dispatch size its args stage derives.
    auto run = [&](PtStop stop) { m.runGraph([&](const PtStageContext& sc) { addPtSample(sc, 0, stop); }, cfg); };
    run(bounce == 0 ? PtStop{PtStop::AfterCamera, 0} : PtStop{PtStop::AfterShade, bounce - 1});
    c.rays = vk::downloadBuffer<gpu::GpuPtPath>(m.ctx, f.paths, pixels);
    run(PtStop{PtStop::AfterShade, bounce});
    const int in = int(bounce % 2);
    c.paths = vk::downloadBuffer<gpu::GpuPtPath>(m.ctx, f.paths, pixels);
    c.hits = vk::downloadBuffer<gpu::GpuPtHit>(m.ctx, f.hits, pixels);
    c.queueIn = vk::downloadBuffer<uint32_t>(m.ctx, f.queue[in], pixels + gpu::kPtQueueHeaderWords);
    c.queueOut = vk::downloadBuffer<uint32_t>(m.ctx, f.queue[1 - in], pixels + gpu::kPtQueueHeaderWords);
    if (m.options.sortRays) c.keys = vk::downloadBuffer<uint32_t>(m.ctx, f.keys, pixels);
    run(PtStop{PtStop::AfterArgs, bounce});
    c.argsOut = vk::downloadBuffer<uint32_t>(m.ctx, f.args[1 - in], 3);
    return c;
}

}  // namespace idk::render
