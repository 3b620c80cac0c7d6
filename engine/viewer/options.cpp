// options.cpp: parses the idk-viewer command line with the same parser as `idk`.
#include "viewer/options.hpp"

#include <cmath>

#include "app/scene_options.hpp"
#include "core/cli.hpp"
#include "frame/settings_table.hpp"
#include "vk/features.hpp"

namespace idk::viewer {

const char* const kViewerHelp =
    "usage: idk-viewer [SCENE.gltf|SCENE.glb] [options]\n"
    "  SCENE             glTF 2.0 file; without one, the embedded Cornell box\n"
    "  --size WxH        window size (default 1280x720)\n"
    "  --frames N        exit after N rendered frames (default: run until closed)\n"
    "  --screenshot F    write the last frame (before the UI) as PNG F on exit\n"
    "  --script F        timed input script: lines 'FRAME down|up|press KEY', 'FRAME mouse DX DY',\n"
    "                    'FRAME cursor X Y', 'FRAME resize W H' (keys: A..Z, 0..9, SPACE, SHIFT, CTRL, ESCAPE, F11,\n"
    "                    MOUSE_RIGHT...)\n"
    "  --fixed-dt S      advance time by S seconds per frame instead of the wall clock (reproducible scripts)\n"
    "  --no-ui           no ImGui (input still works)\n"
    "  --shader-dir DIR  GLSL sources for hot reload (key 1, --watch); default: the source tree's shaders_glsl\n"
    "  --watch           recompile shaders whose source changed, every frame\n"
    "  --capture F       camera recording file for Ctrl+R / Ctrl+Space (default capture.idkcap)\n"
    "  --no-vsync        start without vsync (V toggles)\n"
    "  --sync-textures   load every texture before the first frame (as idk render) instead of streaming\n"
    "  --no-validation   do not load the Vulkan validation layer\n"
    "  --fallback        take the portable rung of every capability ladder\n"
    "  --rung L=R        force capability ladder L to rung R (repeatable; `idk info` lists them)\n"
    "  --memory-log F    every 100 frames, one JSON line of host RSS and device memory by category (soak runs)\n"
    "  --allow-external-uris  let buffer and image URIs point outside the scene's folder (trusted content only)\n"
    "  --max-memory SIZE refuse a scene whose loading would allocate more than SIZE (e.g. 2G) before allocating\n"
    "  --pathtrace       start in the path-traced mode (P toggles): progressive, restarts when the view changes\n"
    "  --denoise         path-traced mode: show the denoiser's output\n"
    "  --max-depth D     path-traced mode: longest path in ray segments (default 8, as idk render --pathtrace)\n"
    "  --seed S          path-traced mode: random seed (default 0; N frames give idk render --spp N --seed S)\n"
    "controls: W/A/S/D move, Space up, Shift faster, E GUI/FPS mode, T pause time, right-click select (GUI) or\n"
    "  shoot a light (FPS), Ctrl+R record, Ctrl+Space replay, G hide GUI, V vsync, F11 fullscreen, 1 recompile\n"
    "  shaders, P path tracer / rasterizer, Esc exit. Without a display use `idk render SCENE --out F.png`.\n";

ViewerOptions parseViewerOptions(const std::vector<std::string>& argv) {
    core::CliArgs args = core::parseCli(
        argv, frame::withSettingOptions(app::withSceneOptions(
                  {{"--no-ui", "--watch", "--no-vsync", "--sync-textures", "--no-validation", "--fallback", "--help",
                    "--pathtrace", "--denoise"},
                   {"--size", "--frames", "--screenshot", "--script", "--shader-dir", "--capture", "--fixed-dt", "--rung",
                    "--memory-log", "--max-depth", "--seed"}})));
    ViewerOptions o;
    o.help = args.has("--help");
    if (args.positional.size() > 1) throw core::CliError("more than one scene given");
    if (!args.positional.empty()) o.scene = args.positional[0];
    if (auto size = args.get("--size")) std::tie(o.width, o.height) = core::parseSize(*size);
    if (auto frames = args.get("--frames")) {
        double n = core::parseNumber("--frames", *frames);
        if (n < 1 || n != std::floor(n)) throw core::CliError("--frames '" + *frames + "': give a whole number >= 1");
        o.frames = uint64_t(n);
    }
    if (auto dt = args.get("--fixed-dt")) {
        double s = core::parseNumber("--fixed-dt", *dt);
        if (!(s > 0 && s <= 1)) throw core::CliError("--fixed-dt '" + *dt + "': give seconds in (0, 1]");
        o.fixedDt = float(s);
    }
    if (auto f = args.get("--screenshot")) {
        if (std::filesystem::path(*f).extension() != ".png")
            throw core::CliError("--screenshot '" + *f + "': the file must end in .png");
        o.screenshot = *f;
    }
    if (auto f = args.get("--script")) o.script = *f;
    if (auto d = args.get("--shader-dir")) {
        if (!std::filesystem::is_directory(*d)) throw core::CliError("--shader-dir '" + *d + "': not a directory");
        o.shaderDir = *d;
    }
    if (auto f = args.get("--capture")) o.captureFile = *f;
    if (auto f = args.get("--memory-log")) o.memoryLog = *f;
    o.ui = !args.has("--no-ui");
    o.watch = args.has("--watch");
    o.vsync = !args.has("--no-vsync");
    o.syncTextures = args.has("--sync-textures");
    o.validation = !args.has("--no-validation");
    o.fallback = args.has("--fallback");
    for (const std::string& spec : args.getAll("--rung")) {
        try {
            vk::parseRungForce(spec);  // names checked here; what the device can run, once it is open
        } catch (const std::invalid_argument& e) {
            throw core::CliError(e.what());
        }
        o.rungs.push_back(spec);
    }
    o.pathTrace.enabled = args.has("--pathtrace");
    o.pathTrace.denoise = args.has("--denoise");
    auto whole = [&](const char* flag, uint32_t minimum, uint32_t maximum) -> std::optional<uint32_t> {
        std::optional<std::string> text = args.get(flag);
        if (!text) return std::nullopt;
        const double n = core::parseNumber(flag, *text);
        if (!(n >= minimum && n <= maximum) || n != std::floor(n))
            throw core::CliError(std::string(flag) + " '" + *text + "': give a whole number in " + std::to_string(minimum) +
                                 ".." + std::to_string(maximum));
        return uint32_t(n);
    };
    if (auto d = whole("--max-depth", 1, 64)) o.pathTrace.maxDepth = *d;
    if (auto s = whole("--seed", 0, 1000000000)) o.pathTrace.seed = *s;
    o.load = app::loadOptionsFromCli(args);
    frame::applySettingOptions(args, o.settings);
    return o;
}

}  // namespace idk::viewer
