// lights_bench.cpp: lights, shadows and media (issue 13), each against its exact reference measured in the same run:
//  * OIT rungs on AlphaBlendModeTest (real glTF, BLEND quads), 512x512 HDR: time of a warm frame for the sorted
//    rung (exact reference, peer), weighted blended and fixed-layer; error vs the sorted frame (mean and worst
//    relative RGB) over the pixels the transparency changes: those where the sorted frame differs from the same
//    scene with every BLEND material at alpha 0 (the panes composite nothing there).
//  * Shadows on the embedded Cornell box, 640x360 HDR: cascade/cube/spot maps vs ray-traced masks (our BVH or ray
//    query; exact hard shadows, equal to the CPU oracle in tests/gpu/shadows); error of the maps' frame vs the
//    ray-traced one (mean relative RGB).
//  * Shadow visibility against the CPU oracle (tests/support/shadow_oracle.hpp) on the soft-shadow tests' scene (a
//    floor, a square occluder, a point light; 128x128 HDR, the oracle's own size): per floor pixel the visibility
//    s = (full - ambient) / (unshadowed - ambient) of three frames against the CPU's (a ray to the light for hard
//    shadows; the average of 48 x 48 stratified rays to a 0.3 sphere light for soft ones); rel_error = mean
//    |s - oracle|. Time: one warm frame; the CPU oracle's rows (primary hits + visibility of the same pixels) are
//    the peers.
//  * Volumetrics against the CPU ray march of tests/gpu/volumetrics (tests/support/volumetric_oracle.hpp: floor,
//    box, point light, density 0.3, g 0.3): time of a warm 640x360 frame, off (peer), half and quarter resolution;
//    error of the 128x128 frame vs the march (mean relative RGB, p95; the off row: the error of ignoring the medium).
//  * Atmosphere: the GPU bake of the 256x128 sky (what a sun move costs) vs the CPU integration of the same
//    model (render::atmosphereRadiance, the conformance oracle) as the peer; error = mean (worst) relative radiance
//    against the CPU at the same quadrature (GPU row) and the CPU's own against a fine 256 x 64 quadrature on a
//    32 x 16 subset of the texels (CPU row).
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
#include "support/shadow_oracle.hpp"
#include "support/volumetric_oracle.hpp"

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

void setError(benchmark::State& state, const ImageError& e) {
    state.counters["rel_error"] = e.mean;
    state.counters["worst_rel_error"] = e.worst;
    state.counters["error_pixels"] = double(e.pixels);
}

// One frame of `settings` from a fresh renderer (textures streamed in first).
core::ImageRgba32f renderImage(const scene::Scene& scene, const scene::CameraView& camera,
                               const render::RenderSettings& settings, uint32_t w, uint32_t h) {
    render::Renderer r(*context(), *shaders(), settings);
    r.setScene(scene);
    render::SceneTextureStream textures(*context(), r, scene);
    textures.finishSynchronously();
    return r.renderOffscreen(camera, w, h).image;
}

// Times warm frames of `settings` (GPU time per pass as pass_ms.* counters); returns the last frame.
core::ImageRgba32f timeFrames(benchmark::State& state, const scene::Scene& scene, const scene::CameraView& camera,
                              const render::RenderSettings& settings, uint32_t w, uint32_t h) {
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
        last = std::move(frame.image);
    }
    const auto iterations = double(state.iterations());
    for (const auto& [name, ms] : passMs) state.counters["pass_ms." + name] = ms / iterations;
    return last;
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
    const core::ImageRgba32f frame = timeFrames(state, scene, camera, settings, 512, 512);
    if (!peer) {
        // The pixels the transparency changes: where the sorted frame differs from the panes at alpha 0 (the
        // "over" composite of alpha 0 leaves the opaque frame as it is).
        scene::Scene clear = scene;
        for (scene::Material& m : clear.materials)
            if (m.alphaMode == scene::AlphaMode::Blend) m.baseColorFactor.a = 0.0f;
        const core::ImageRgba32f base = renderImage(clear, camera, sorted, 512, 512);
        setError(state, relativeError(frame, renderImage(scene, camera, sorted, 512, 512), &base));
    }
    setRow(state, {"lights", "AlphaBlendModeTest, 512x512 HDR (error vs sorted over the pixels the panes change)",
                   v.settings, "-", peer ? "" : "BM_Oit/sorted", peer ? "peer" : "ours", "real"});
}

