// render_pathtrace.hpp: `idk render [SCENE] --pathtrace ...`, called by runRender (cmd_render.cpp) once it has parsed
// the shared render options and loaded the scene.
#pragma once
#include <cstdint>

#include "core/cli.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"

namespace idk::app {

// The path-tracing options (flag names as `idk render --help` lists them).
extern const char* const kPathTraceHelp;

// Renders `scene` with the GPU wavefront path tracer and writes --out. Returns the exit code.
int runRenderPathTrace(const core::CliArgs& args, const scene::Scene& scene, const render::RenderSettings& settings,
                       uint32_t width, uint32_t height);

}  // namespace idk::app
