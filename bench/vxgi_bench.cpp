// vxgi_bench.cpp: voxel global illumination on the embedded Cornell box and two shared scenes at 128x128, next to
// --gi none and the path tracer. Errors are relative L1 (sum |a - b| / sum b over RGB) against a depth-matched
// path-traced reference of the same camera (1024 spp, computed once per process, not timed). VXGI carries one
// bounce of every source, and each source's light is matched at its own depth (light transport is linear in the
// sources, so the reference is the sum of two path-traced images):
//  * emission and sky: maxDepth 2 (camera segment + one bounce), traced with the punctual lights removed;
//  * punctual lights: maxDepth 3 (the rasterizer lights the camera's surface directly, the voxels carry one bounce
//    of that light), traced with the emission zeroed and the environment off.
// One maxDepth 3 path tracer for a scene with both (the Cornell box: a point light under an emissive panel) would
// count the emission's second bounce, which VXGI never carries, as indirect, and its first bounce, which VXGI
// carries through the cones (the rasterizer has no area lights), as direct: measured on the Cornell box (64x64,
// 1024 spp) the two indirect references differ by 0.212 relative L1 (emission one bounce 0.033 mean luminance,
// its second 0.017), so no one-bounce renderer could have scored better than about that.
//  * rel_error: the whole HDR frame against that reference.
//  * rel_error_indirect: the indirect term: the frame minus the direct frame (--gi none with the environment off:
//    emission and punctual lights with their shadows), against the reference minus the path tracer's direct frame
//    (the same two parts one segment shorter, environment off, 1024 spp).
//  * indirect_error.emission_sky, indirect_error.punctual (VXGI rows of scenes with punctual lights): the indirect
//    term split by source: the frame rendered with only that source (punctual lights removed, environment on; or
//    emission zeroed, environment off) minus its own direct frame, against that part of the reference (its two
//    path traces, kept apart). Each is the part's relative L1 against its own reference; indirect_error_share.*
//    is the part's absolute L1 over the whole reference indirect sum (the shares add up to at least
//    rel_error_indirect: the parts' errors may cancel in the sum); indirect_ratio.* is the part's summed indirect
//    light over its reference's (signed sums over RGB: below 1 the part is too dark as a whole, above 1 too bright).
//  * pt_ms_same_error (VXGI rows): the (two-part) path tracer's time to reach the frame's indirect error, interpolated
//    log-log between runs at 1, 2, 4, ... 64 spp (beyond 64: extrapolated as error ~ 1/sqrt(spp),
//    pt_extrapolated = 1); pt_time_ratio = that time / the frame's time.
// BM_VxgiCornell/N: one rasterized frame with --gi vxgi at N^3 voxels (warm renderer: the voxelization, mips and
// cone tracing run every frame), GPU pass times as counters. BM_VxgiCornellOff: the same frame with --gi none.
// BM_VxgiVoxelizeDraws/R/N: the Cornell frame at N^3 voxels (64, 128) by each voxelization raster rung lavapipe
// runs, side by side in pass_ms.vxgi_voxelize: R = 0 three draws, one per axis, pixel centres (--gi-raster centre);
// R = 1 one draw whose geometry shader re-emits each triangle along its dominant axis (--gi-voxel-draws single:
// the voxel-single-draw fallback; its native rung, VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle, is
// absent here); R = 2 three draws with the conservative-raster fallback (geometry-shader dilation, the default
// here); R = 3 one draw of that dilation shader (it projects each triangle itself). Peers: 0 <-> 1, 2 <-> 3.
// BM_VxgiCornellCones/R/F/N: BM_VxgiCornell (the default 1 + 5 cones, 4 footprint cones each) with R ring cones
// (--gi-cones) and each diffuse cone traced as F footprint cones (--gi-footprint 1, 4, 7): the cone set's error
// against its cone-trace time (pass_ms.vxgi_cone_trace).
// BM_VxgiPathTraced/S: the two-part path tracer at S spp (the peer: the time for its own error).
// BM_VxgiCornellResolution/R: BM_VxgiCornell at 128^3 with the cones traced at full (R = 0) or half (R = 1)
// resolution (--gi-resolution; half adds the edge-aware upsample, pass_ms.vxgi_upsample).
// BM_VxgiShared/K/N, BM_VxgiSharedOff/K, BM_VxgiSharedPathTraced/K/S: the same three on shared scene K
// (../shared/scenes, default camera, no texture streaming in either renderer): 0 EmissiveStrengthTest (emitters
// lighting their neighbours), 1 SimpleInstancing (instanced cubes under the sky).
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "app/default_scene.hpp"
#include "bench_support.hpp"
#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::bench {
namespace {

constexpr uint32_t kSize = 128;

double relativeL1(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    double diff = 0.0, sum = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        diff += std::abs(double(a.pixels[i]) - b.pixels[i]);
        sum += std::abs(double(b.pixels[i]));
    }
    return diff / sum;
}

