// ssr_bench.cpp: screen-space reflections (issue 12) on the embedded Cornell box with its floor made a mirror
// (metallic 1, roughness 0; the blocks and walls reflect in it): time of a warm 1280x720 frame with --ssr against
// the same frame without (the peer, measured in the same run), GPU time of the SSR passes; and the error of both
// against the GPU path tracer (64 spp, 320x180, measured once per run): the mean absolute radiance difference over
// the pixels whose first hit faces up (the mirror floor and the blocks' tops, from the tracer's normal guide),
// relative to the tracer's mean there, and the PSNR of display-compressed values c / (1 + c) over the whole image.
// The rasterizer's own shading (no GI) differs from the tracer's everywhere: the gap between the two errors is
// SSR's part. The --ssr row carries both (rel_error / psnr_db with SSR, off_rel_error / off_psnr_db without).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <string>

#include "app/default_scene.hpp"
#include "app/image_compare.hpp"
#include "bench_support.hpp"
#include "render/path_tracer.hpp"
#include "render/renderer.hpp"

namespace idk::bench {
namespace {

constexpr uint32_t kWidth = 1280, kHeight = 720;
constexpr uint32_t kErrorWidth = 320, kErrorHeight = 180;

scene::Scene mirrorFloorBox() {
    scene::Scene s = app::loadDefaultScene();
    scene::Material mirror = s.materials.at(0);
    mirror.name = "mirror";
    mirror.metallic = 1.0f;
    mirror.roughness = 0.0f;
    s.materials.push_back(mirror);
    for (scene::Mesh& m : s.meshes)
        if (m.name == "floor")
            for (scene::Primitive& p : m.primitives) p.material = uint32_t(s.materials.size() - 1);
    return s;
}

core::ImageRgba32f compressed(core::ImageRgba32f image) {
    for (size_t i = 0; i < image.pixels.size(); ++i)
        if (i % 4 != 3) image.pixels[i] = std::max(image.pixels[i], 0.0f) / (1.0f + std::max(image.pixels[i], 0.0f));
    return image;
}

struct Reference {
    core::ImageRgba32f image, normal;
};

const Reference& pathTraced(const scene::Scene& scene, const scene::CameraView& camera) {
    static const Reference ref = [&] {
        render::PathTracerOptions options;
        options.readGuides = true;
        render::PathTracer tracer(*context(), *shaders(), scene, options);
        render::PathTraceSettings settings;
        settings.spp = 64;
        render::PathTraceResult r = tracer.render(camera, kErrorWidth, kErrorHeight, settings);
        return Reference{std::move(r.image), std::move(r.normal)};
    }();
    return ref;
}

// Mean |a - ref| / mean ref over the pixels whose first hit faces up.
double upFacingError(const core::ImageRgba32f& img, const Reference& ref) {
    double diff = 0.0, sum = 0.0;
    for (size_t i = 0; i < size_t(kErrorWidth) * kErrorHeight; ++i) {
        if (ref.normal.pixels[i * 4 + 1] < 0.99f) continue;
        for (int c = 0; c < 3; ++c) {
            diff += std::abs(double(img.pixels[i * 4 + c]) - ref.image.pixels[i * 4 + c]);
            sum += ref.image.pixels[i * 4 + c];
        }
    }
    return sum > 0.0 ? diff / sum : 0.0;
}

void BM_SsrFrame(benchmark::State& state, bool ssr) {
    const scene::Scene scene = mirrorFloorBox();
    const scene::CameraView camera = scene::defaultCamera(scene);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.ssr.enabled = ssr;
    std::map<std::string, double> passMs;
    render::Renderer renderer(*context(), *shaders(), settings);
    renderer.setScene(scene);
    renderer.renderOffscreen(camera, kWidth, kHeight);  // warm-up: pipelines, graph resources, SSR's history
    for (auto _ : state) {
        render::FrameResult frame = renderer.renderOffscreen(camera, kWidth, kHeight);
        for (const vk::ScopeTiming& t : frame.passTimes) passMs[t.name] += t.milliseconds;
        benchmark::DoNotOptimize(frame.image.pixels.data());
    }
    const Reference& ref = pathTraced(scene, camera);
    const core::ImageRgba32f still = renderer.renderStill(camera, kErrorWidth, kErrorHeight).image;
    state.counters["rel_error"] = upFacingError(still, ref);
    state.counters["psnr_db"] = app::psnr(app::compareImages(compressed(still), compressed(ref.image)));
    if (ssr) {  // the peer's error next to ours in the same row (the report shows peers' timings only)
        render::RenderSettings plain = settings;
        plain.ssr.enabled = false;
        render::Renderer off(*context(), *shaders(), plain);
        off.setScene(scene);
        const core::ImageRgba32f image = off.renderStill(camera, kErrorWidth, kErrorHeight).image;
        state.counters["off_rel_error"] = upFacingError(image, ref);
        state.counters["off_psnr_db"] = app::psnr(app::compareImages(compressed(image), compressed(ref.image)));
    }
    const auto iterations = double(state.iterations());
    for (const auto& [name, ms] : passMs)
        if (name.rfind("ssr_", 0) == 0) state.counters["pass_ms." + name] = ms / iterations;
    setRow(state, {"screen-space reflections",
                   "embedded Cornell box with a mirror floor, 1280x720 (error: 320x180 vs path tracer 64 spp)",
                   ssr ? "--ssr (64 steps, thickness 0.1), error over up-facing pixels"
                       : "--ssr off (peer): the environment specular term only",
                   "-", ssr ? "BM_SsrFrame/off" : "", ssr ? "ours" : "peer", "real"});
}

[[maybe_unused]] const bool kRegistered = [] {
    for (bool on : {false, true})
        benchmark::RegisterBenchmark(on ? "BM_SsrFrame/ssr" : "BM_SsrFrame/off", BM_SsrFrame, on)
            ->UseRealTime()->Iterations(3)->Repetitions(3)->Unit(benchmark::kMillisecond);
    return true;
}();

}  // namespace
}  // namespace idk::bench
