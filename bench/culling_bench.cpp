// culling_bench.cpp: GPU culling (issue 10) at 1280x720: frame time and triangles drawn with --culling off /
// frustum / hiz, on the mesh-shader rung (shared context, where the device has VK_EXT_mesh_shader) and the MDI rung
// (a --fallback context), each against "off" on the same rung as its peer. Scenes: an occluder scene built here
// (a wall in front of a grid of DamagedHelmets, a few peeking over its top edge, a few behind the camera) and
// ToyCar. Each iteration renders one frame through a warm Renderer (two frames first, so the hiz rows run with
// last frame's visibility); the GPU counters of the last frame go into the row's settings.
// Ground truth: the unculled frame's surface-ID buffer (Renderer::renderSurfaceIds: the draw and triangle of every
// pixel) says which draws and triangles are visible; the rest are hidden. Counters: hidden_culled_fraction (the
// hidden triangles that culling did not draw / all hidden triangles), false_culls (visible draws the culler dropped:
// the drawn set follows from the visibility bits before and after the last frame and the CPU frustum oracle) and
// mismatches (pixels that differ from the unculled frame: catches meshlets the task shader dropped wrongly). On the
// mesh rung, meshlet_cullable_fraction: the hidden triangles in meshlets that hold no visible triangle, over all
// hidden triangles (the bound of any culler that draws whole meshlets).
// BM_HizBuild: the compute rung's Hi-Z pyramid at 1280x720, one dispatch per level against six levels per dispatch.
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "frame/culling_feature.hpp"
#include "passes/depth_pyramid_levels.hpp"
#include "render/depth_pyramid.hpp"
#include "render/culling_math.hpp"
#include "render/meshlets.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "scene/gltf_loader.hpp"
#include "vk/bindless.hpp"
#include "vk/timestamps.hpp"
#include "vk/transfer.hpp"