// Relative L1 of (a - aBase) against (b - bBase): the error of an indirect term.
double indirectL1(const core::ImageRgba32f& a, const core::ImageRgba32f& aBase, const core::ImageRgba32f& b,
                  const core::ImageRgba32f& bBase) {
    double diff = 0.0, sum = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        const double x = double(a.pixels[i]) - aBase.pixels[i], y = double(b.pixels[i]) - bBase.pixels[i];
        diff += std::abs(x - y);
        sum += std::abs(y);
    }
    return diff / sum;
}

// Scene K: -1 the embedded Cornell box, else kSharedScenes[K].
constexpr const char* kSharedScenes[] = {"EmissiveStrengthTest", "SimpleInstancing"};

scene::Scene loadScene(int k) {
    return k < 0 ? app::loadDefaultScene() : scene::loadGltf(sharedScene(kSharedScenes[k]));
}

std::string sceneLabel(int k) {
    return (k < 0 ? std::string("Cornell box (embedded)") : std::string(kSharedScenes[k])) + ", 128x128";
}

uint32_t matchedDepth(const scene::Scene& scene) { return scene.lights.empty() ? 2u : 3u; }

// One path-traced image and its wall time (ms); environment on or off.
core::ImageRgba32f pathTrace(const scene::Scene& scene, uint32_t spp, uint32_t depth, uint32_t seed, bool environment,
                             double* ms = nullptr) {
    render::PathTracerOptions options;
    options.environmentIntensity = environment ? 1.0f : 0.0f;
    render::PathTracer tracer(*context(), *shaders(), scene, options);
    render::PathTraceSettings settings;
    settings.spp = spp;
    settings.maxDepth = depth;
    settings.seed = seed;
    if (ms) tracer.render(scene::defaultCamera(scene), kSize, kSize, settings);  // warm-up: pipelines, tables
    const auto t0 = std::chrono::steady_clock::now();
    core::ImageRgba32f image = tracer.render(scene::defaultCamera(scene), kSize, kSize, settings).image;
    if (ms) *ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return image;
}

// The scene's two sources of light for the depth-matched reference: its punctual lights alone (emission zeroed;
// empty when it has none) and everything else (punctual lights removed).
struct SourceSplit {
    std::optional<scene::Scene> punctual;
    scene::Scene rest;
};

SourceSplit splitSources(const scene::Scene& scene) {
    SourceSplit split{std::nullopt, scene};
    split.rest.lights.clear();
    if (!scene.lights.empty()) {
        split.punctual = scene;
        for (scene::Material& m : split.punctual->materials) m.emissive = glm::vec3(0.0f);
    }
    return split;
}

