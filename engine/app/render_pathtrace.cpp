// render_pathtrace.cpp: `idk render [SCENE] --pathtrace --spp N --max-depth D --seed S --light-sampling nee-mis|bsdf
// --sampler sobol|independent --sort on|off --traversal auto|bvh|bvh2|rayquery [--denoise] --out F.exr|F.png
// [--json]`: the GPU wavefront path tracer (render/path_tracer.hpp) headless, with a progress bar on stderr when
// stderr is a terminal. .exr gets the linear radiance, .png the raster's display transform (exposure, AgX, sRGB).
// --json adds a "pathtrace" object: spp, maxDepth, traversal, sort, lightSampling, sampler, denoised,
// wallMilliseconds, gpuMilliseconds, samplesPerSecond, stageMilliseconds.
#include "app/render_pathtrace.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "app/camera_spec.hpp"
#include "app/cli_context.hpp"
#include "app/ladder_report.hpp"
#include "core/image_file.hpp"
#include "render/path_tracer.hpp"
#include "tools/video_writer.hpp"
#include "shared/agx.h"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::app {

const char* const kPathTraceHelp =
    "usage: idk render [SCENE] --pathtrace --out FILE.exr|FILE.png [options]\n"
    "  --pathtrace      render with the GPU wavefront path tracer instead of the rasterizer\n"
    "  --spp N          samples per pixel (default 16)\n"
    "  --max-depth D    longest path in ray segments (default 8; 1 = what the camera sees, 2 = direct light)\n"
    "  --seed S         random seed (default 0; the same seed gives the same image)\n"
    "  --light-sampling nee-mis|bsdf  next-event estimation + MIS (default) or BSDF sampling only (the original's)\n"
    "  --sampler sobol|independent  Owen-scrambled Sobol' points (default; lower error at equal spp) or independent\n"
    "                   PCG random numbers per pixel and sample\n"
    "  --sort on|off    sort rays by material and direction before shading (default off)\n"
    "  --traversal auto|bvh|bvh2|rayquery  auto: the ray-traversal ladder's rung (`idk info`: VK_KHR_ray_query on a\n"
    "                   GPU that has it; our BVH with --fallback and on CPU devices such as lavapipe, whose ray query\n"
    "                   is far slower); bvh (8-wide compressed nodes) / rayquery force the rung (as --rung\n"
    "                   ray-traversal=fallback|native); bvh2: the portable rung with the binary walk (same hits)\n"
    "  --sample-range a:b  render only sample indices a..b-1 of the --seed's sequence and write the raw accumulation\n"
    "                   to --out F.exr (RGB = radiance sum, A = sample count) for `idk merge` (render farms)\n"
    "  --denoise        also run the edge-aware denoiser (albedo/normal/depth guided) and write its output\n"
    "  --sky hdr|atmosphere  the environment: the --environment file (default) or the single-scattering sky of\n"
    "                   --sun-elevation and --sun-azimuth, baked as the raster bakes it (lights with and\n"
    "                   importance-samples that map)\n"
    "  --camera, --orbit, --camera-index, --environment, --env-intensity, --exposure (.png only), --size, --json,\n"
    "  --no-validation, --fallback, --rung as above; --json adds the camera and the rungs that ran\n";

namespace {

uint32_t parseCount(const core::CliArgs& args, const char* flag, const char* fallback, uint32_t minimum) {
    const std::string text = args.get(flag, fallback);
    const double v = core::parseNumber(flag, text);
    if (!(v >= minimum) || v != std::floor(v) || v > 1e9)
        throw core::CliError(std::string(flag) + " '" + text + "': give a whole number >= " + std::to_string(minimum));
    return uint32_t(v);
}

std::string oneOf(const core::CliArgs& args, const char* flag, const char* fallback, std::initializer_list<const char*> allowed) {
    const std::string v = args.get(flag, fallback);
    std::string list;
    for (const char* a : allowed) {
        if (v == a) return v;
        list += list.empty() ? a : std::string("|") + a;
    }
    throw core::CliError(std::string(flag) + " '" + v + "': use " + list);
}

}  // namespace