// ---- Shadows ----------------------------------------------------------------------------------------------------
const Variant kShadows[] = {
    {"raytraced", "--shadows raytraced (exact hard shadows, reference, peer)",
     [](render::RenderSettings& s) { s.lightShadows.rayTraced = true; }},
    {"maps", "--shadows maps (cubes 512, cascades/spot 1024, PCF)", [](render::RenderSettings&) {}},
};

void BM_Shadows(benchmark::State& state, const Variant& v) {
    if (!requireDevice(state)) return;
    const scene::Scene scene = app::loadDefaultScene();
    const scene::CameraView camera = scene::defaultCamera(scene);
    render::RenderSettings settings = hdr(), traced = hdr();
    v.apply(settings);
    kShadows[0].apply(traced);
    const bool peer = std::string(v.name) == "raytraced";
    context()->clearConsultedLadders();
    const core::ImageRgba32f frame = timeFrames(state, scene, camera, settings, 640, 360);
    const std::string rungs = rungsThatRan(context()->consultedLadders());
    if (!peer) setError(state, relativeError(frame, renderImage(scene, camera, traced, 640, 360), nullptr));
    setRow(state, {"lights", "embedded Cornell box, 640x360 HDR (error vs ray-traced frame, all pixels)", v.settings,
                   rungs, peer ? "" : "BM_Shadows/raytraced", peer ? "peer" : "ours", "real"});
}

// ---- Shadow visibility against the CPU oracle ---------------------------------------------------------------------
constexpr uint32_t kVisSize = test::kShadowFrameSize;
constexpr float kLightRadius = 0.3f;
constexpr int kSoftOracleRays = 48;  // per side: 2304 stratified directions per pixel, as SoftShadowTest

struct VisibilityCase {
    test::PlacedQuad occluder;
    std::vector<test::PlacedQuad> quads;
    scene::Scene scene;
    glm::vec3 light{0.2f, 2.4f, 0.1f};
    scene::CameraView camera = test::shadowTestCamera({0.0f, 4.0f, 3.5f}, {0.0f, 0.0f, 0.2f});
};

const VisibilityCase& visibilityCase() {  // tests/gpu/shadows/soft_shadow_test.cpp's scene
    static const VisibilityCase c = [] {
        VisibilityCase v;
        v.occluder.centre = {0.0f, 0.8f, 0.0f};
        v.occluder.normal = {0.0f, 1.0f, 0.0f};
        v.occluder.halfSize = {0.5f, 0.5f};
        v.occluder.doubleSided = true;
        v.quads = {test::floorQuad(3.0f), v.occluder};
        v.scene = test::makePlacedQuadScene(v.quads);
        v.scene.lights.push_back(test::pointLight(v.light, 20.0f));
        return v;
    }();
    return c;
}

// The CPU oracle's visibility per interior floor pixel (-1 elsewhere): hard (one ray to the light's centre) or soft.
std::vector<double> cpuVisibility(const VisibilityCase& c, bool soft) {
    const test::PrimaryHits hits = test::primaryHits(c.quads, c.camera);
    std::vector<double> v(size_t(kVisSize) * kVisSize, -1.0);
    for (uint32_t py = 0; py < kVisSize; ++py)
        for (uint32_t px = 0; px < kVisSize; ++px) {
            const size_t i = size_t(py) * kVisSize + px;
            if (hits.quad[i] != 0 || !test::interiorPixel(hits, px, py)) continue;
            v[i] = soft ? test::sphereVisibility({c.occluder}, hits.point[i], glm::dvec3(c.light), kLightRadius,
                                                 kSoftOracleRays)
                        : (test::occludedFrom({c.occluder}, hits.point[i], glm::dvec3(c.light)) ? 0.0 : 1.0);
        }
    return v;
}

