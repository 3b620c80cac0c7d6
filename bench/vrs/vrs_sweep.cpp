// vrs_sweep.cpp: idk_vrs_bench, issue 14's benchmark. Replays a camera path (an orbit that accelerates from rest to
// 1.2 rad/s, generated, deterministic) over shared scenes at 1280x720 with VRS off and with VRS on
// for a sweep of the classifier's two factors (SpeedFactor x LumVarianceFactor, the original's 0.2 / 0.04 among
// them), each configuration in its own renderer so its rates follow the path as the viewer's would. Per frame
// after the first: shading invocations of lighting + sky, GPU time of lighting + sky (+ the software rung's
// reconstruction and the classifier with its velocity input, the motion-vector pass included, reported apart), and the error of the displayed frame against VRS off of
// the same frame (PSNR over the sRGB-encoded 8-bit values, and LDR-FLIP). Writes one JSON (bench/vrs_report.py
// turns it into the plot and the BENCHMARKS.md section).
//
// usage: idk_vrs_bench OUT.json [--size 1280x720] [--frames 12] [--scenes helmet,spheres]
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "app/flip.hpp"
#include "core/image_file.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/gltf_loader.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace {

using namespace idk;

const std::map<std::string, std::string> kScenes = {
    {"helmet", "DamagedHelmet/glTF-Binary/DamagedHelmet.glb"},
    {"spheres", "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb"},
};

// Frame i of the path: an orbit around the scene's centre whose angular speed ramps up linearly from rest to
// 1.2 rad/s at 60 frames per second (the frame time VrsSettings assumes), a brisk mouse-look pan.
scene::CameraView pathCamera(const scene::Scene& s, int i, int frames) {
    const glm::vec3 center = (s.bounds.min + s.bounds.max) * 0.5f;
    const float radius = glm::length(s.bounds.max - s.bounds.min) * 0.9f;
    const float maxStep = 1.2f / 60.0f;  // radians per frame at the end of the path
    const float theta = 0.5f * maxStep * float(i * i) / float(std::max(frames - 1, 1));
    return scene::orbitCamera(center, radius, theta, 1.35f);
}

struct Sample {
    double invocations = 0, lightingMs = 0, reconstructMs = 0, classifyMs = 0, psnr = 0, flip = 0;
};

double passMs(const render::FrameResult& f, std::initializer_list<const char*> names) {
    double ms = 0;
    for (const vk::ScopeTiming& t : f.passTimes)
        for (const char* n : names)
            if (t.name == n) ms += t.milliseconds;
    return ms;
}