tools::VideoOptions videoOptionsFromCli(const core::CliArgs& args, double fps) {
    tools::VideoOptions o{.fps = fps};
    o.crf = int(parseCount(args, "--crf", "22", 0));
    if (o.crf > 51) throw core::CliError("--crf '" + *args.get("--crf") + "': give 0..51");
    return o;
}

void drawProgressBar(uint64_t done, uint64_t total, const char* unit) {
    constexpr int kWidth = 40;
    const int filled = total ? int(kWidth * done / total) : kWidth;
    std::fprintf(stderr, "\r[%.*s%*s] %llu/%llu %s", filled, "########################################", kWidth - filled,
                 "", static_cast<unsigned long long>(done), static_cast<unsigned long long>(total), unit);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
}

core::ImageRgba32f displayImage(core::ImageRgba32f image, float exposure) {
    // The raster's display transform (shared/agx.h, as the tonemap pass): exposure, AgX to display-linear;
    // writeImage applies the sRGB encoding.
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
        const glm::vec3 radiance(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]);
        const glm::vec3 display = gpu::agx(radiance * exposure);
        for (int c = 0; c < 3; ++c) image.pixels[i + c] = display[c];
    }
    return image;
}

std::vector<uint8_t> displayBytes(const core::ImageRgba32f& image, float exposure) {
    const core::ImageRgba32f display = displayImage(image, exposure);
    std::vector<uint8_t> bytes(display.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = i % 4 == 3 ? 255 : uint8_t(std::lround(core::linearToSrgb(display.pixels[i]) * 255.0f));
    return bytes;
}

PathTraceCli pathTraceFromCli(const core::CliArgs& args, const render::RenderSettings& settings) {
    PathTraceCli p;
    p.settings.spp = parseCount(args, "--spp", "16", 1);
    p.settings.maxDepth = parseCount(args, "--max-depth", "8", 1);
    p.settings.seed = parseCount(args, "--seed", "0", 0);
    p.lightSampling = oneOf(args, "--light-sampling", "nee-mis", {"nee-mis", "bsdf"});
    p.settings.nee = p.lightSampling == "nee-mis";
    p.settings.sampler = *pathtrace::parseSampler(oneOf(args, "--sampler", "sobol", {"sobol", "independent"}));
    const std::string sort = oneOf(args, "--sort", "off", {"on", "off"});
    const std::string traversal = oneOf(args, "--traversal", "auto", {"auto", "bvh", "bvh2", "rayquery"});
    if (traversal == "rayquery" && args.has("--fallback"))
        throw core::CliError("--traversal rayquery contradicts --fallback (which takes our BVH, the portable rung)");
    p.contextDesc = contextDescFromCli(args);
    if (traversal != "auto") {
        for (const vk::RungForce& f : p.contextDesc.forcedRungs)
            if (f.ladder == "ray-traversal")
                throw core::CliError("--traversal " + traversal + " and --rung ray-traversal=...: give one of them");
        // The tracer follows the ladder (PtTraversal::Auto), so the ladder reports the traversal that ran.
        p.contextDesc.forcedRungs.push_back({"ray-traversal", traversal == "rayquery" ? vk::Rung::Native : vk::Rung::Fallback});
    }
    p.options.traversal = traversal == "bvh2" ? render::PtTraversal::Bvh2 : render::PtTraversal::Auto;
    p.options.sortRays = sort == "on";
    p.options.denoise = args.has("--denoise");
    if (std::optional<std::string> range = args.get("--sample-range")) {
        const size_t colon = range->find(':');
        const std::string a = colon == std::string::npos ? "" : range->substr(0, colon);
        const std::string b = colon == std::string::npos ? "" : range->substr(colon + 1);
        auto whole = [&](const std::string& t) {
            if (t.empty() || t.size() > 9 || t.find_first_not_of("0123456789") != std::string::npos)
                throw core::CliError("--sample-range '" + *range + "': give a:b, sample indices a <= i < b");
            return uint32_t(std::stoul(t));
        };
        const uint32_t first = whole(a), end = whole(b);
        if (end <= first) throw core::CliError("--sample-range '" + *range + "': b must be greater than a");
        if (args.get("--spp")) throw core::CliError("--sample-range a:b sets the sample count: drop --spp");
        if (p.options.denoise) throw core::CliError("--sample-range writes raw sums: drop --denoise (denoise after idk merge)");
        p.settings.firstSample = first;
        p.settings.spp = end - first;
        p.options.readSum = true;
    }
    p.options.environment = settings.environment;
    p.options.environmentIntensity = settings.environmentIntensity;
    p.options.atmosphere = settings.atmosphere;  // `--sky atmosphere`: path-trace under the raster's baked sky
    return p;
}

int runRenderPathTrace(const core::CliArgs& args, const scene::Scene& scene, const render::RenderSettings& settings,
                       uint32_t width, uint32_t height, const std::vector<scene::CameraView>& views, double fps) {
    const std::optional<std::string> video = args.get("--video");
    const std::string out = video ? *video : *args.get("--out");
    const PathTraceCli cli = pathTraceFromCli(args, settings);
    const render::PathTraceSettings& pt = cli.settings;
    const render::PathTracerOptions& options = cli.options;

    std::unique_ptr<vk::Context> ctx = createContext(cli.contextDesc);
    vk::ShaderLibrary shaders(*ctx);
    render::PathTraceResult result;
    {
        render::PathTracer tracer(*ctx, shaders, scene, options);
        std::optional<tools::VideoWriter> writer;
        if (video) writer.emplace(*video, width, height, videoOptionsFromCli(args, fps));
        if (options.readSum && (video || views.size() != 1 || std::filesystem::path(out).extension() != ".exr"))
            throw core::CliError("--sample-range a:b writes one raw accumulation: a single view and --out F.exr");
        const bool terminal = isatty(fileno(stderr)) != 0;
        auto progress = [](uint32_t done, uint32_t total) { drawProgressBar(done, total, "spp"); };
        for (size_t k = 0; k < views.size(); ++k) {
            result = tracer.render(views[k], width, height, pt,
                                   terminal ? render::PathTracer::Progress(progress) : render::PathTracer::Progress());
            if (options.readSum) {
                core::writeImage(out, result.sum);
                continue;
            }
            const core::ImageRgba32f& image = options.denoise && result.didDenoise ? result.denoised : result.image;
            if (writer) {
                writer->addFrame(displayBytes(image, settings.exposure));
                continue;
            }
            const std::filesystem::path path = views.size() > 1 ? turntablePath(out, k, views.size()) : std::filesystem::path(out);
            core::writeImage(path, path.extension() == ".png" ? displayImage(image, settings.exposure) : image);
        }
        if (writer) {
            if (ctx->validationErrors() != 0) writer->abort();
            else writer->finish();
        }
    }

    if (args.has("--json") || args.has("--stats")) {
        nlohmann::json j;
        j["device"] = ctx->info().name;
        j["camera"] = cameraJson(views.back());
        j["frames"] = views.size();
        j["rungs"] = laddersJson(ctx->consultedLadders());
        nlohmann::json p;
        p["spp"] = pt.spp;
        p["maxDepth"] = pt.maxDepth;
        p["seed"] = pt.seed;
        p["traversal"] = render::traversalName(result.traversal);
        p["sort"] = options.sortRays;
        p["lightSampling"] = cli.lightSampling;
        p["sampler"] = pathtrace::samplerName(pt.sampler);
        p["denoised"] = result.didDenoise;
        p["wallMilliseconds"] = result.wallMilliseconds;
        p["gpuMilliseconds"] = result.gpuMilliseconds;
        p["samplesPerSecond"] =
            result.wallMilliseconds > 0 ? double(pt.spp) * width * height / (result.wallMilliseconds / 1000.0) : 0.0;
        nlohmann::json stages = nlohmann::json::object();
        for (const render::PtStageTime& s : result.stageTimes) stages[s.stage] = s.milliseconds;
        p["stageMilliseconds"] = stages;
        j["pathtrace"] = p;
        std::cout << j.dump(2) << "\n";
    }
    if (ctx->validationErrors() != 0) {
        std::fprintf(stderr, "idk render: %u Vulkan validation error(s)\n", ctx->validationErrors());
        return 1;
    }
    std::fprintf(stderr, "idk render: wrote %s (%ux%u, %u spp, %s traversal)\n", out.c_str(), width, height, pt.spp,
                 render::traversalName(result.traversal));
    return options.denoise && !result.didDenoise ? 1 : 0;
}

}  // namespace idk::app