// The depth-matched image (`direct`: each part one segment shorter, environment off) at `spp`, and its time;
// `punctualPart` (if given) receives the punctual lights' part alone (the rest is the returned image minus it).
core::ImageRgba32f matchedTrace(const SourceSplit& split, uint32_t spp, uint32_t seed, bool direct,
                                double* ms = nullptr, core::ImageRgba32f* punctualPart = nullptr) {
    double restMs = 0.0, punctualMs = 0.0;
    core::ImageRgba32f image = pathTrace(split.rest, spp, direct ? 1u : 2u, seed, !direct, ms ? &restMs : nullptr);
    if (split.punctual) {
        const core::ImageRgba32f lit =
            pathTrace(*split.punctual, spp, direct ? 2u : 3u, seed, false, ms ? &punctualMs : nullptr);
        for (size_t i = 0; i < image.pixels.size(); ++i)
            if (i % 4 != 3) image.pixels[i] += lit.pixels[i];
        if (punctualPart) *punctualPart = lit;
    }
    if (ms) *ms = restMs + punctualMs;
    return image;
}

struct Reference {
    core::ImageRgba32f full, direct;  // depth-matched frame; its direct part (one segment less, environment off)
    core::ImageRgba32f punctualFull, punctualDirect;  // the punctual lights' parts of those (scenes with lights)
    uint32_t depth = 2;               // the punctual lights' depth (3 where there are any)
    std::vector<std::pair<double, double>> ptCurve;  // (ms, indirect error) of the path tracer at 1..64 spp
};

const Reference& reference(int k, const scene::Scene& scene) {
    static std::map<int, Reference> refs;
    auto it = refs.find(k);
    if (it != refs.end()) return it->second;
    Reference r;
    r.depth = matchedDepth(scene);
    const SourceSplit split = splitSources(scene);
    r.full = matchedTrace(split, 1024, 7, false, nullptr, &r.punctualFull);
    r.direct = matchedTrace(split, 1024, 7, true, nullptr, &r.punctualDirect);
    for (uint32_t spp = 1; spp <= 64; spp *= 2) {
        double ms = 0.0;
        const core::ImageRgba32f img = matchedTrace(split, spp, 1, false, &ms);
        r.ptCurve.push_back({ms, indirectL1(img, r.direct, r.full, r.direct)});
    }
    return refs.emplace(k, std::move(r)).first->second;
}

// The path tracer's time to reach indirect error `e` on its (ms, error) curve; `extrapolated` when below its end.
double ptTimeForError(const std::vector<std::pair<double, double>>& curve, double e, bool& extrapolated) {
    extrapolated = false;
    if (e >= curve.front().second) return curve.front().first;
    for (size_t i = 1; i < curve.size(); ++i) {
        const auto [t0, e0] = curve[i - 1];
        const auto [t1, e1] = curve[i];
        if (e >= e1) {
            const double f = std::log(e0 / e) / std::log(e0 / e1);  // log-log interpolation
            return std::exp(std::log(t0) + f * (std::log(t1) - std::log(t0)));
        }
    }
    extrapolated = true;  // error ~ 1/sqrt(spp), time ~ spp
    const auto [t, last] = curve.back();
    return t * (last / e) * (last / e);
}

core::ImageRgba32f rasterDirect(const scene::Scene& scene) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    render::Renderer renderer(*context(), *shaders(), settings);
    renderer.setScene(scene);
    return renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize).image;
}

core::ImageRgba32f minus(core::ImageRgba32f a, const core::ImageRgba32f& b) {
    for (size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] -= b.pixels[i];
    return a;
}

