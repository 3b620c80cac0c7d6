// vxgi_bench.cpp: voxel global illumination on the embedded Cornell box and two shared scenes at 128x128, next to --gi none and the path
// tracer. Error: relative L1 of the whole HDR frame (sum |a - b| / sum b over RGB) against the path tracer's image
// of the same camera at 1024 spp (computed once per process, not timed).
// BM_VxgiCornell/N: one rasterized frame with --gi vxgi at N^3 voxels (warm renderer: the voxelization, mips and
// cone tracing run every frame), GPU pass times as counters. BM_VxgiCornellOff: the same frame with --gi none.
// BM_VxgiPathTraced/S: the path tracer at S spp (the peer: the time it takes for its own error).
// BM_VxgiShared/K/N, BM_VxgiSharedOff/K, BM_VxgiSharedPathTraced/K/S: the same three on shared scene K
// (../shared/scenes, default camera, no texture streaming in either renderer): 0 EmissiveStrengthTest (emitters
// lighting their neighbours), 1 SimpleInstancing (instanced cubes under the sky); reference 1024 spp.
#include <cmath>
#include <map>
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

core::ImageRgba32f pathTrace(const scene::Scene& scene, uint32_t spp) {
    render::PathTracer tracer(*context(), *shaders(), scene);
    render::PathTraceSettings settings;
    settings.spp = spp;
    settings.seed = 7;
    return tracer.render(scene::defaultCamera(scene), kSize, kSize, settings).image;
}

// Scene K: -1 the embedded Cornell box, else kSharedScenes[K].
constexpr const char* kSharedScenes[] = {"EmissiveStrengthTest", "SimpleInstancing"};

scene::Scene loadScene(int k) {
    return k < 0 ? app::loadDefaultScene() : scene::loadGltf(sharedScene(kSharedScenes[k]));
}

std::string sceneLabel(int k) {
    return (k < 0 ? std::string("Cornell box (embedded)") : std::string(kSharedScenes[k])) + ", 128x128";
}

const core::ImageRgba32f& reference(int k, const scene::Scene& scene) {
    static std::map<int, core::ImageRgba32f> images;
    auto it = images.find(k);
    if (it == images.end()) it = images.emplace(k, pathTrace(scene, 1024)).first;
    return it->second;
}

void rasterFrames(benchmark::State& state, int k, frame::GiMode gi, uint32_t voxels, const char* settingsText,
                  const std::string& peer) {
    if (!requireDevice(state)) return;
    scene::Scene scene = loadScene(k);
    const core::ImageRgba32f& ref = reference(k, scene);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.vxgi.mode = gi;
    settings.vxgi.voxels = voxels;
    context()->clearConsultedLadders();
    double gpuMs = 0.0, error = 0.0;
    std::map<std::string, double> passMs;
    {
        render::Renderer renderer(*context(), *shaders(), settings);
        renderer.setScene(scene);
        error = relativeL1(renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize).image, ref);
        for (auto _ : state) {
            render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize);
            for (const vk::ScopeTiming& t : frame.passTimes) {
                gpuMs += t.milliseconds;
                if (t.name.rfind("vxgi_", 0) == 0) passMs[t.name] += t.milliseconds;
            }
            benchmark::DoNotOptimize(frame.image.pixels.data());
        }
    }
    const double iterations = double(state.iterations());
    state.counters["gpu_ms"] = gpuMs / iterations;
    state.counters["rel_error"] = error;
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    setRow(state, {"vxgi", sceneLabel(k), settingsText, rungsThatRan(context()->consultedLadders()), peer, "ours",
                   "real"});
}

void BM_VxgiCornell(benchmark::State& state) {
    const auto voxels = uint32_t(state.range(0));
    const std::string text = "--gi vxgi --voxels " + std::to_string(voxels) + ", 1 + 5 cones, 1 frame, warm";
    rasterFrames(state, -1, frame::GiMode::Vxgi, voxels, text.c_str(), "BM_VxgiPathTraced/4");
}
BENCHMARK(BM_VxgiCornell)->Arg(64)->Arg(128)->Arg(256)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void BM_VxgiCornellOff(benchmark::State& state) {
    rasterFrames(state, -1, frame::GiMode::None, 64, "--gi none (SH9 + split-sum ambient), 1 frame, warm",
                 "BM_VxgiPathTraced/4");
}
BENCHMARK(BM_VxgiCornellOff)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void pathTracedFrames(benchmark::State& state, int k, uint32_t spp) {
    if (!requireDevice(state)) return;
    scene::Scene scene = loadScene(k);
    const core::ImageRgba32f& ref = reference(k, scene);
    context()->clearConsultedLadders();
    double error = 0.0;
    {
        render::PathTracer tracer(*context(), *shaders(), scene);
        render::PathTraceSettings settings;
        settings.spp = spp;
        settings.seed = 1;  // another sequence than the reference's
        for (auto _ : state) {
            render::PathTraceResult r = tracer.render(scene::defaultCamera(scene), kSize, kSize, settings);
            error = relativeL1(r.image, ref);
            benchmark::DoNotOptimize(r.image.pixels.data());
        }
    }
    state.counters["rel_error"] = error;
    setRow(state, {"vxgi", sceneLabel(k), std::to_string(spp) + " spp path tracer, warm",
                   rungsThatRan(context()->consultedLadders()), "", "peer", "real"});
}

void BM_VxgiPathTraced(benchmark::State& state) { pathTracedFrames(state, -1, uint32_t(state.range(0))); }
BENCHMARK(BM_VxgiPathTraced)->Arg(4)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void BM_VxgiShared(benchmark::State& state) {
    const auto k = int(state.range(0));
    const auto voxels = uint32_t(state.range(1));
    const std::string text = "--gi vxgi --voxels " + std::to_string(voxels) + ", 1 + 5 cones, 1 frame, warm";
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
