// cmd_render.cpp: `idk render [SCENE] --out F.png|.exr`: loads a glTF scene (default: the embedded Cornell
// box), renders one frame headless (deferred PBR by default, --shading lambert for the foundation's pass) and
// writes the image: .png gets the AgX-tonemapped sRGB frame, .exr the linear radiance before tonemapping.
// --time T [--animation N] poses the scene first (deterministic). --camera/--orbit/--camera-index place the camera
// (app/camera_spec.hpp), --orbit-frames N renders a turntable (N images, or one video with --video), --background
// transparent gives the PNG an alpha channel = geometry coverage (the EXR's alpha). --stats lists the passes that
// ran, their GPU times, their indirect draws and GPU memory by category; --json also the camera and the capability
// rungs the frame ran (the objects `idk info --json` prints), and with --sky atmosphere the sky bakes (skyBakes).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "app/camera_spec.hpp"
#include "app/cli_context.hpp"
#include "app/commands.hpp"
#include "app/default_scene.hpp"
#include "app/ladder_report.hpp"
#include "app/render_pathtrace.hpp"
#include "app/render_replay.hpp"
#include "app/scene_options.hpp"
#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "frame/culling_feature.hpp"
#include "frame/settings_table.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "tools/video_writer.hpp"

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
    "  --variant NAME   KHR_materials_variants: render the file's material variant NAME (an unknown name is a\n"
    "                   usage error listing the file's variants)\n"
    "  --stats          print the passes that ran, their GPU times and GPU memory by category\n"
    "  --json           print the stats as JSON (implies --stats)\n"
    "  --graph FILE     write the frame's render graph: .dot (graphviz) or any other name (text)\n"
    "  --camera eye=X,Y,Z:target=X,Y,Z[:up=X,Y,Z][:yfov=DEG]  look from eye at target (up default +Y, yfov 45)\n"
    "  --orbit theta=DEG,phi=DEG[,radius=R][,target=X,Y,Z][,yfov=DEG]  orbit camera (Khronos render-fidelity\n"
    "                   convention: theta = azimuth around +Y from +Z, phi = polar angle from +Y; without radius\n"
    "                   or target the scene's bounding sphere is fitted into the view, as the default camera)\n"
    "  --camera-index N the file's camera N (0-based, cameras placed by nodes of the default scene)\n"
    "                   without any of the three: the file's first camera, else the auto-fit view of the bounds\n"
    "  --orbit-frames N turntable: N views with theta stepping 360/N degrees from --orbit's (default theta=0,phi=90);\n"
    "                   --out F.png writes F_000.png, F_001.png, ...; --video OUT.mp4 [--fps R] one video instead\n"
    "                   (rasterized, or path-traced with --pathtrace: every view with the same --seed)\n"
    "  --background sky|transparent  transparent: PNG alpha = geometry coverage (1 surface, 0 sky), as the EXR's\n"
    "                   alpha always is (pbr shading, rasterizer only); sky (default): opaque PNG\n"
    "  --no-validation  do not load the Vulkan validation layer\n"
    "  --fallback       take the portable rung of every capability ladder (as `idk info --fallback` shows)\n"
    "  --rung L=R       force capability ladder L to rung R (repeatable; `idk info` lists them; exit 2 when the\n"
    "                   name is unknown or the device cannot run it)\n"
    "\n"
    "usage: idk render [SCENE] --replay F.idkcap --video OUT.mp4 [--frames a:b] [--size WxH] [options]\n"
    "  --replay F       render every frame of a camera capture (the viewer's Ctrl+R) at its recorded camera and\n"
    "                   scene time, with the same renderer and options as a still image\n"
    "  --video OUT.mp4  encode the frames with ffmpeg (H.264, yuv420p, the capture's frame rate); odd sizes are\n"
    "                   padded to even with a black column/row; on any error no video is left behind\n"
    "  --frames a:b     only frames a..b-1 (counted from 0; 'a:' to the end), to split a long video across machines\n"
    "  --crf N          libx264 constant rate factor of --video (default 22; 0 = lossless: decoded frames then\n"
    "                   do not depend on how a video was split into chunks, see `idk farm`)\n"
    "  --pathtrace      path-trace every frame (--spp, --seed, --denoise, ... as below): frame i equals the still\n"
    "                   `--pathtrace --time T --camera eye=...:target=...` of record i with the same --seed;\n"
    "                   --out F.exr|F.png also writes F_0000.exr, ... per frame (with or without --video)\n"
    "\n";

