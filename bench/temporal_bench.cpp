// temporal_bench.cpp: the temporal and screen-space passes (issue 12) on the embedded Cornell box: time of a warm
// 1280x720 frame (renderOffscreen, readback included) with each feature on, against the same frame with all off
// (the peer, measured in the same run), plus GPU time per pass; and the error of the anti-aliased still against
// the 16x supersampled truth (the same frame at 4x width and height, box-filtered), measured once per run at
// 320x180 (the reference is then 1280x720), next to the single-sample frame's: PSNR and FLIP of display-compressed
// values c / (1 + c) (the off row: the single-sample frame's; the all row: against the same passes supersampled
// without AA). SSAO's error: its visibility at 320x180 against ambient occlusion traced through our BVH from
// the same G-buffer (frame/ssao_oracle.cpp). Bloom's: the relative drift of the 320x180 image's total radiance
// (an energy-conserving bloom moves light, it adds or loses none).
#include <benchmark/benchmark.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "app/default_scene.hpp"
#include "app/flip.hpp"
#include "app/image_compare.hpp"
#include "bench_support.hpp"
#include "core/image_resample.hpp"
#include "frame/ssao_oracle.hpp"
#include "render/renderer.hpp"

namespace idk::bench {
namespace {

using core::boxDownsample;  // core/image_resample.hpp
using core::compressed;

constexpr uint32_t kWidth = 1280, kHeight = 720;
constexpr uint32_t kErrorWidth = 320, kErrorHeight = 180, kSuper = 4;

struct Variant {
    const char* name;
    const char* settings;
    std::function<void(render::RenderSettings&)> apply;
    bool stillError;  // measure the still's (and the no-AA frame's) error against the supersampled reference
    bool aoError = false;  // measure SSAO's visibility against ambient occlusion traced through our BVH
    bool energyError = false;  // measure how far the image's total radiance drifts (bloom must conserve it)
};

const Variant kVariants[] = {
    {"off", "all temporal/screen-space passes off (peer), error: the single-sample frame", [](render::RenderSettings&) {},
     true},
    {"taa", "--aa taa, 16 jitter phases, time: one frame with history, error: the converged still and the no-AA frame",
     [](render::RenderSettings& s) { s.temporal.aa = frame::AntiAliasing::Taa; }, true},
    {"bloom", "--bloom (strength 0.04), error: drift of the image's total radiance (energy conservation)",
     [](render::RenderSettings& s) { s.bloom.enabled = true; }, false, false, true},
    {"ssao", "--ssao (16 rays x 4 depth tests, radius 0.2), error: visibility vs 64 BVH-traced rays per pixel",
     [](render::RenderSettings& s) { s.ssao.enabled = true; }, false, true},
    {"all", "--aa taa --bloom --ssao, error: vs the 16x supersampled frame with bloom and SSAO (no AA)",
     [](render::RenderSettings& s) {
         s.temporal.aa = frame::AntiAliasing::Taa;
         s.bloom.enabled = true;
         s.ssao.enabled = true;
     }, true},
};

void BM_TemporalFrame(benchmark::State& state, const Variant& v) {
    const scene::Scene scene = app::loadDefaultScene();
    const scene::CameraView camera = scene::defaultCamera(scene);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    v.apply(settings);
    std::map<std::string, double> passMs;
    {
        render::Renderer renderer(*context(), *shaders(), settings);
        renderer.setScene(scene);
        renderer.renderOffscreen(camera, kWidth, kHeight);  // warm-up: pipelines, graph resources, history
        for (auto _ : state) {
            render::FrameResult frame = renderer.renderOffscreen(camera, kWidth, kHeight);
            for (const vk::ScopeTiming& t : frame.passTimes) passMs[t.name] += t.milliseconds;
            benchmark::DoNotOptimize(frame.image.pixels.data());
        }
        if (v.stillError) {
            // The truth: the same passes without anti-aliasing, supersampled. SSAO's radius is in world units, but
            // bloom's coarsest level is ~10 pixels wide at any size (passes/bloom.cpp bloomLevels), so the truth's
            // glow is narrower: for the all row part of the error is bloom's footprint, not aliasing.
            render::RenderSettings plain = settings;
            plain.temporal.aa = frame::AntiAliasing::None;
            render::Renderer reference(*context(), *shaders(), plain);
            reference.setScene(scene);
            const core::ImageRgba32f truth = compressed(boxDownsample(
                reference.renderOffscreen(camera, kErrorWidth * kSuper, kErrorHeight * kSuper).image, kSuper));
            const core::ImageRgba32f still = compressed(renderer.renderStill(camera, kErrorWidth, kErrorHeight).image);
            const core::ImageRgba32f single = compressed(reference.renderOffscreen(camera, kErrorWidth, kErrorHeight).image);
            state.counters["psnr_db"] = app::psnr(app::compareImages(still, truth));
            state.counters["flip"] = app::computeFlip(still, truth).mean;
            state.counters["noaa_psnr_db"] = app::psnr(app::compareImages(single, truth));
            state.counters["noaa_flip"] = app::computeFlip(single, truth).mean;
        }
        if (v.energyError) {
            // Bloom redistributes light: the sum of the 320x180 image with bloom against the same frame without.
            render::RenderSettings plain;
            plain.output = render::OutputKind::Hdr;
            render::Renderer without(*context(), *shaders(), plain);
            without.setScene(scene);
            const auto total = [](const core::ImageRgba32f& image) {
                double sum = 0.0;
                for (size_t i = 0; i < image.pixels.size(); ++i)
                    if (i % 4 != 3) sum += image.pixels[i];
                return sum;
            };
            const double with = total(renderer.renderOffscreen(camera, kErrorWidth, kErrorHeight).image);
            const double reference = total(without.renderOffscreen(camera, kErrorWidth, kErrorHeight).image);
            state.counters["rel_error"] = reference > 0.0 ? std::abs(with - reference) / reference : 0.0;
        }
        if (v.aoError) {
            // SSAO's visibility at 320x180 against rays traced through our BVH from the same G-buffer's surface
            // points (frame/ssao_oracle.cpp); rel_error = mean |SSAO - traced| / mean traced visibility.
            renderer.ssao().capture(true);
            renderer.renderOffscreen(camera, kErrorWidth, kErrorHeight);
            const frame::AoComparison c =
                frame::compareWithTracedAo(scene, camera, kErrorWidth, kErrorHeight, renderer.ssao().captured(),
                                           settings.ssao.radius, 64, 3);
            state.counters["ao_mae"] = c.mae;
            state.counters["ao_mae_constant_guess"] = c.maeConstant;
            state.counters["ao_correlation"] = c.correlation;
            state.counters["rel_error"] = c.meanTraced > 0.0 ? c.mae / c.meanTraced : 0.0;
        }
    }
    const auto iterations = double(state.iterations());
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    setRow(state, {"temporal", "embedded Cornell box, 1280x720 (error: 320x180 still vs 16x SSAA)", v.settings, "-",
                   std::string(v.name) == "off" ? "" : "BM_TemporalFrame/off",
                   std::string(v.name) == "off" ? "peer" : "ours", "real"});
}

[[maybe_unused]] const bool kRegistered = [] {
    for (const Variant& v : kVariants)
        benchmark::RegisterBenchmark((std::string("BM_TemporalFrame/") + v.name).c_str(), BM_TemporalFrame, v)
            ->UseRealTime()->Iterations(3)->Repetitions(3)->Unit(benchmark::kMillisecond);
    return true;
}();

}  // namespace
}  // namespace idk::bench
