// cmd_render.cpp: `idk render [SCENE] --out F.png|.exr`: loads a glTF scene (default: the embedded Cornell
// box), renders one frame headless (deferred PBR by default, --shading lambert for the foundation's pass) and
// writes the image: .png gets the AgX-tonemapped sRGB frame, .exr the linear radiance before tonemapping.
// --time T [--animation N] poses the scene first (deterministic). --stats lists the passes that ran, their GPU
// times, their indirect draws and GPU memory by category.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/cli_context.hpp"
#include "app/commands.hpp"
#include "app/default_scene.hpp"
#include "app/render_pathtrace.hpp"
#include "app/render_replay.hpp"
#include "app/scene_options.hpp"
#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::app {

const char* const kRenderHelp =
    "usage: idk render [SCENE.gltf|SCENE.glb] --out FILE.png|FILE.exr [options]\n"
    "  SCENE            glTF 2.0 file; without one, the embedded Cornell box is rendered\n"
    "  --out FILE       output image: .png (AgX-tonemapped, 8-bit sRGB) or .exr (linear radiance before\n"
    "                   tonemapping, alpha = geometry coverage; --shading lambert: linear in both)\n"
    "  --size WxH       image size in pixels (default 256x256)\n"
    "  --shading MODE   pbr (deferred glTF PBR, default) or lambert (the foundation's forward pass)\n"
    "  --exposure X     linear exposure before tonemapping (default 1)\n"
    "  --environment F  equirectangular HDR environment (default ../shared/environments/snow_field_puresky_1k.hdr,\n"
    "                   or $IDK_ENVIRONMENT); 'none' = constant grey\n"
    "  --env-intensity X  scale of the sky and ambient light (default 1; 0 = black sky, no ambient)\n"
    "  --time T         pose the scene at T seconds before rendering (keyframes clamped, no looping; the same T\n"
    "                   gives the same image); without --time the file's rest pose is drawn\n"
    "  --animation N    play only animation N (0-based; default: all of them); implies --time 0 when alone\n"
    "  --stats          print the passes that ran, their GPU times and GPU memory by category\n"
    "  --json           print the stats as JSON (implies --stats)\n"
    "  --graph FILE     write the frame's render graph: .dot (graphviz) or any other name (text)\n"
    "  --no-validation  do not load the Vulkan validation layer\n"
    "  --fallback       take the portable rung of every capability ladder (as `idk info --fallback` shows)\n"
    "\n"
    "usage: idk render [SCENE] --replay F.idkcap --video OUT.mp4 [--frames a:b] [--size WxH] [options]\n"
    "  --replay F       render every frame of a camera capture (the viewer's Ctrl+R) at its recorded camera and\n"
    "                   scene time, with the same renderer and options as a still image\n"
    "  --video OUT.mp4  encode the frames with ffmpeg (H.264, yuv420p, the capture's frame rate); odd sizes are\n"
    "                   padded to even with a black column/row; on any error no video is left behind\n"
    "  --frames a:b     only frames a..b-1 (counted from 0; 'a:' to the end), to split a long video across machines\n";

namespace {

nlohmann::json statsJson(const render::FrameResult& frame, const vk::Context& ctx, const vk::MemoryStats& memory) {
    nlohmann::json j;
    j["device"] = ctx.info().name;
    j["passes"] = frame.passesRun;
    nlohmann::json times = nlohmann::json::object();
    for (const vk::ScopeTiming& t : frame.passTimes) times[t.name] = t.milliseconds;
    j["gpuMilliseconds"] = times;
    nlohmann::json draws = nlohmann::json::object();
    for (const passes::IndirectDrawLog::Entry& e : frame.indirectDraws)
        draws[e.pass] = {{"indirectCalls", e.calls}, {"draws", e.draws}};
    j["indirectDraws"] = draws;
    j["memoryBytes"] = memory.bytesByCategory;
    j["deviceMemoryObjects"] = memory.deviceMemoryCount;
    j["reservedBlockBytes"] = memory.blockBytes;
    return j;
}

// --time T [--animation N]: scene::evaluateAnimations before the scene is uploaded (its pose is the first frame's).
void posePerOptions(const core::CliArgs& args, scene::Scene& scene) {
    std::optional<std::string> time = args.get("--time"), animation = args.get("--animation");
    if (!time && !animation) return;
    double t = core::parseNumber("--time", time.value_or("0"));
    if (!std::isfinite(t)) throw core::CliError("--time '" + *time + "': give a finite number of seconds");
    int index = -1;
    if (animation) {
        double n = core::parseNumber("--animation", *animation);
        if (n < 0 || n != std::floor(n) || n >= double(scene.animations.size()))
            throw core::CliError("--animation '" + *animation + "': the scene has " +
                                 std::to_string(scene.animations.size()) + " animation(s), numbered from 0");
        index = int(n);
    }
    scene::evaluateAnimations(scene, t, index);
}

}  // namespace

