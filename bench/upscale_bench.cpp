// upscale_bench.cpp: the temporal upscaler (--aa taa --upscale S, issue 12) at S = 0.5, 0.67, 0.77 (and at 1 by
// its alias --aa upscale), TAA, and the
// plain full-resolution frame (the peer, measured in the same run) on the embedded Cornell box. Time: a warm
// 1280x720 output frame with history (renderOffscreen, readback included), plus GPU time per pass. Error: over a
// replayed sideways camera path of 16 frames from a cold history at 320x180 output, the mean PSNR and FLIP (of
// display-compressed values c / (1 + c)) of frames 4..15 against each frame's 16x supersampled truth (the
// full-resolution no-AA frame rendered at 4x width and height, box-filtered); "bilinear_*" counters: the same
// path's S x 320x180 no-AA frames upscaled bilinearly (what the upscaler must beat).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "app/default_scene.hpp"
#include "app/flip.hpp"
#include "app/image_compare.hpp"
#include "bench_support.hpp"
#include "core/image_resample.hpp"
#include "frame/upscale_feature.hpp"
#include "render/renderer.hpp"

namespace idk::bench {
namespace {

using core::boxDownsample;  // core/image_resample.hpp
using core::compressed;

constexpr uint32_t kWidth = 1280, kHeight = 720;
constexpr uint32_t kErrorWidth = 320, kErrorHeight = 180, kSuper = 4;
constexpr int kPathFrames = 16, kWarmup = 4;

scene::CameraView pathCamera(const scene::Scene& scene, int i) {
    scene::CameraView c = scene::defaultCamera(scene);
    const glm::vec3 right = glm::normalize(glm::cross(c.forward, c.up));
    c.position += right * (0.006f * float(i)) + c.up * (0.003f * float(i));
    return c;
}

render::RenderSettings hdr() {
    render::RenderSettings s;
    s.output = render::OutputKind::Hdr;
    return s;
}

// The path's supersampled truths (compressed), computed once per run.
const std::vector<core::ImageRgba32f>& truths(const scene::Scene& scene) {
    static std::vector<core::ImageRgba32f> t;
    if (!t.empty()) return t;
    render::Renderer reference(*context(), *shaders(), hdr());
    reference.setScene(scene);
    for (int i = 0; i < kPathFrames; ++i)
        t.push_back(compressed(boxDownsample(
            reference.renderOffscreen(pathCamera(scene, i), kErrorWidth * kSuper, kErrorHeight * kSuper).image,
            kSuper)));
    return t;
}

struct Variant {
    const char* name;
    frame::AntiAliasing aa;
    float scale;
};
// S < 1 with --aa taa runs the upscaler; at S = 1 --aa taa is TAA, so that row uses the alias --aa upscale.
const Variant kVariants[] = {{"full", frame::AntiAliasing::None, 1.0f},  {"taa", frame::AntiAliasing::Taa, 1.0f},
                             {"s0.50", frame::AntiAliasing::Taa, 0.5f},   {"s0.67", frame::AntiAliasing::Taa, 0.67f},
                             {"s0.77", frame::AntiAliasing::Taa, 0.77f},  {"s1.00", frame::AntiAliasing::Upscale, 1.0f}};

void BM_Upscale(benchmark::State& state, const Variant& v) {
    if (!requireDevice(state)) return;
    const scene::Scene scene = app::loadDefaultScene();
    render::RenderSettings settings = hdr();
    settings.temporal.aa = v.aa;
    settings.temporal.upscale = v.scale;
    const bool upscaler = frame::upscalerRuns(settings.temporal);
    std::map<std::string, double> passMs;
    {
        render::Renderer renderer(*context(), *shaders(), settings);
        renderer.setScene(scene);
        const scene::CameraView camera = scene::defaultCamera(scene);
        renderer.renderOffscreen(camera, kWidth, kHeight);  // warm-up: pipelines, graph resources, history
        for (auto _ : state) {
            render::FrameResult frame = renderer.renderOffscreen(camera, kWidth, kHeight);
            for (const vk::ScopeTiming& t : frame.passTimes) passMs[t.name] += t.milliseconds;
            benchmark::DoNotOptimize(frame.image.pixels.data());
        }
    }
    // Error over the replayed path, from a cold history (a fresh renderer).
    const std::vector<core::ImageRgba32f>& truth = truths(scene);
    render::Renderer path(*context(), *shaders(), settings);
    render::Renderer low(*context(), *shaders(), hdr());
    path.setScene(scene);
    low.setScene(scene);
    const VkExtent2D lowSize = frame::UpscaleFeature::renderExtent(settings, kErrorWidth, kErrorHeight);
    double psnr = 0, flip = 0, bilinearPsnr = 0, bilinearFlip = 0;
    for (int i = 0; i < kPathFrames; ++i) {
        const scene::CameraView camera = pathCamera(scene, i);
        const core::ImageRgba32f image = compressed(path.renderOffscreen(camera, kErrorWidth, kErrorHeight).image);
        if (i < kWarmup) continue;
        psnr += app::psnr(app::compareImages(image, truth[size_t(i)]));
        flip += app::computeFlip(image, truth[size_t(i)]).mean;
        if (!upscaler) continue;
        const core::ImageRgba32f lowFrame = low.renderOffscreen(camera, lowSize.width, lowSize.height).image;
        const core::ImageRgba32f up = compressed(core::bilinearUpscale(lowFrame, kErrorWidth, kErrorHeight));
        bilinearPsnr += app::psnr(app::compareImages(up, truth[size_t(i)]));
        bilinearFlip += app::computeFlip(up, truth[size_t(i)]).mean;
    }
    const double n = kPathFrames - kWarmup;
    state.counters["psnr_db"] = psnr / n;
    state.counters["flip"] = flip / n;
    if (upscaler) {
        state.counters["bilinear_psnr_db"] = bilinearPsnr / n;
        state.counters["bilinear_flip"] = bilinearFlip / n;
    }
    const auto iterations = double(state.iterations());
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    const std::string settingsText =
        v.aa == frame::AntiAliasing::None ? std::string("--aa none (full-resolution render, peer)")
        : !upscaler                       ? std::string("--aa taa (16 phases)")
        : v.aa == frame::AntiAliasing::Taa ? "--aa taa --upscale " + std::string(v.name + 1)
                                           : "--aa upscale --upscale " + std::string(v.name + 1);
    const bool peer = v.aa == frame::AntiAliasing::None;
    // The full-resolution row is the others' peer and a row of its own (its error is the no-AA baseline).
    setRow(state, {"upscale", "embedded Cornell box, 1280x720 output (error: 16-frame path at 320x180 vs 16x SSAA)",
                   settingsText, "-", peer ? "" : "BM_Upscale/full", "ours", "real"});
}

[[maybe_unused]] const bool kRegistered = [] {
    for (const Variant& v : kVariants)
        benchmark::RegisterBenchmark((std::string("BM_Upscale/") + v.name).c_str(), BM_Upscale, v)
            ->UseRealTime()->Iterations(3)->Repetitions(3)->Unit(benchmark::kMillisecond);
    return true;
}();

}  // namespace
}  // namespace idk::bench
