// render_pathtrace.cpp: `idk render [SCENE] --pathtrace --spp N --max-depth D --seed S --light-sampling nee-mis|bsdf
// --sort on|off --traversal auto|bvh|bvh2|rayquery [--denoise] --out F.exr|F.png [--json]`: the GPU wavefront path
// tracer (render/path_tracer.hpp) headless, with a progress bar on stderr when stderr is a terminal. .exr gets the
// linear radiance, .png the raster's display transform (exposure, AgX, sRGB). --json adds a "pathtrace"
// object: spp, maxDepth, traversal, sort, lightSampling, denoised, wallMilliseconds, gpuMilliseconds,
// samplesPerSecond, stageMilliseconds.
#include "app/render_pathtrace.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "app/cli_context.hpp"
#include "render/path_tracer.hpp"
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
    "  --sort on|off    sort rays by material and direction before shading (default off)\n"
    "  --traversal auto|bvh|bvh2|rayquery  auto: VK_KHR_ray_query on a GPU that has it; bvh (our BVH, 8-wide\n"
    "                   compressed nodes) with --fallback and on CPU devices such as lavapipe, whose ray query is far\n"
    "                   slower; bvh2: our binary BVH walk (same hits as bvh)\n"
    "  --denoise        also run the edge-aware denoiser (albedo/normal/depth guided) and write its output\n"
    "  --environment, --env-intensity, --exposure (.png only), --size, --json, --no-validation, --fallback as above\n";

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

void drawProgress(uint32_t done, uint32_t total) {
    constexpr int kWidth = 40;
    const int filled = total ? int(kWidth * uint64_t(done) / total) : kWidth;
    std::fprintf(stderr, "\r[%.*s%*s] %u/%u spp", filled, "########################################", kWidth - filled, "",
                 done, total);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
}

}  // namespace

int runRenderPathTrace(const core::CliArgs& args, const scene::Scene& scene, const render::RenderSettings& settings,
                       uint32_t width, uint32_t height) {
    const std::string out = *args.get("--out");
    render::PathTraceSettings pt;
    pt.spp = parseCount(args, "--spp", "16", 1);
    pt.maxDepth = parseCount(args, "--max-depth", "8", 1);
    pt.seed = parseCount(args, "--seed", "0", 0);
    const std::string lightSampling = oneOf(args, "--light-sampling", "nee-mis", {"nee-mis", "bsdf"});
    pt.nee = lightSampling == "nee-mis";
    const std::string sort = oneOf(args, "--sort", "off", {"on", "off"});
    const std::string traversal = oneOf(args, "--traversal", "auto", {"auto", "bvh", "bvh2", "rayquery"});
    if (traversal == "rayquery" && args.has("--fallback"))
        throw core::CliError("--traversal rayquery contradicts --fallback (which takes our BVH, the portable rung)");

    render::PathTracerOptions options;
    options.traversal = traversal == "bvh"        ? render::PtTraversal::Bvh
                        : traversal == "bvh2"     ? render::PtTraversal::Bvh2
                        : traversal == "rayquery" ? render::PtTraversal::RayQuery
                                                  : render::PtTraversal::Auto;
    options.sortRays = sort == "on";
    options.denoise = args.has("--denoise");
    options.environment = settings.environment;
    options.environmentIntensity = settings.environmentIntensity;

    vk::Context ctx(contextDescFromCli(args));
    vk::ShaderLibrary shaders(ctx);
    render::PathTraceResult result;
    {
        render::PathTracer tracer(ctx, shaders, scene, options);
        const bool terminal = isatty(fileno(stderr)) != 0;
        result = tracer.render(scene::defaultCamera(scene), width, height, pt,
                               terminal ? render::PathTracer::Progress(drawProgress) : render::PathTracer::Progress());
    }
    core::ImageRgba32f image = options.denoise && result.didDenoise ? result.denoised : result.image;
    if (std::filesystem::path(out).extension() == ".png") {
        // The raster's display transform (shared/agx.h, as the tonemap pass): exposure, AgX to display-linear;
        // writeImage applies the sRGB encoding.
        for (size_t i = 0; i < image.pixels.size(); i += 4) {
            const glm::vec3 radiance(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]);
            const glm::vec3 display = gpu::agx(radiance * settings.exposure);
            for (int c = 0; c < 3; ++c) image.pixels[i + c] = display[c];
        }
    }
    core::writeImage(out, image);

    if (args.has("--json") || args.has("--stats")) {
        nlohmann::json j;
        j["device"] = ctx.info().name;
        nlohmann::json p;
        p["spp"] = pt.spp;
        p["maxDepth"] = pt.maxDepth;
        p["seed"] = pt.seed;
        p["traversal"] = render::traversalName(result.traversal);
        p["sort"] = options.sortRays;
        p["lightSampling"] = lightSampling;
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
    if (ctx.validationErrors() != 0) {
        std::fprintf(stderr, "idk render: %u Vulkan validation error(s)\n", ctx.validationErrors());
        return 1;
    }
    std::fprintf(stderr, "idk render: wrote %s (%ux%u, %u spp, %s traversal)\n", out.c_str(), width, height, pt.spp,
                 render::traversalName(result.traversal));
    return options.denoise && !result.didDenoise ? 1 : 0;
}

}  // namespace idk::app