int runRender(const std::vector<std::string>& argv) {
    core::CliArgs args =
        core::parseCli(argv, withSceneOptions({{"--stats", "--json", "--no-validation", "--fallback", "--help", "--pathtrace", "--denoise"},
                                  {"--out", "--size", "--graph", "--shading", "--exposure", "--environment",
                                   "--env-intensity", "--time", "--animation", "--replay", "--video", "--frames",
                                   "--spp", "--max-depth", "--seed", "--light-sampling", "--sort", "--traversal"}}));
    if (args.has("--help")) {
        std::fputs(kRenderHelp, stdout);
        std::fputs(kSceneOptionsHelp, stdout);
        std::fputs(kPathTraceHelp, stdout);
        return 0;
    }
    if (args.positional.size() > 1) throw core::CliError("more than one scene given");
    std::optional<std::string> out = args.get("--out");
    if (!out && !args.get("--replay")) throw core::CliError("--out FILE is required");
    auto [width, height] = core::parseSize(args.get("--size", "256x256"));
    std::string extension = std::filesystem::path(out.value_or("replay.png")).extension().string();
    if (extension != ".png" && extension != ".exr") {
        throw core::CliError("--out '" + *out + "': the file must end in .png or .exr");
    }

    render::RenderSettings settings;
    std::string shading = args.get("--shading", "pbr");
    if (shading != "pbr" && shading != "lambert")
        throw core::CliError("--shading '" + shading + "': use pbr or lambert");
    settings.shading = shading == "pbr" ? render::Shading::Pbr : render::Shading::Lambert;
    settings.output = extension == ".exr" ? render::OutputKind::Hdr : render::OutputKind::Display;
    settings.exposure = float(core::parseNumber("--exposure", args.get("--exposure", "1")));
    settings.environmentIntensity = float(core::parseNumber("--env-intensity", args.get("--env-intensity", "1")));
    if (std::optional<std::string> env = args.get("--environment"))
        settings.environment = *env == "none" ? std::filesystem::path() : std::filesystem::path(*env);

    // Load first: a bad scene path fails fast, before any Vulkan work.
    scene::Scene scene = args.positional.empty() ? loadDefaultScene() : scene::loadGltf(args.positional[0], loadOptionsFromCli(args));
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "idk render: warning: %s\n", w.c_str());
    posePerOptions(args, scene);
    if (args.get("--replay")) return runRenderReplay(args, scene, settings, width, height);
    if (args.has("--pathtrace")) return runRenderPathTrace(args, scene, settings, width, height);

    vk::Context ctx(contextDescFromCli(args));
    vk::ShaderLibrary shaders(ctx);
    render::FrameResult frame;
    vk::MemoryStats memory;
    {
        render::Renderer renderer(ctx, shaders, settings);
        renderer.setScene(scene);
        render::SceneTextureStream textures(ctx, renderer, scene);
        textures.finishSynchronously();  // a single image wants every texture, not placeholders
        frame = renderer.renderOffscreen(scene::defaultCamera(scene), width, height);
        memory = ctx.allocator().stats();  // while the scene and the graph's resources are alive
    }
    core::writeImage(*out, frame.image);
    if (std::optional<std::string> graphFile = args.get("--graph")) {
        core::writeFileAtomically(
            *graphFile, std::filesystem::path(*graphFile).extension() == ".dot" ? frame.graphDot : frame.graphText);
    }

    if (args.has("--json")) {
        std::cout << statsJson(frame, ctx, memory).dump(2) << "\n";
    } else if (args.has("--stats")) {
        std::printf("passes:\n");
        for (const vk::ScopeTiming& t : frame.passTimes) std::printf("  %-24s %8.3f ms\n", t.name.c_str(), t.milliseconds);
        for (const passes::IndirectDrawLog::Entry& e : frame.indirectDraws)
            std::printf("  %-24s %u indirect call(s), %u draws\n", e.pass.c_str(), e.calls, e.draws);
        std::printf("GPU memory by category:\n");
        for (const auto& [category, bytes] : memory.bytesByCategory)
            std::printf("  %-24s %10.1f KiB\n", category.c_str(), double(bytes) / 1024.0);
    }
    if (ctx.validationErrors() != 0) {
        std::fprintf(stderr, "idk render: %u Vulkan validation error(s)\n", ctx.validationErrors());
        return 1;
    }
    std::fprintf(stderr, "idk render: wrote %s (%ux%u)\n", out->c_str(), width, height);
    return 0;
}

}  // namespace idk::app