namespace {

nlohmann::json statsJson(const render::FrameResult& frame, const vk::Context& ctx, const vk::MemoryStats& memory,
                         const scene::CameraView& camera, const render::RenderSettings& settings) {
    nlohmann::json j;
    j["device"] = ctx.info().name;
    j["camera"] = cameraJson(camera);
    j["rungs"] = laddersJson(ctx.consultedLadders());
    j["settings"] = frame::settingsJson(settings);
    j["passes"] = frame.passesRun;
    nlohmann::json times = nlohmann::json::object();
    for (const vk::ScopeTiming& t : frame.passTimes) times[t.name] = t.milliseconds;
    j["gpuMilliseconds"] = times;
    nlohmann::json draws = nlohmann::json::object();
    for (const passes::IndirectDrawLog::Entry& e : frame.indirectDraws)
        draws[e.pass] = {{"indirectCalls", e.calls}, {"draws", e.draws}};
    j["indirectDraws"] = draws;
    if (settings.shading == render::Shading::Pbr) j["shadingInvocations"] = frame.shadingInvocations;  // lighting + sky
    if (!frame.geometryPath.empty()) j["geometryPath"] = frame.geometryPath;  // mesh, mdi or indirect (culling off)
    if (settings.atmosphere.enabled) j["skyBakes"] = frame.skyBakes;  // outside the graph: not among "passes"
    if (!frame.culling.empty()) {
        nlohmann::json views = nlohmann::json::object();
        for (const passes::CullingViewStats& v : frame.culling)
            views[v.view] = {{"instancesTested", v.instancesTested}, {"instancesDrawn", v.instancesDrawn},
                             {"trianglesDrawn", v.trianglesDrawn}};
        for (const passes::CullingViewStats& v : frame.culling)
            if (v.meshlets) {
                views[v.view]["meshletsTested"] = v.meshletsTested;
                views[v.view]["meshletsDrawn"] = v.meshletsDrawn;
            }
        j["culling"] = views;
    }
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

int runRender(const std::vector<std::string>& argv) { return runRender(argv, nullptr); }

int runRender(const std::vector<std::string>& argv, std::vector<vk::Ladder>* rungsThatRan) {
    core::CliArgs args =
        core::parseCli(argv, frame::withSettingOptions(withSceneOptions({{"--stats", "--json", "--no-validation", "--fallback", "--help", "--pathtrace", "--denoise"},
                                  {"--out", "--size", "--graph", "--shading", "--environment", "--time", "--animation", "--replay", "--video", "--frames",
                                   "--spp", "--max-depth", "--seed", "--light-sampling", "--sampler", "--sort", "--traversal",
                                   "--camera", "--orbit", "--camera-index", "--orbit-frames", "--background", "--fps",
                                   "--rung", "--sample-range", "--crf", "--variant"}})));
    if (args.has("--help")) {
        std::fputs(kRenderHelp, stdout);
        std::fputs("rasterizer settings (also the viewer's panels and --json's \"settings\"):\n", stdout);
        std::fputs(frame::settingOptionsHelp().c_str(), stdout);
        std::fputs(kSceneOptionsHelp, stdout);
        std::fputs(kPathTraceHelp, stdout);
        return 0;
    }
    if (args.positional.size() > 1) throw core::CliError("more than one scene given");
    std::optional<std::string> out = args.get("--out");
    const bool replay = args.get("--replay").has_value();
    const bool orbitVideo = !replay && args.get("--video").has_value();
    if (orbitVideo && !args.get("--orbit-frames")) throw core::CliError("--video needs --replay F or --orbit-frames N");
    if (!replay && !orbitVideo && !out) throw core::CliError("--out FILE is required");
    if (orbitVideo && out) throw core::CliError("--orbit-frames with --video writes the video only: drop --out");
    auto [width, height] = core::parseSize(args.get("--size", "256x256"));
    std::string extension = std::filesystem::path(out.value_or("replay.png")).extension().string();
    if (extension != ".png" && extension != ".exr") {
        throw core::CliError("--out '" + *out + "': the file must end in .png or .exr");
    }
    const std::string background = args.get("--background", "sky");
    if (background != "sky" && background != "transparent")
        throw core::CliError("--background '" + background + "': use sky or transparent");
    const bool transparent = background == "transparent";
    if (transparent && (args.has("--pathtrace") || replay || orbitVideo))
        throw core::CliError("--background transparent: only for rasterized images (not --pathtrace, --replay, --video)");

    render::RenderSettings settings;
    std::string shading = args.get("--shading", "pbr");
    if (shading != "pbr" && shading != "lambert")
        throw core::CliError("--shading '" + shading + "': use pbr or lambert");
    settings.shading = shading == "pbr" ? render::Shading::Pbr : render::Shading::Lambert;
    if (orbitVideo && settings.shading != render::Shading::Pbr)
        throw core::CliError("--video encodes the display image of --shading pbr, not lambert");
    if (transparent && settings.shading != render::Shading::Pbr)
        throw core::CliError("--background transparent needs --shading pbr (lambert has no coverage)");
    settings.output = extension == ".exr" ? render::OutputKind::Hdr : render::OutputKind::Display;
    frame::applySettingOptions(args, settings);
    if (std::optional<std::string> env = args.get("--environment"))
        settings.environment = *env == "none" ? std::filesystem::path() : std::filesystem::path(*env);
    double fps = 30.0;
    if (std::optional<std::string> f = args.get("--fps")) {
        fps = core::parseNumber("--fps", *f);
        if (!(fps > 0.0 && fps <= 1000.0)) throw core::CliError("--fps '" + *f + "': give a rate in (0, 1000] Hz");
    }
    if (orbitVideo && std::filesystem::path(*args.get("--video")).extension() != ".mp4")
        throw core::CliError("--video '" + *args.get("--video") + "': the file must end in .mp4");

    // Load first: a bad scene path fails fast, before any Vulkan work.
    scene::Scene scene = args.positional.empty() ? loadDefaultScene() : scene::loadGltf(args.positional[0], loadOptionsFromCli(args));
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "idk render: warning: %s\n", w.c_str());
    if (std::optional<std::string> variant = args.get("--variant")) {
        try {
            scene::applyMaterialVariant(scene, *variant);
        } catch (const std::invalid_argument& e) {
            throw core::CliError(std::string("--variant: ") + e.what());
        }
    }
    posePerOptions(args, scene);
    if (args.get("--sample-range") && (replay || orbitVideo || !args.has("--pathtrace")))
        throw core::CliError("--sample-range a:b: only for a path-traced still (--pathtrace --out F.exr)");
    if (replay) return runRenderReplay(args, scene, settings, width, height);
    const std::vector<scene::CameraView> views = camerasFromCli(args, scene);  // usage errors before Vulkan too
    if (args.has("--pathtrace")) return runRenderPathTrace(args, scene, settings, width, height, views, fps);

    std::unique_ptr<vk::Context> ctx = createContext(contextDescFromCli(args));
    if (settings.shading == render::Shading::Pbr)  // --geometry mesh needs the device's mesh shaders
        if (std::string e = frame::CullingFeature::geometryError(*ctx, settings.culling); !e.empty())
            throw core::CliError(e);
    vk::ShaderLibrary shaders(*ctx);
    render::FrameResult frame;
    vk::MemoryStats memory;
    {
        render::Renderer renderer(*ctx, shaders, settings);
        renderer.setScene(scene);
        render::SceneTextureStream textures(*ctx, renderer, scene);
        textures.finishSynchronously();  // a single image wants every texture, not placeholders
        std::optional<tools::VideoWriter> video;
        if (orbitVideo) video.emplace(*args.get("--video"), width, height, videoOptionsFromCli(args, fps));
        for (size_t k = 0; k < views.size(); ++k) {
            // A video is one moving camera (per-frame history); each still converges on its own.
            frame = video ? renderer.renderOffscreen(views[k], width, height) : renderer.renderStill(views[k], width, height);
            if (video) {
                video->addFrame(frame.display);
                continue;
            }
            if (transparent && settings.output == render::OutputKind::Display) {
                // The same frame as linear HDR: its alpha is the geometry coverage the EXR stores.
                renderer.settings().output = render::OutputKind::Hdr;
                const render::FrameResult hdr = renderer.renderStill(views[k], width, height);
                renderer.settings().output = render::OutputKind::Display;
                for (size_t i = 3; i < frame.image.pixels.size(); i += 4) frame.image.pixels[i] = hdr.image.pixels[i];
            }
            core::writeImage(views.size() > 1 ? turntablePath(*out, k, views.size()) : std::filesystem::path(*out),
                             frame.image);
        }
        if (video) {
            if (ctx->validationErrors() != 0) video->abort();
            else video->finish();
        }
        memory = ctx->allocator().stats();  // while the scene and the graph's resources are alive
    }
    if (rungsThatRan) *rungsThatRan = ctx->consultedLadders();
    if (std::optional<std::string> graphFile = args.get("--graph")) {
        core::writeFileAtomically(
            *graphFile, std::filesystem::path(*graphFile).extension() == ".dot" ? frame.graphDot : frame.graphText);
    }

    if (args.has("--json")) {
        std::cout << statsJson(frame, *ctx, memory, views.back(), settings).dump(2) << "\n";
    } else if (args.has("--stats")) {
        std::printf("passes:\n");
        for (const vk::ScopeTiming& t : frame.passTimes) std::printf("  %-24s %8.3f ms\n", t.name.c_str(), t.milliseconds);
        for (const passes::IndirectDrawLog::Entry& e : frame.indirectDraws)
            std::printf("  %-24s %u indirect call(s), %u draws\n", e.pass.c_str(), e.calls, e.draws);
        if (!frame.culling.empty()) {
            std::printf("culling (GPU counters per view, %s, geometry path %s):\n",
                        frame::toString(settings.culling.mode), frame.geometryPath.c_str());
            for (const passes::CullingViewStats& v : frame.culling) {
                std::printf("  %-24s %u of %u instances drawn", v.view.c_str(), v.instancesDrawn, v.instancesTested);
                if (v.meshlets) std::printf(", %u of %u meshlets", v.meshletsDrawn, v.meshletsTested);
                std::printf(", %u triangles\n", v.trianglesDrawn);
            }
        }
        std::printf("GPU memory by category:\n");
        for (const auto& [category, bytes] : memory.bytesByCategory)
            std::printf("  %-24s %10.1f KiB\n", category.c_str(), double(bytes) / 1024.0);
        std::printf("capability rungs that ran:\n");
        for (const vk::Ladder& l : ctx->consultedLadders())
            std::printf("  %-20s %-11s %s\n", l.id.c_str(), vk::rungName(l.chosen), l.reason.c_str());
    }
    if (ctx->validationErrors() != 0) {
        std::fprintf(stderr, "idk render: %u Vulkan validation error(s)\n", ctx->validationErrors());
        return 1;
    }
    const std::string written = orbitVideo        ? *args.get("--video")
                                : views.size() > 1 ? turntablePath(*out, 0, views.size()).string() + " .. " +
                                                         turntablePath(*out, views.size() - 1, views.size()).string()
                                                   : *out;
    std::fprintf(stderr, "idk render: wrote %s (%ux%u)\n", written.c_str(), width, height);
    return 0;
}

}  // namespace idk::app