namespace idk::bench {
namespace {

constexpr uint32_t kWidth = 1280, kHeight = 720;

// Helmets (the scene's first mesh) on a 10 x 10 grid behind a 24 x 12 wall at z = 0, four of them raised above the
// wall's top edge, two behind the camera.
scene::Scene occluderScene() {
    scene::Scene s = scene::loadGltf(sharedScene("DamagedHelmet"));
    const scene::Instance helmet = s.instances.at(0);
    s.instances.clear();
    auto place = [&](glm::vec3 at, float scale) {
        scene::Instance i = helmet;
        i.world = glm::scale(glm::translate(glm::mat4(1.0f), at), glm::vec3(scale)) * helmet.world;
        s.instances.push_back(i);
        s.bounds.extend(at - glm::vec3(scale));
        s.bounds.extend(at + glm::vec3(scale));
    };
    for (int x = 0; x < 10; ++x)
        for (int z = 0; z < 10; ++z) place({-11.0f + 2.4f * float(x), 1.5f, -2.0f - 2.4f * float(z)}, 1.0f);
    for (int x = 0; x < 4; ++x) place({-9.0f + 6.0f * float(x), 12.4f, -2.0f}, 0.7f);  // peeking over the wall
    place({-3.0f, 1.0f, 24.0f}, 1.0f);                                                 // behind the camera
    place({3.0f, 1.0f, 24.0f}, 1.0f);

    scene::Material wallMaterial;
    wallMaterial.name = "wall";
    wallMaterial.baseColorFactor = glm::vec4(0.6f, 0.55f, 0.5f, 1.0f);
    s.materials.push_back(wallMaterial);
    scene::Primitive p;
    p.positions = {{-12.0f, 0.0f, 0.0f}, {12.0f, 0.0f, 0.0f}, {12.0f, 12.0f, 0.0f}, {-12.0f, 12.0f, 0.0f}};
    p.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
    p.uv0 = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
    p.indices = {0, 1, 2, 0, 2, 3};
    p.material = uint32_t(s.materials.size() - 1);
    scene::Mesh wall;
    wall.name = "wall";
    wall.primitives.push_back(std::move(p));
    s.meshes.push_back(std::move(wall));
    scene::Instance w = helmet;
    w.mesh = uint32_t(s.meshes.size() - 1);
    w.world = glm::mat4(1.0f);
    s.instances.push_back(w);
    s.lights.clear();
    return s;
}

struct FallbackDevice {
    std::unique_ptr<vk::Context> ctx;
    std::unique_ptr<vk::ShaderLibrary> shaders;
};
FallbackDevice& fallbackDevice() {  // `idk render --fallback`: the MDI rung of "mesh-shading"
    static FallbackDevice d;
    if (!d.ctx) {
        vk::ContextDesc desc = context()->desc();
        desc.forceFallbackRungs = true;
        d.ctx = std::make_unique<vk::Context>(desc);
        d.shaders = std::make_unique<vk::ShaderLibrary>(*d.ctx);
    }
    return d;
}

// What the unculled frame shows: per draw, its visible triangles (0: hidden), and the image.
struct GroundTruth {
    std::vector<uint32_t> visibleTriangles;  // per GpuScene draw
    uint64_t totalVisibleTriangles = 0;
    std::vector<uint8_t> image;
    std::vector<uint64_t> keys;  // (draw << 32 | triangle) of every visible triangle, sorted
};

// The most any meshlet culler can reach: the hidden triangles of the meshlets that hold no visible triangle, as a
// fraction of all hidden triangles (a meshlet with one visible triangle must be drawn whole).
double meshletCullableFraction(const render::GpuSceneData& data, const GroundTruth& truth, uint64_t sceneTriangles) {
    const render::MeshletData m = render::buildMeshlets(data);
    auto byte = [&](uint32_t i) { return (m.triangles[i / 4] >> (8 * (i % 4))) & 0xFFu; };
    std::vector<std::map<std::array<uint32_t, 3>, uint32_t>> meshletOf(m.firstMeshlet.size());  // sorted vertices
    auto sorted = [](uint32_t a, uint32_t b, uint32_t c) {
        std::array<uint32_t, 3> k{a, b, c};
        std::sort(k.begin(), k.end());
        return k;
    };
    std::set<uint64_t> needed;  // (draw << 32 | meshlet) holding a visible triangle
    for (uint64_t key : truth.keys) {
        const uint32_t draw = uint32_t(key >> 32), triangle = uint32_t(key);
        const uint32_t mesh = data.instances[draw].mesh;
        auto& map = meshletOf[mesh];
        if (map.empty())
            for (uint32_t local = 0; local < m.meshletCount[mesh]; ++local) {
                const gpu::GpuMeshlet& g = m.meshlets[m.firstMeshlet[mesh] + local];
                for (uint32_t t = 0; t < g.triangleCount; ++t) {
                    const uint32_t b = g.triangleOffset + 3 * t;
                    map[sorted(m.vertices[g.vertexOffset + byte(b)], m.vertices[g.vertexOffset + byte(b + 1)],
                               m.vertices[g.vertexOffset + byte(b + 2)])] = m.firstMeshlet[mesh] + local;
                }
            }
        const uint32_t* ix = &data.indices[data.draws[draw].firstIndex + 3 * triangle];
        const auto it = map.find(sorted(ix[0], ix[1], ix[2]));
        if (it != map.end()) needed.insert(uint64_t(draw) << 32 | it->second);
    }
    uint64_t mustDraw = 0;  // every triangle of the needed meshlets
    for (uint64_t k : needed) mustDraw += m.meshlets[uint32_t(k)].triangleCount;
    const uint64_t hidden = sceneTriangles - truth.totalVisibleTriangles;
    return hidden > 0 ? double(sceneTriangles - mustDraw) / double(hidden) : 1.0;
}

GroundTruth groundTruth(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                        const scene::CameraView& camera) {
    render::Renderer renderer(ctx, shaders);
    renderer.settings().culling.mode = frame::CullingMode::Off;
    renderer.setScene(scene);
    const std::vector<glm::uvec2> ids = renderer.renderSurfaceIds(camera, kWidth, kHeight);
    GroundTruth t;
    t.image = renderer.renderOffscreen(camera, kWidth, kHeight).display;
    t.visibleTriangles.assign(renderer.gpuScene()->data().draws.size(), 0u);
    std::vector<uint64_t> keys;  // (draw, triangle) of every covered pixel
    keys.reserve(ids.size());
    for (const glm::uvec2& id : ids)
        if (id.x < t.visibleTriangles.size()) keys.push_back(uint64_t(id.x) << 32 | id.y);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    for (uint64_t k : keys) ++t.visibleTriangles[size_t(k >> 32)];
    t.totalVisibleTriangles = keys.size();
    t.keys = std::move(keys);
    return t;
}

// Args: scene (0 occluder, 1 ToyCar), mode (frame::CullingMode), rung (0 native mesh shaders, 1 fallback MDI).
void BM_Culling(benchmark::State& state) {
    if (!requireDevice(state)) return;
    const bool toyCar = state.range(0) == 1;
    const auto mode = frame::CullingMode(state.range(1));
    const bool fallback = state.range(2) == 1;
    vk::Context& ctx = fallback ? *fallbackDevice().ctx : *context();
    vk::ShaderLibrary& shaders = fallback ? *fallbackDevice().shaders : *bench::shaders();
    const scene::Scene scene = toyCar ? scene::loadGltf(std::filesystem::path(IDK_BENCH_SOURCE_DIR) /
                                                        "../shared/scenes/ToyCar/glTF/ToyCar.gltf")
                                      : occluderScene();
    scene::CameraView camera = scene::defaultCamera(scene);
    if (!toyCar) {
        camera.position = {0.0f, 6.0f, 18.0f};
        camera.forward = glm::normalize(glm::vec3(0.0f, 6.0f, 0.0f) - camera.position);
        camera.up = glm::normalize(glm::cross(glm::cross(camera.forward, glm::vec3(0, 1, 0)), camera.forward));
        camera.znear = 0.1f;  // the default camera fits the helmet's own bounds
        camera.zfar = 0.0f;
    }
    const GroundTruth truth = groundTruth(ctx, shaders, scene, camera);
    ctx.clearConsultedLadders();
    double gpuMs = 0.0;
    passes::CullingViewStats last;
    uint64_t sceneTriangles = 0;
    std::vector<bool> drawnDraws;  // per draw: drawn in the last frame
    size_t mismatches = 0;
    double meshletBound = -1.0;  // mesh rung: meshletCullableFraction
    {
        render::Renderer renderer(ctx, shaders);
        renderer.settings().culling.mode = mode;
        renderer.setScene(scene);
        const render::GpuSceneData& data = renderer.gpuScene()->data();
        for (const VkDrawIndexedIndirectCommand& d : data.draws) sceneTriangles += d.instanceCount * (d.indexCount / 3);
        if (mode != frame::CullingMode::Off && frame::CullingFeature::usesMeshShaders(ctx, renderer.settings().culling))
            meshletBound = meshletCullableFraction(data, truth, sceneTriangles);
        renderer.renderOffscreen(camera, kWidth, kHeight);  // warm-up: pipelines, meshlets, visibility bits
        renderer.renderOffscreen(camera, kWidth, kHeight);
        for (auto _ : state) {
            render::FrameResult frame = renderer.renderOffscreen(camera, kWidth, kHeight);
            for (const vk::ScopeTiming& t : frame.passTimes) gpuMs += t.milliseconds;
            if (!frame.culling.empty()) last = frame.culling[0];
        }
        // One more frame, untimed, between two readbacks of the visibility bits: hiz draws in its early phase the
        // draws visible before it that are in the frustum, in its late phase those newly found visible.
        const std::vector<uint32_t> before = renderer.cullingVisibility();
        const render::FrameResult checked = renderer.renderOffscreen(camera, kWidth, kHeight);
        const std::vector<uint32_t> after = renderer.cullingVisibility();
        for (size_t i = 0; i < checked.display.size(); ++i) mismatches += checked.display[i] != truth.image[i];
        const glm::mat4 viewProjection =
            scene::projectionMatrix(camera, float(kWidth) / float(kHeight)) * scene::viewMatrix(camera);
        const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(data);
        const std::vector<bool> inFrustum = render::cullOracle(records, data.instances, render::frustumView(viewProjection));
        drawnDraws.assign(records.size(), mode == frame::CullingMode::Off);
        for (size_t i = 0; i < records.size() && mode != frame::CullingMode::Off; ++i)
            drawnDraws[i] = mode == frame::CullingMode::Frustum || before.at(i) != 0 ? bool(inFrustum[i]) : after.at(i) != 0;
    }
    const uint64_t drawn = mode == frame::CullingMode::Off ? sceneTriangles : last.trianglesDrawn;
    uint32_t falseCulls = 0;
    uint64_t visibleNotDrawn = 0;  // visible triangles of the falsely culled draws
    for (size_t i = 0; i < drawnDraws.size(); ++i)
        if (truth.visibleTriangles[i] > 0 && !drawnDraws[i]) ++falseCulls, visibleNotDrawn += truth.visibleTriangles[i];
    const uint64_t hidden = sceneTriangles - truth.totalVisibleTriangles;
    const uint64_t hiddenCulled = sceneTriangles - drawn - visibleNotDrawn;
    state.counters["gpu_ms"] = gpuMs / double(state.iterations());
    state.counters["triangles_drawn"] = double(drawn);
    state.counters["hidden_culled_fraction"] = hidden > 0 ? double(hiddenCulled) / double(hidden) : 1.0;
    state.counters["false_culls"] = double(falseCulls);
    if (mode != frame::CullingMode::Off) state.counters["mismatches"] = double(mismatches);
    if (meshletBound >= 0.0) state.counters["meshlet_cullable_fraction"] = meshletBound;
    static const char* kModes[] = {"off", "frustum", "hiz"};
    std::string settings = std::to_string(kWidth) + "x" + std::to_string(kHeight) + ", --culling " + kModes[int(mode)] +
                           ", triangles drawn " + std::to_string(drawn) + " of " + std::to_string(sceneTriangles) +
                           " (" + std::to_string(truth.totalVisibleTriangles) + " visible)";
    if (mode != frame::CullingMode::Off)
        settings += ", instances " + std::to_string(last.instancesDrawn) + " of " + std::to_string(last.instancesTested) +
                    (last.meshlets ? ", meshlets " + std::to_string(last.meshletsDrawn) + " of " +
                                         std::to_string(last.meshletsTested)
                                   : "");
    const std::string peer = "BM_Culling/" + std::to_string(state.range(0)) + "/0/" + std::to_string(state.range(2));
    setRow(state, {"culling", toyCar ? "ToyCar" : "occluder scene: 106 DamagedHelmets, 100 behind a wall, 4 peeking over it, 2 behind the camera", settings,
                   rungsThatRan(ctx.consultedLadders()), mode == frame::CullingMode::Off ? "" : peer,
                   "ours", "real"});
}
BENCHMARK(BM_Culling)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1}})
    ->UseRealTime()
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond);

