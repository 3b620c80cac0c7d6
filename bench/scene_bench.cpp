// scene_bench.cpp: per-scene cost of the deferred PBR renderer on the shared glTF assets: synchronous load
// (loadGltf + GPU upload + all textures) and first frame, asynchronous time-to-first-frame (textures streamed behind
// placeholders), and a warm 1280x720 frame with each pass's GPU time (FrameResult::passTimes); animated scenes
// advance their clock per frame (evaluateAnimations + skinning). Counterpart of IDKEngine's frame timings (ref. 4).
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::bench {
namespace {

constexpr uint32_t kWidth = 1280, kHeight = 720;
const char* const kRung = "- (deferred PBR raster: no ladder)";

struct SceneCase {
    const char* name;
    const char* file;  // under ../shared/scenes
    int repetitions;   // heavy scenes run fewer (BENCHMARKS.md says so)
};
const SceneCase kScenes[] = {
    {"Box", "Box/glTF-Binary/Box.glb", 5},
    {"DamagedHelmet", "DamagedHelmet/glTF-Binary/DamagedHelmet.glb", 5},
    {"BrainStem", "BrainStem/glTF-Binary/BrainStem.glb", 5},
    {"Fox", "Fox/glTF-Binary/Fox.glb", 5},
    {"MetalRoughSpheresNoTextures", "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", 3},
    {"ToyCar", "ToyCar/glTF/ToyCar.gltf", 5},
};

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::filesystem::path scenePath(const SceneCase& s) {
    return std::filesystem::path(IDK_BENCH_SOURCE_DIR) / ".." / "shared" / "scenes" / s.file;
}

bool ready(benchmark::State& state, const SceneCase& s) {
    if (!requireDevice(state)) return false;
    if (std::filesystem::exists(scenePath(s))) return true;
    state.SkipWithError(("missing " + scenePath(s).string()).c_str());
    for (auto _ : state) {
    }
    return false;
}

std::string inputText(const scene::Scene& scene, const SceneCase& s) {
    size_t triangles = 0;
    for (const scene::Instance& inst : scene.instances)
        for (const scene::Primitive& p : scene.meshes[inst.mesh].primitives) triangles += p.indices.size() / 3;
    return std::string(s.name) + " (" + std::to_string(triangles) + " triangles drawn)";
}

// Load (sync or async textures) and render the first 1280x720 frame with a fresh renderer; manual time = all of it.
void BM_SceneFirstFrame(benchmark::State& state, const SceneCase& s, bool async) {
    if (!ready(state, s)) return;
    std::map<std::string, double> parts;
    std::string input;
    for (auto _ : state) {
        Clock::time_point start = Clock::now(), t = start;
        scene::Scene scene = scene::loadGltf(scenePath(s));
        parts["gltf_ms"] += msSince(t);
        t = Clock::now();
        auto renderer = std::make_unique<render::Renderer>(*context(), *shaders());
        renderer->setScene(scene);
        parts["upload_ms"] += msSince(t);
        t = Clock::now();
        auto textures = std::make_unique<render::SceneTextureStream>(*context(), *renderer, scene);
        if (!async) textures->finishSynchronously();
        parts["textures_ms"] += msSince(t);
        t = Clock::now();
        render::FrameResult frame = renderer->renderOffscreen(scene::defaultCamera(scene), kWidth, kHeight);
        parts["frame_ms"] += msSince(t);
        state.SetIterationTime(msSince(start) / 1e3);
        if (async && textures->streamer()) parts["textures_ready"] += textures->streamer()->stats().readyTextures;
        benchmark::DoNotOptimize(frame.display.data());
        textures.reset();  // joins the streamer's workers (outside the timed part)
        renderer.reset();
        input = inputText(scene, s);
    }
    for (const auto& [name, value] : parts) state.counters[name] = value / double(state.iterations());
    const std::string peer = std::string("BM_SceneFirstFrameSync/") + s.name;
    setRow(state, {"scenes", input,
                   async ? "async: loadGltf + GPU scene upload + start texture streaming + first 1280x720 frame "
                           "(placeholders where textures have not arrived)"
                         : "sync: loadGltf + GPU scene upload + every texture decoded, mipmapped and uploaded + "
                           "first 1280x720 frame",
                   kRung, async ? peer : "", async ? "ours" : "peer", "manual"});
}

// A warm renderer (scene uploaded, textures in, pipelines built): one 1280x720 frame per iteration, wall time of
// renderOffscreen (graph build + compile, record, submit, wait, readback), GPU time per pass as counters.
void BM_SceneFrame(benchmark::State& state, const SceneCase& s) {
    if (!ready(state, s)) return;
    scene::Scene scene = scene::loadGltf(scenePath(s));
    const bool animated = !scene.animations.empty();
    const double period = animated ? std::max(0.1f, scene.animations[0].end - scene.animations[0].start) : 0.0;
    scene::CameraView camera = scene::defaultCamera(scene);
    std::map<std::string, double> passMs;
    double gpuMs = 0.0;
    uint64_t frameIndex = 0;
    {
        render::Renderer renderer(*context(), *shaders());
        renderer.setScene(scene);
        render::SceneTextureStream textures(*context(), renderer, scene);
        textures.finishSynchronously();
        renderer.renderOffscreen(camera, kWidth, kHeight);  // warm-up: pipelines, graph resources
        for (auto _ : state) {
            if (animated) {  // a 60 Hz clock: every frame has a new pose
                scene::evaluateAnimations(scene, std::fmod(double(++frameIndex) / 60.0, period), 0);
                renderer.setPose(scene);
            }
            render::FrameResult frame = renderer.renderOffscreen(camera, kWidth, kHeight);
            for (const vk::ScopeTiming& t : frame.passTimes) {
                gpuMs += t.milliseconds;
                passMs[t.name] += t.milliseconds;
            }
            benchmark::DoNotOptimize(frame.display.data());
        }
    }
    const auto iterations = double(state.iterations());
    state.counters["gpu_ms"] = gpuMs / iterations;
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    setRow(state, {"scenes", inputText(scene, s),
                   std::string("1280x720 frame, warm renderer, readback included") +
                       (animated ? "; animation 0 advanced 1/60 s per frame (evaluate + pose upload + skinning)" : ""),
                   kRung, "", "ours", "real"});
}

[[maybe_unused]] const bool kRegistered = [] {
    for (const SceneCase& s : kScenes) {
        const std::string name = s.name;
        benchmark::RegisterBenchmark(("BM_SceneFirstFrameSync/" + name).c_str(), BM_SceneFirstFrame, s, false)
            ->UseManualTime()->Iterations(1)->Repetitions(s.repetitions)->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_SceneFirstFrameAsync/" + name).c_str(), BM_SceneFirstFrame, s, true)
            ->UseManualTime()->Iterations(1)->Repetitions(s.repetitions)->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_SceneFrame/" + name).c_str(), BM_SceneFrame, s)
            ->UseRealTime()->Iterations(s.repetitions == 5 ? 4 : 2)->Repetitions(s.repetitions)
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
}  // namespace idk::bench