double psnr8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    double se = 0;
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (i % 4 == 3) continue;
        const double d = (double(a[i]) - double(b[i])) / 255.0;
        se += d * d;
        n++;
    }
    return se == 0 ? 99.0 : -10.0 * std::log10(se / double(n));  // 99: identical
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: idk_vrs_bench OUT.json [--size WxH] [--frames N] [--scenes a,b]\n");
        return 2;
    }
    uint32_t width = 1280, height = 720;
    int frames = 12;
    std::vector<std::string> scenes = {"helmet", "spheres"};
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string k = argv[i], v = argv[i + 1];
        if (k == "--size") std::sscanf(v.c_str(), "%ux%u", &width, &height);
        else if (k == "--frames") frames = std::max(2, std::atoi(v.c_str()));
        else if (k == "--scenes") {
            scenes.clear();
            for (size_t p = 0; p <= v.size();) {
                size_t q = v.find(',', p);
                if (q == std::string::npos) q = v.size();
                scenes.push_back(v.substr(p, q - p));
                p = q + 1;
            }
        } else {
            std::fprintf(stderr, "idk_vrs_bench: unknown option %s\n", k.c_str());
            return 2;
        }
    }
    vk::ContextDesc desc;
    desc.validation = false;
    vk::Context ctx(desc);
    vk::ShaderLibrary shaders(ctx);

    // (speedFactor, lumVarianceFactor); {-1, -1}: VRS off, the reference.
    std::vector<std::pair<float, float>> configs = {{-1.0f, -1.0f}};
    for (float sf : {0.0f, 0.2f, 0.8f})
        for (float lf : {0.02f, 0.04f, 0.08f, 0.16f}) configs.push_back({sf, lf});

    nlohmann::json out;
    out["device"] = ctx.info().name;
    out["size"] = std::to_string(width) + "x" + std::to_string(height);
    out["frames"] = frames;
    out["command"] = "build/bin/idk_vrs_bench bench/results/vrs.json --size " + std::to_string(width) + "x" +
                     std::to_string(height) + " --frames " + std::to_string(frames);
    for (const std::string& name : scenes) {
        if (!kScenes.count(name)) {
            std::fprintf(stderr, "idk_vrs_bench: unknown scene %s\n", name.c_str());
            return 2;
        }
        const scene::Scene scene = scene::loadGltf(std::string(IDK_BENCH_SHARED_DIR) + "/scenes/" + kScenes.at(name));
        std::vector<std::vector<uint8_t>> reference(static_cast<size_t>(frames));
        std::vector<core::ImageRgba32f> referenceLinear(static_cast<size_t>(frames));
        nlohmann::json rows = nlohmann::json::array();
        for (const auto& [sf, lf] : configs) {
            const bool off = sf < 0.0f;
            render::RenderSettings settings;
            settings.vrs.enabled = !off;
            if (!off) {
                settings.vrs.speedFactor = sf;
                settings.vrs.lumVarianceFactor = lf;
            }
            render::Renderer renderer(ctx, shaders, settings);
            renderer.setScene(scene);
            render::SceneTextureStream textures(ctx, renderer, scene);
            textures.finishSynchronously();
            std::vector<Sample> samples;
            for (int i = 0; i < frames; ++i) {
                render::FrameResult f = renderer.renderOffscreen(pathCamera(scene, i, frames), width, height);
                if (off) {
                    reference[size_t(i)] = f.display;
                    referenceLinear[size_t(i)] = f.image;
                }
                if (i == 0) continue;  // VRS's first frame has no rates yet
                Sample s;
                s.invocations = double(f.shadingInvocations);
                s.lightingMs = passMs(f, {"deferred_lighting", "sky"});
                s.reconstructMs = passMs(f, {"vrs_reconstruct"});
                // With --aa none the motion-vector pass runs for VRS alone: its cost is the classifier's.
                s.classifyMs = off ? 0.0
                                   : passMs(f, {"motion_vectors", "vrs_velocity", "vrs_classify", "vrs_rates_readback"});
                s.psnr = off ? 99.0 : psnr8(f.display, reference[size_t(i)]);
                s.flip = off ? 0.0 : app::computeFlip(f.image, referenceLinear[size_t(i)]).mean;
                samples.push_back(s);
            }
            auto med = [&](double Sample::*m) {
                std::vector<double> v;
                for (const Sample& s : samples) v.push_back(s.*m);
                return median(v);
            };
            double meanInv = 0;
            for (const Sample& s : samples) meanInv += s.invocations / double(samples.size());
            nlohmann::json row = {{"vrs", !off},
                                  {"speedFactor", off ? 0.0 : sf},
                                  {"lumVarianceFactor", off ? 0.0 : lf},
                                  {"invocationsMean", meanInv},
                                  {"lightingMsMedian", med(&Sample::lightingMs)},
                                  {"reconstructMsMedian", med(&Sample::reconstructMs)},
                                  {"classifyMsMedian", med(&Sample::classifyMs)},
                                  {"psnrMedian", med(&Sample::psnr)},
                                  {"psnrMin", [&] { double m = 99; for (auto& s : samples) m = std::min(m, s.psnr); return m; }()},
                                  {"flipMedian", med(&Sample::flip)}};
            std::fprintf(stderr, "idk_vrs_bench: %s %s: %.0f invocations, lighting %.2f ms, PSNR %.2f dB\n",
                         name.c_str(), off ? "off" : (std::to_string(sf) + "/" + std::to_string(lf)).c_str(), meanInv,
                         double(row["lightingMsMedian"]), double(row["psnrMedian"]));
            rows.push_back(row);
        }
        out["scenes"][name] = rows;
    }
    std::ofstream(argv[1]) << out.dump(1) << "\n";
    return 0;
}