const std::vector<double>& oracleVisibility(bool soft) {
    static const std::vector<double> hard = cpuVisibility(visibilityCase(), false);
    static const std::vector<double> sphere = cpuVisibility(visibilityCase(), true);
    return soft ? sphere : hard;
}

struct VisibilityVariant {
    const char* name;
    const char* settings;
    bool gpu, soft, rayTraced;
    uint32_t rays;
};
const VisibilityVariant kVisibility[] = {
    {"cpu_hard", "CPU oracle: one ray per floor pixel to the light (peer of the hard rows)", false, false, false, 0},
    {"maps", "--shadows maps (cube 512, PCF)", true, false, false, 0},
    {"raytraced", "--shadows raytraced (hard)", true, false, true, 0},
    {"cpu_soft", "CPU oracle: 48 x 48 stratified rays per floor pixel to the sphere (peer of the soft rows)", false,
     true, false, 0},
    {"soft4", "--shadows raytraced --light-radius 0.3 --soft-shadow-rays 4 (denoised)", true, true, true, 4},
    {"soft16", "--shadows raytraced --light-radius 0.3 --soft-shadow-rays 16 (denoised)", true, true, true, 16},
    {"soft64", "--shadows raytraced --light-radius 0.3 --soft-shadow-rays 64 (denoised)", true, true, true, 64},
};

void BM_ShadowVisibility(benchmark::State& state, const VisibilityVariant& v) {
    const VisibilityCase& c = visibilityCase();
    const std::string peerName = v.soft ? "BM_ShadowVisibility/cpu_soft" : "BM_ShadowVisibility/cpu_hard";
    const std::string input =
        "floor + square occluder + point light (soft: radius 0.3), 128x128 HDR, error: mean |s - CPU oracle|";
    if (!v.gpu) {
        for (auto _ : state) benchmark::DoNotOptimize(cpuVisibility(c, v.soft).data());
        setRow(state, {"lights", input, v.settings, "-", "", "peer", "real"});
        return;
    }
    if (!requireDevice(state)) return;
    render::RenderSettings settings = test::shadowTestSettings(512);
    settings.pointShadows.maxLights = 8;
    settings.lightShadows.rayTraced = v.rayTraced;
    if (v.soft) {
        settings.lightShadows.lightRadius = kLightRadius;
        settings.lightShadows.softShadowRays = v.rays;
    }
    context()->clearConsultedLadders();
    const core::ImageRgba32f full = timeFrames(state, c.scene, c.camera, settings, kVisSize, kVisSize);
    const std::string rungs = rungsThatRan(context()->consultedLadders());
    render::RenderSettings unshadowedSettings = settings;
    unshadowedSettings.pointShadows.maxLights = 0;
    const core::ImageRgba32f unshadowed = renderImage(c.scene, c.camera, unshadowedSettings, kVisSize, kVisSize);
    scene::Scene dark = c.scene;
    dark.lights[0].intensity = 0.0f;
    const core::ImageRgba32f ambient = renderImage(dark, c.camera, settings, kVisSize, kVisSize);
    const std::vector<double>& oracle = oracleVisibility(v.soft);
    double sum = 0.0, worst = 0.0;
    size_t pixels = 0;
    for (size_t i = 0; i < oracle.size(); ++i) {
        const double lit = test::rgbSum(unshadowed, i) - test::rgbSum(ambient, i);
        if (oracle[i] < 0.0 || lit <= 1e-3) continue;
        const double err = std::abs((test::rgbSum(full, i) - test::rgbSum(ambient, i)) / lit - oracle[i]);
        sum += err;
        worst = std::max(worst, err);
        ++pixels;
    }
    state.counters["rel_error"] = pixels ? sum / double(pixels) : 0.0;
    state.counters["worst_abs_error"] = worst;
    state.counters["error_pixels"] = double(pixels);
    setRow(state, {"lights", input, v.settings, rungs, peerName, "ours", "real"});
}