// The indirect error split by source (see the header): one VXGI frame per source with `settings`, each against
// its part of the reference. Untimed, before the row's timed frames.
void sourceSplitCounters(benchmark::State& state, const scene::Scene& scene, const Reference& ref,
                         const render::RenderSettings& settings) {
    const SourceSplit split = splitSources(scene);
    if (!split.punctual) return;
    double totalRef = 0.0;
    for (size_t i = 0; i < ref.full.pixels.size(); ++i)
        if (i % 4 != 3) totalRef += std::abs(double(ref.full.pixels[i]) - ref.direct.pixels[i]);
    const core::ImageRgba32f restFull = minus(ref.full, ref.punctualFull);
    const core::ImageRgba32f restDirect = minus(ref.direct, ref.punctualDirect);
    struct Part {
        const char* name;
        const scene::Scene& scene;
        bool environment;
        const core::ImageRgba32f &full, &direct;
    };
    for (const Part& part : {Part{"emission_sky", split.rest, true, restFull, restDirect},
                             Part{"punctual", *split.punctual, false, ref.punctualFull, ref.punctualDirect}}) {
        render::RenderSettings s = settings;
        s.environmentIntensity = part.environment ? 1.0f : 0.0f;
        render::Renderer renderer(*context(), *shaders(), s);
        renderer.setScene(part.scene);
        const core::ImageRgba32f frame = renderer.renderOffscreen(scene::defaultCamera(part.scene), kSize, kSize).image;
        const core::ImageRgba32f direct = rasterDirect(part.scene);
        const double relative = indirectL1(frame, direct, part.full, part.direct);
        double partRef = 0.0;
        for (size_t i = 0; i < part.full.pixels.size(); ++i)
            if (i % 4 != 3) partRef += std::abs(double(part.full.pixels[i]) - part.direct.pixels[i]);
        double partIndirect = 0.0;
        for (size_t i = 0; i < frame.pixels.size(); ++i)
            if (i % 4 != 3) partIndirect += double(frame.pixels[i]) - direct.pixels[i];
        double partSigned = 0.0;
        for (size_t i = 0; i < part.full.pixels.size(); ++i)
            if (i % 4 != 3) partSigned += double(part.full.pixels[i]) - part.direct.pixels[i];
        state.counters[std::string("indirect_error.") + part.name] = relative;
        state.counters[std::string("indirect_ratio.") + part.name] = partIndirect / partSigned;
        state.counters[std::string("indirect_error_share.") + part.name] = relative * partRef / totalRef;
    }
}

void rasterFrames(benchmark::State& state, int k, frame::GiMode gi, uint32_t voxels, const char* settingsText,
                  const std::string& peer, frame::VoxelDraws draws = frame::VoxelDraws::Three,
                  frame::GiResolution resolution = frame::VxgiSettings{}.resolution,
                  frame::VoxelRaster raster = frame::VoxelRaster::Conservative,
                  uint32_t ringCones = frame::VxgiSettings{}.ringCones,
                  uint32_t footprintCones = frame::VxgiSettings{}.footprintCones) {
    if (!requireDevice(state)) return;
    scene::Scene scene = loadScene(k);
    const Reference& ref = reference(k, scene);
    const core::ImageRgba32f direct = rasterDirect(scene);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.vxgi.mode = gi;
    settings.vxgi.voxels = voxels;
    settings.vxgi.draws = draws;
    settings.vxgi.resolution = resolution;
    settings.vxgi.raster = raster;
    settings.vxgi.ringCones = ringCones;
    settings.vxgi.footprintCones = footprintCones;
    if (gi == frame::GiMode::Vxgi) sourceSplitCounters(state, scene, ref, settings);
    context()->clearConsultedLadders();
    double gpuMs = 0.0, error = 0.0, indirect = 0.0, wallMs = 0.0;
    std::map<std::string, double> passMs;
    {
        render::Renderer renderer(*context(), *shaders(), settings);
        renderer.setScene(scene);
        const core::ImageRgba32f first = renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize).image;
        error = relativeL1(first, ref.full);
        indirect = indirectL1(first, direct, ref.full, ref.direct);
        const auto t0 = std::chrono::steady_clock::now();
        for (auto _ : state) {
            render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize);
            for (const vk::ScopeTiming& t : frame.passTimes) {
                gpuMs += t.milliseconds;
                if (t.name.rfind("vxgi_", 0) == 0) passMs[t.name] += t.milliseconds;
            }
            benchmark::DoNotOptimize(frame.image.pixels.data());
        }
        wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    const double iterations = double(state.iterations());
    state.counters["gpu_ms"] = gpuMs / iterations;
    state.counters["rel_error"] = error;
    state.counters["rel_error_indirect"] = indirect;
    state.counters["reference_depth"] = double(ref.depth);
    if (gi == frame::GiMode::Vxgi) {
        bool extrapolated = false;
        const double ptMs = ptTimeForError(ref.ptCurve, indirect, extrapolated);
        state.counters["pt_ms_same_error"] = ptMs;
        state.counters["pt_extrapolated"] = extrapolated ? 1.0 : 0.0;
        state.counters["pt_time_ratio"] = ptMs / (wallMs / iterations);  // against the frame's wall time
    }
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    setRow(state, {"vxgi", sceneLabel(k), settingsText, rungsThatRan(context()->consultedLadders()), peer, "ours",
                   "real"});
}

