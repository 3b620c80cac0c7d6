// options.hpp: the idk-viewer command line (what a user types and what tests use to drive the viewer headless of
// a human: a frame count, a screenshot, a timed input script).
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/render_settings.hpp"
#include "scene/gltf_loader.hpp"
#include "viewer/pt_view.hpp"

namespace idk::viewer {

extern const char* const kViewerHelp;

struct ViewerOptions {
    std::optional<std::filesystem::path> scene;       // none: the embedded Cornell box
    uint32_t width = 1280, height = 720;              // window size (--size)
    uint64_t frames = 0;                              // exit after this many rendered frames; 0 = run until closed
    std::optional<std::filesystem::path> screenshot;  // PNG of the last frame's image before the UI
    std::optional<std::filesystem::path> script;      // timed input script (input_script.hpp)
    std::optional<std::filesystem::path> shaderDir;   // GLSL sources for hot reload (default: the build's)
    std::filesystem::path captureFile = "capture.idkcap";  // Ctrl+R writes, Ctrl+Space replays
    std::optional<std::filesystem::path> memoryLog;   // --memory-log: vk::MemoryLog every 100 frames
    std::optional<float> fixedDt;                     // seconds per frame instead of the wall clock (tests)
    bool ui = true;                                   // --no-ui: no ImGui at all
    bool watch = false;                               // poll shader sources every frame
    bool vsync = true;
    bool syncTextures = false;                        // load every texture before the first frame
    bool validation = true;
    bool fallback = false;
    std::vector<std::string> rungs;                   // --rung LADDER=RUNG (repeatable), checked by parseViewerOptions
    bool help = false;
    scene::LoadOptions load;                          // --allow-external-uris, --max-memory (app/scene_options.hpp)
    render::RenderSettings settings;                  // the rasterizer options of frame/settings_table.hpp
    PtViewSettings pathTrace;                         // --pathtrace, --denoise, --max-depth, --seed
};

// Throws core::CliError naming the option.
ViewerOptions parseViewerOptions(const std::vector<std::string>& argv);

}  // namespace idk::viewer