// ---- Volumetrics ------------------------------------------------------------------------------------------------
const Variant kVolumetrics[] = {
    {"off", "volumetrics off (peer, error: the medium ignored)", [](render::RenderSettings&) {}},
    {"half", "--volumetrics --volumetrics-scale 2", [](render::RenderSettings& s) {
         s.volumetrics.enabled = true;
         s.volumetrics.scale = 2;
     }},
    {"quarter", "--volumetrics --volumetrics-scale 4", [](render::RenderSettings& s) {
         s.volumetrics.enabled = true;
         s.volumetrics.scale = 4;
     }},
};

void BM_Volumetrics(benchmark::State& state, const Variant& v) {
    if (!requireDevice(state)) return;
    static const test::VolumetricCase c = test::volumetricCase();
    render::RenderSettings settings = test::volumetricSettings(c, false, 2);
    v.apply(settings);
    const bool peer = std::string(v.name) == "off";
    timeFrames(state, c.scene, c.camera, settings, 640, 360);
    static const test::VolumetricPrediction march = test::predictVolumetrics(
        c, renderImage(c.scene, c.camera, test::volumetricSettings(c, false, 2), kVisSize, kVisSize), kVisSize);
    const test::RelativeErrors e =
        test::relativeErrors(renderImage(c.scene, c.camera, settings, kVisSize, kVisSize), march.predicted);
    state.counters["rel_error"] = e.mean;
    state.counters["p95_rel_error"] = e.p95;
    setRow(state, {"lights",
                   "floor, box, point light, density 0.3, g 0.3: time 640x360 HDR, error 128x128 vs CPU ray march "
                   "(512 steps, shadowed)",
                   v.settings, "-", peer ? "" : "BM_Volumetrics/off", peer ? "peer" : "ours", "real"});
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
    } else {
        // The shipped quadrature (32 x 8) against a fine one (256 x 64) on every 8th texel of each axis.
        const gpu::GpuAtmosphere params = skyParams(0);
        ImageError e;
        for (uint32_t y = 4; y < kSkyHeight; y += 8)
            for (uint32_t x = 4; x < kSkyWidth; x += 8) {
                const glm::dvec3 d(render::equirectDirection(glm::vec2((x + 0.5f) / kSkyWidth, (y + 0.5f) / kSkyHeight)));
                const glm::dvec3 coarse = render::atmosphereRadiance(params, d, params.viewSamples, params.lightSamples);
                const glm::dvec3 fine = render::atmosphereRadiance(params, d, 256, 64);
                const double rel = glm::length(coarse - fine) / std::max(glm::length(fine), 1e-4);
                e.mean += rel;
                e.worst = std::max(e.worst, rel);
                ++e.pixels;
            }
        state.counters["rel_error"] = e.mean / double(e.pixels);
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
    for (const VisibilityVariant& v : kVisibility)
        reg(std::string("BM_ShadowVisibility/") + v.name, BM_ShadowVisibility, v, v.gpu ? 3 : 1);
    for (const Variant& v : kVolumetrics) reg(std::string("BM_Volumetrics/") + v.name, BM_Volumetrics, v, 3);
    reg("BM_AtmosphereBake/gpu", BM_AtmosphereBake, true, 3);
    reg("BM_AtmosphereBake/cpu", BM_AtmosphereBake, false, 1);
    return true;
}();

}  // namespace
}  // namespace idk::bench
