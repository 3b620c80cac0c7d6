// lights_bench.cpp: lights, shadows and media (issue 13), each against its exact reference measured in the same run:
//  * OIT rungs on AlphaBlendModeTest (real glTF, BLEND quads), 512x512 HDR: time of a warm frame for the sorted
//    rung (exact reference, peer), weighted blended and fixed-layer; error vs the sorted frame (mean and worst
//    relative RGB over the pixels the transparency changes).
//  * Shadows on the embedded Cornell box, 640x360 HDR: cascade/cube/spot maps vs ray-traced masks (our BVH or ray
//    query; exact hard shadows, equal to the CPU oracle in tests/gpu/shadows); error of the maps' frame vs the
//    ray-traced one (mean relative RGB); soft shadows of 5 cm sphere lights, 16 rays (time only). The CPU oracle
//    itself is not timed here (it lives in the tests' support).
//  * Volumetrics on the Cornell box, 640x360: off (peer), half and quarter resolution; error of quarter vs half
//    (no full-resolution rung exists; the tests compare half resolution with a CPU ray march).
//  * Atmosphere: the GPU bake of the 256x128 sky (what a sun move costs) vs the CPU integration of the same
//    model (render::atmosphereRadiance, the conformance oracle) as the peer; error = worst relative radiance.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "app/default_scene.hpp"
#include "bench_support.hpp"
#include "render/atmosphere.hpp"
#include "render/environment.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::bench {
namespace {

struct Variant {
    const char* name;
    const char* settings;
    std::function<void(render::RenderSettings&)> apply;
};

struct ImageError {
    double mean = 0.0, worst = 0.0;
    size_t pixels = 0;
};

// Relative RGB error of `a` against `reference` over the pixels where `reference` differs from `base` (what the
// feature under test changes; all pixels when base is empty).
ImageError relativeError(const core::ImageRgba32f& a, const core::ImageRgba32f& reference,
                         const core::ImageRgba32f* base) {
    ImageError e;
    for (size_t i = 0; i < size_t(reference.width) * reference.height; ++i) {
        double diff = 0.0, norm = 0.0, changed = 0.0;
        for (size_t c = 0; c < 3; ++c) {
            diff += std::pow(double(a.pixels[4 * i + c]) - reference.pixels[4 * i + c], 2.0);
            norm += std::pow(double(reference.pixels[4 * i + c]), 2.0);
            if (base) changed += std::abs(double(base->pixels[4 * i + c]) - reference.pixels[4 * i + c]);
        }
        if (base && changed <= 1e-6) continue;
        const double rel = std::sqrt(diff) / std::max(std::sqrt(norm), 1e-4);
        e.mean += rel;
        e.worst = std::max(e.worst, rel);
        ++e.pixels;
    }
    if (e.pixels) e.mean /= double(e.pixels);
    return e;
}

// Times warm frames of `settings` and, when `reference` is given, stores the frame's error against it.
void timeFrames(benchmark::State& state, const scene::Scene& scene, const scene::CameraView& camera,
                const render::RenderSettings& settings, uint32_t w, uint32_t h, const render::RenderSettings* reference,
                const render::RenderSettings* base) {
    std::map<std::string, double> passMs;
    render::Renderer renderer(*context(), *shaders(), settings);
    renderer.setScene(scene);
    render::SceneTextureStream textures(*context(), renderer, scene);
    textures.finishSynchronously();
    core::ImageRgba32f last = renderer.renderOffscreen(camera, w, h).image;  // warm-up: pipelines, resources
    for (auto _ : state) {
        render::FrameResult frame = renderer.renderOffscreen(camera, w, h);
        for (const vk::ScopeTiming& t : frame.passTimes) passMs[t.name] += t.milliseconds;
        benchmark::DoNotOptimize(frame.image.pixels.data());
    }
    const auto iterations = double(state.iterations());
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    if (!reference) return;
    auto render = [&](const render::RenderSettings& s) {
        render::Renderer r(*context(), *shaders(), s);
        r.setScene(scene);
        render::SceneTextureStream rTextures(*context(), r, scene);
        rTextures.finishSynchronously();
        return r.renderOffscreen(camera, w, h).image;
    };
    const core::ImageRgba32f ref = render(*reference);
    const core::ImageRgba32f unchanged = base ? render(*base) : core::ImageRgba32f{};
    const ImageError e = relativeError(last, ref, base ? &unchanged : nullptr);
    state.counters["rel_error"] = e.mean;
    state.counters["worst_rel_error"] = e.worst;
    state.counters["error_pixels"] = double(e.pixels);
}

render::RenderSettings hdr() {
    render::RenderSettings s;
    s.output = render::OutputKind::Hdr;
    return s;
}

// ---- OIT --------------------------------------------------------------------------------------------------------
const Variant kOit[] = {
    {"sorted", "--oit sorted (exact reference, peer)", [](render::RenderSettings& s) { s.oit = render::OitMode::Sorted; }},
    {"weighted", "--oit weighted", [](render::RenderSettings& s) { s.oit = render::OitMode::Weighted; }},
    {"layers", "--oit layers (10 nearest per pixel)", [](render::RenderSettings& s) { s.oit = render::OitMode::Layers; }},
};

void BM_Oit(benchmark::State& state, const Variant& v) {
    if (!requireDevice(state)) return;
    const scene::Scene scene = scene::loadGltf(sharedScene("AlphaBlendModeTest"));
    const scene::CameraView camera = scene::defaultCamera(scene);
    render::RenderSettings settings = hdr(), sorted = hdr();
    v.apply(settings);
    const bool peer = std::string(v.name) == "sorted";
    timeFrames(state, scene, camera, settings, 512, 512, peer ? nullptr : &sorted, nullptr);
    setRow(state, {"lights", "AlphaBlendModeTest, 512x512 HDR (error vs sorted over all pixels)", v.settings, "-",
                   peer ? "" : "BM_Oit/sorted", peer ? "peer" : "ours", "real"});
}

// ---- Shadows ----------------------------------------------------------------------------------------------------
const Variant kShadows[] = {
    {"raytraced", "--shadows raytraced (exact hard shadows; reference, peer)",
     [](render::RenderSettings& s) { s.lightShadows.rayTraced = true; }},
    {"maps", "--shadows maps (cubes 512, cascades/spot 1024, PCF)", [](render::RenderSettings&) {}},
    {"soft", "--shadows raytraced --light-radius 0.05 --soft-shadow-rays 16 (time only: a different image)",
     [](render::RenderSettings& s) {
         s.lightShadows.rayTraced = true;
         s.lightShadows.lightRadius = 0.05f;
         s.lightShadows.softShadowRays = 16;
     }},
};

void BM_Shadows(benchmark::State& state, const Variant& v) {
    if (!requireDevice(state)) return;
    const scene::Scene scene = app::loadDefaultScene();
    const scene::CameraView camera = scene::defaultCamera(scene);
    render::RenderSettings settings = hdr(), traced = hdr();
    v.apply(settings);
    kShadows[0].apply(traced);
    const bool peer = std::string(v.name) == "raytraced", maps = std::string(v.name) == "maps";
    context()->clearConsultedLadders();
    timeFrames(state, scene, camera, settings, 640, 360, maps ? &traced : nullptr, nullptr);
    setRow(state, {"lights", "embedded Cornell box, 640x360 HDR (error vs ray-traced frame, all pixels)", v.settings,
                   rungsThatRan(context()->consultedLadders()), peer ? "" : "BM_Shadows/raytraced",
                   peer ? "peer" : "ours", "real"});
}

// ---- Volumetrics ------------------------------------------------------------------------------------------------
const Variant kVolumetrics[] = {
    {"off", "volumetrics off (peer)", [](render::RenderSettings&) {}},
    {"half", "--volumetrics --volumetrics-scale 2 (error: reference)", [](render::RenderSettings& s) {
         s.volumetrics.enabled = true;
         s.volumetrics.scale = 2;
     }},
    {"quarter", "--volumetrics --volumetrics-scale 4 (error vs half)", [](render::RenderSettings& s) {
         s.volumetrics.enabled = true;
         s.volumetrics.scale = 4;
     }},
};

void BM_Volumetrics(benchmark::State& state, const Variant& v) {
    if (!requireDevice(state)) return;
    const scene::Scene scene = app::loadDefaultScene();
    const scene::CameraView camera = scene::defaultCamera(scene);
    render::RenderSettings settings = hdr(), half = hdr();
    v.apply(settings);
    kVolumetrics[1].apply(half);
    const bool quarter = std::string(v.name) == "quarter";
    const bool peer = std::string(v.name) == "off";
    timeFrames(state, scene, camera, settings, 640, 360, quarter ? &half : nullptr, nullptr);
    setRow(state, {"lights", "embedded Cornell box, 640x360 HDR, density 0.05, g 0.3", v.settings, "-",
                   peer ? "" : "BM_Volumetrics/off", peer ? "peer" : "ours", "real"});
}

// ---- Atmosphere -------------------------------------------------------------------------------------------------
constexpr uint32_t kSkyWidth = 256, kSkyHeight = 128;

gpu::GpuAtmosphere skyParams(int iteration) {  // the sun moves every iteration, as a bake is triggered by
    return render::earthAtmosphere(render::sunDirection(10.0f + float(iteration % 7), 30.0f), 20.0f, kSkyWidth,
                                   kSkyHeight);
}

core::ImageRgba32f cpuSky(const gpu::GpuAtmosphere& params) {
    core::ImageRgba32f out;
    out.width = kSkyWidth;
    out.height = kSkyHeight;
    out.pixels.assign(size_t(kSkyWidth) * kSkyHeight * 4, 1.0f);
    for (uint32_t y = 0; y < kSkyHeight; ++y)
        for (uint32_t x = 0; x < kSkyWidth; ++x) {
            glm::vec2 uv((x + 0.5f) / kSkyWidth, (y + 0.5f) / kSkyHeight);
            glm::dvec3 r = render::atmosphereRadiance(params, glm::dvec3(render::equirectDirection(uv)),
                                                      params.viewSamples, params.lightSamples);
            for (int c = 0; c < 3; ++c) out.pixels[(size_t(y) * kSkyWidth + x) * 4 + c] = float(r[c]);
        }
    return out;
}

void BM_AtmosphereBake(benchmark::State& state, bool gpu) {
    if (gpu && !requireDevice(state)) return;
    if (gpu) render::bakeAtmosphere(*context(), *shaders(), skyParams(0));  // warm-up: pipeline
    int iteration = 0;
    for (auto _ : state) {
        const gpu::GpuAtmosphere params = skyParams(++iteration);
        core::ImageRgba32f sky = gpu ? render::bakeAtmosphere(*context(), *shaders(), params) : cpuSky(params);
        benchmark::DoNotOptimize(sky.pixels.data());
    }
    if (gpu) {
        const ImageError e = relativeError(render::bakeAtmosphere(*context(), *shaders(), skyParams(0)),
                                           cpuSky(skyParams(0)), nullptr);
        state.counters["rel_error"] = e.mean;
        state.counters["worst_rel_error"] = e.worst;
    }
    setRow(state, {"lights", "atmosphere sky 256x128, quadrature 32 x 8, sun 10-16 degrees",
                   gpu ? "GPU bake + readback (one per sun move)" : "CPU integration of the same model (peer)", "-",
                   gpu ? "BM_AtmosphereBake/cpu" : "", gpu ? "ours" : "peer", "real"});
}

[[maybe_unused]] const bool kRegistered = [] {
    auto reg = [](const std::string& name, auto fn, auto arg, int iterations) {
        benchmark::RegisterBenchmark(name.c_str(), fn, arg)
            ->UseRealTime()->Iterations(iterations)->Repetitions(3)->Unit(benchmark::kMillisecond);
    };
    for (const Variant& v : kOit) reg(std::string("BM_Oit/") + v.name, BM_Oit, v, 5);
    for (const Variant& v : kShadows) reg(std::string("BM_Shadows/") + v.name, BM_Shadows, v, 3);
    for (const Variant& v : kVolumetrics) reg(std::string("BM_Volumetrics/") + v.name, BM_Volumetrics, v, 3);
    reg("BM_AtmosphereBake/gpu", BM_AtmosphereBake, true, 3);
    reg("BM_AtmosphereBake/cpu", BM_AtmosphereBake, false, 1);
    return true;
}();

}  // namespace
}  // namespace idk::bench