void BM_VxgiCornell(benchmark::State& state) {
    const auto voxels = uint32_t(state.range(0));
    const std::string text = "--gi vxgi --voxels " + std::to_string(voxels) +
                             " (--gi-resolution half, the default), 1 + 5 cones x 4 footprint cones, 1 frame, warm";
    rasterFrames(state, -1, frame::GiMode::Vxgi, voxels, text.c_str(), "BM_VxgiPathTraced/4");
}
BENCHMARK(BM_VxgiCornell)->Arg(64)->Arg(128)->Arg(256)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void BM_VxgiVoxelizeDraws(benchmark::State& state) {
    const auto rung = int(state.range(0));
    const auto voxels = uint32_t(state.range(1));
    const bool single = rung % 2 == 1, dilated = rung >= 2;
    const std::string text = "--gi vxgi --voxels " + std::to_string(voxels) + " --gi-voxel-draws " +
                             (single ? "single" : "three") + " --gi-raster " + (dilated ? "conservative" : "centre") +
                             ", 1 frame, warm (pass_ms.vxgi_voxelize: the raster rung)";
    const std::string peer = "BM_VxgiVoxelizeDraws/" + std::to_string(rung ^ 1) + "/" + std::to_string(voxels);
    rasterFrames(state, -1, frame::GiMode::Vxgi, voxels, text.c_str(), peer,
                 single ? frame::VoxelDraws::Single : frame::VoxelDraws::Three, frame::VxgiSettings{}.resolution,
                 dilated ? frame::VoxelRaster::Conservative : frame::VoxelRaster::Centre);
}
BENCHMARK(BM_VxgiVoxelizeDraws)
    ->ArgsProduct({{0, 1, 2, 3}, {64, 128}})
    ->UseRealTime()
    ->MinTime(0.5)
    ->Unit(benchmark::kMillisecond);

void BM_VxgiCornellResolution(benchmark::State& state) {
    const bool half = state.range(0) != 0;
    const std::string text = std::string("--gi vxgi --voxels 128 --gi-resolution ") + (half ? "half" : "full") +
                             ", 1 + 5 cones x 4 footprint cones, 1 frame, warm";
    rasterFrames(state, -1, frame::GiMode::Vxgi, 128, text.c_str(), "BM_VxgiPathTraced/4", frame::VoxelDraws::Three,
                 half ? frame::GiResolution::Half : frame::GiResolution::Full);
}
BENCHMARK(BM_VxgiCornellResolution)->Arg(0)->Arg(1)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