// The compute rung's Hi-Z pyramid of a 1280x720 depth image (random depth on a 2^-24 grid): Arg = levels per
// dispatch of culling/hiz_build.comp.glsl, 1 (one dispatch per level, eleven) or kHizTileLevels (two dispatches:
// six levels from 32 x 32 shared-memory tiles, then the rest). Both give the CPU reduction's pyramid (the
// mismatches counter; the conformance check culling/hi-z pyramid covers every size). Peer: one per level.
void BM_HizBuild(benchmark::State& state) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    const uint32_t perDispatch = uint32_t(state.range(0));
    const glm::uvec2 size(kWidth, kHeight);
    std::vector<float> depth = randomFloats(size_t(size.x) * size.y, 11);
    for (float& d : depth) d -= 0.5f;  // [0, 1)
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R32_SFLOAT;
    desc.extent = {size.x, size.y, 1};
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    desc.name = "bench depth";
    desc.category = "bench";
    vk::Image image = ctx.createImage(desc);
    vk::uploadImage(ctx, image, depth.data(), depth.size() * sizeof(float), VK_IMAGE_LAYOUT_GENERAL);
    vk::StorageImageIndex storage = ctx.bindless().addStorage(image.view);
    const uint32_t count = gpu::hizLevelOffset(size, gpu::hizLevelCount(size));
    vk::Buffer pyramid = ctx.createBuffer(
        {count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "bench pyramid", "bench"});
    vk::TimestampQueries queries(ctx, 1);
    auto record = [&](VkCommandBuffer cmd) {
        passes::recordDepthPyramidLevels(cmd, ctx, *shaders(), storage.value, size, pyramid.address,
                                         passes::HizReduction::Farthest, perDispatch);
    };
    timeGpu(ctx, queries, record);  // warm-up: pipeline creation
    for (auto _ : state) state.SetIterationTime(timeGpu(ctx, queries, record));
    const std::vector<float> got = vk::downloadBuffer<float>(ctx, pyramid, count);
    const std::vector<float> expected = render::buildDepthPyramid(depth, size);
    double mismatches = 0;
    for (size_t i = 0; i < got.size(); ++i) mismatches += got[i] != expected[i];
    ctx.bindless().release(storage);
    ctx.destroyDeferred(pyramid);
    ctx.destroyDeferred(image);
    const uint32_t levels = gpu::hizLevelCount(size);
    state.counters["mismatches"] = mismatches;
    state.counters["dispatches"] = double((levels + perDispatch - 1) / perDispatch);
    setRow(state, {"culling", "1280x720 random depth", "Hi-Z pyramid (compute rung), " + std::to_string(perDispatch) +
                                                          " level(s) per dispatch",
                   "hiz-reduction=fallback (compute)", perDispatch == 1 ? "" : "BM_HizBuild/1", "ours", "manual"});
}
BENCHMARK(BM_HizBuild)->Arg(1)->Arg(gpu::kHizTileLevels)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace idk::bench
