// render_replay.hpp: `idk render [SCENE] --replay F.idkcap --video OUT.mp4 [--frames a:b] [--size WxH]`, called
// by runRender (cmd_render.cpp) once it has parsed the shared render options and loaded the scene.
#pragma once

#include <cstdint>
#include <string>

#include "core/cli.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"

namespace idk::app {

// Frames [first, end) of a capture with `count` records. Text "a:b" (half-open, so "0:100" and "100:200" split a
// video without overlap), "a:" (to the end), ":b", or "a" (that frame only). Throws core::CliError.
struct FrameRange {
    uint64_t first = 0;
    uint64_t end = 0;
};
FrameRange parseFrameRange(const std::string& text, uint64_t count);

// Renders every frame of the range with the same Renderer as `idk render` and encodes them. Returns the exit code.
int runRenderReplay(const core::CliArgs& args, scene::Scene& scene, render::RenderSettings settings, uint32_t width,
                    uint32_t height);

}  // namespace idk::app
