// render_bench.cpp: `idk render` of the embedded Cornell box (engine/app/default_scene.hpp) at 256x256.
// BM_RenderCornellBox: one frame through a warm Renderer (scene uploaded and pipelines built once): wall time of
// Renderer::renderOffscreen (build + compile the frame graph, record, submit, wait, read back, unpack), with the
// GPU time of each pass from FrameResult::passTimes as counters ("gpu_ms" total, "pass_ms.<name>" each).
// BM_IdkRenderCommand: the whole command, cold: device, shaders, scene load and upload, one frame, PNG write.
// Each row's rung column lists the capability ladders the render consulted (the rungs that ran).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/default_scene.hpp"
#include "bench_support.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"

namespace idk::bench {
namespace {

void BM_RenderCornellBox(benchmark::State& state) {
    if (!requireDevice(state)) return;
    auto size = uint32_t(state.range(0));
    scene::Scene scene = app::loadDefaultScene();
    scene::CameraView camera = scene::defaultCamera(scene);
    double gpuMs = 0.0;
    std::map<std::string, double> passMs;
    context()->clearConsultedLadders();
    {
        render::Renderer renderer(*context(), *shaders());
        renderer.setScene(scene);
        renderer.renderOffscreen(camera, size, size);   // warm-up: pipelines, graph resources
        for (auto _ : state) {
            render::FrameResult frame = renderer.renderOffscreen(camera, size, size);
            for (const vk::ScopeTiming& t : frame.passTimes) {
                gpuMs += t.milliseconds;
                passMs[t.name] += t.milliseconds;
            }
            benchmark::DoNotOptimize(frame.image.pixels.data());
        }
    }
    auto iterations = double(state.iterations());
    state.counters["gpu_ms"] = gpuMs / iterations;
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    std::string dims = std::to_string(size) + "x" + std::to_string(size);
    setRow(state, {"render", "Cornell box (embedded)", dims + ", 1 frame, warm renderer, readback included",
                   rungsThatRan(context()->consultedLadders()), "", "ours", "real"});
}
BENCHMARK(BM_RenderCornellBox)->Arg(256)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kMillisecond);

void BM_IdkRenderCommand(benchmark::State& state) {
    if (!requireDevice(state)) return;   // the command creates its own device; skip where there is none
    std::string size = std::to_string(state.range(0));
    std::filesystem::path out = std::filesystem::temp_directory_path() / "idk_bench_render.png";
    const std::vector<std::string> args = {"--out", out.string(), "--size", size + "x" + size, "--no-validation"};
    std::vector<vk::Ladder> ran;  // the command's own context's consulted ladders
    for (auto _ : state) {
        if (app::runRender(args, &ran) != 0) {
            state.SkipWithError("idk render failed");
            break;
        }
    }
    std::filesystem::remove(out);
    setRow(state, {"render", "Cornell box (embedded)",
                   size + "x" + size + ", cold `idk render --out F.png --no-validation` in-process: device, shaders, "
                                      "scene, 1 frame, PNG",
                   rungsThatRan(ran), "", "ours", "real"});
}
BENCHMARK(BM_IdkRenderCommand)->Arg(256)->UseRealTime()->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace idk::bench