// The cone set's options side by side: ring cones R and footprint cones F (each cone traced as F narrower ones).
void BM_VxgiCornellCones(benchmark::State& state) {
    const auto ring = uint32_t(state.range(0)), footprint = uint32_t(state.range(1));
    const auto voxels = uint32_t(state.range(2));
    const std::string text = "--gi vxgi --voxels " + std::to_string(voxels) + " --gi-cones " + std::to_string(ring) +
                             " --gi-footprint " + std::to_string(footprint) + ", 1 frame, warm";
    rasterFrames(state, -1, frame::GiMode::Vxgi, voxels, text.c_str(), "BM_VxgiPathTraced/4", frame::VoxelDraws::Three,
                 frame::VxgiSettings{}.resolution, frame::VoxelRaster::Conservative, ring, footprint);
}
BENCHMARK(BM_VxgiCornellCones)
    ->Args({12, 1, 64})->Args({16, 1, 64})->Args({5, 1, 64})->Args({3, 4, 64})->Args({5, 7, 64})
    ->Args({12, 1, 128})->Args({16, 1, 128})->Args({5, 1, 128})->Args({3, 4, 128})->Args({5, 7, 128})
    ->Args({12, 1, 256})->Args({5, 1, 256})
    ->UseRealTime()
    ->MinTime(0.5)
    ->Unit(benchmark::kMillisecond);

void BM_VxgiCornellOff(benchmark::State& state) {
    rasterFrames(state, -1, frame::GiMode::None, 64, "--gi none (SH9 + split-sum ambient), 1 frame, warm",
                 "BM_VxgiPathTraced/4");
}
BENCHMARK(BM_VxgiCornellOff)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void pathTracedFrames(benchmark::State& state, int k, uint32_t spp) {
    if (!requireDevice(state)) return;
    scene::Scene scene = loadScene(k);
    const Reference& ref = reference(k, scene);
    context()->clearConsultedLadders();
    double error = 0.0, indirect = 0.0;
    const SourceSplit split = splitSources(scene);
    for (auto _ : state) {
        const core::ImageRgba32f image = matchedTrace(split, spp, 1, false);  // another sequence than the reference's
        error = relativeL1(image, ref.full);
        indirect = indirectL1(image, ref.direct, ref.full, ref.direct);
        benchmark::DoNotOptimize(image.pixels.data());
    }
    state.counters["rel_error"] = error;
    state.counters["rel_error_indirect"] = indirect;
    state.counters["reference_depth"] = double(ref.depth);
    setRow(state, {"vxgi", sceneLabel(k),
                   std::to_string(spp) + " spp path tracer, depth-matched per source (maxDepth 2; punctual lights " +
                       std::to_string(ref.depth) + "), warm",
                   rungsThatRan(context()->consultedLadders()), "", "peer", "real"});
}

void BM_VxgiPathTraced(benchmark::State& state) { pathTracedFrames(state, -1, uint32_t(state.range(0))); }
BENCHMARK(BM_VxgiPathTraced)->Arg(4)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void BM_VxgiShared(benchmark::State& state) {
    const auto k = int(state.range(0));
    const auto voxels = uint32_t(state.range(1));
    const std::string text = "--gi vxgi --voxels " + std::to_string(voxels) +
                             " (--gi-resolution half, the default), 1 + 5 cones x 4 footprint cones, 1 frame, warm";
    rasterFrames(state, k, frame::GiMode::Vxgi, voxels, text.c_str(),
                 "BM_VxgiSharedPathTraced/" + std::to_string(k) + "/4");
}
BENCHMARK(BM_VxgiShared)
    ->ArgsProduct({{0, 1}, {64, 128, 256}})
    ->UseRealTime()
    ->MinTime(0.5)
    ->Unit(benchmark::kMillisecond);

void BM_VxgiSharedOff(benchmark::State& state) {
    const auto k = int(state.range(0));
    rasterFrames(state, k, frame::GiMode::None, 64, "--gi none (SH9 + split-sum ambient), 1 frame, warm",
                 "BM_VxgiSharedPathTraced/" + std::to_string(k) + "/4");
}
BENCHMARK(BM_VxgiSharedOff)->Arg(0)->Arg(1)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void BM_VxgiSharedPathTraced(benchmark::State& state) {
    pathTracedFrames(state, int(state.range(0)), uint32_t(state.range(1)));
}
BENCHMARK(BM_VxgiSharedPathTraced)
    ->ArgsProduct({{0, 1}, {4}})
    ->UseRealTime()
    ->MinTime(0.5)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace idk::bench
