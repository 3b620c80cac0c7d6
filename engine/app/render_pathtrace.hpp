// render_pathtrace.hpp: `idk render [SCENE] --pathtrace ...`, called by runRender (cmd_render.cpp) once it has parsed
// the shared render options and loaded the scene.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/cli.hpp"
#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "vk/context.hpp"
#include "scene/scene.hpp"
#include "tools/video_writer.hpp"

namespace idk::app {

// The path-tracing options (flag names as `idk render --help` lists them).
extern const char* const kPathTraceHelp;

// Renders `scene` from each of `views` with the GPU wavefront path tracer (one tracer for all of them) and writes
// --out (numbered F_000.exr, ... for several views) or, with --video, one video at `fps`. Returns the exit code.
int runRenderPathTrace(const core::CliArgs& args, const scene::Scene& scene, const render::RenderSettings& settings,
                       uint32_t width, uint32_t height, const std::vector<scene::CameraView>& views, double fps);

// The path-tracing options shared by stills and --replay --pathtrace: settings, tracer options and the context
// description (--traversal bvh|rayquery forces the "ray-traversal" ladder's rung, so the ladder names what ran).
struct PathTraceCli {
    render::PathTraceSettings settings;
    render::PathTracerOptions options;
    std::string lightSampling;
    vk::ContextDesc contextDesc;
};
PathTraceCli pathTraceFromCli(const core::CliArgs& args, const render::RenderSettings& settings);

// Linear radiance -> what a PNG stores: the raster's display transform (exposure, AgX; writeImage encodes sRGB).
core::ImageRgba32f displayImage(core::ImageRgba32f image, float exposure);
// RGBA8 sRGB bytes of displayImage(image) for the video writer (alpha 255).
std::vector<uint8_t> displayBytes(const core::ImageRgba32f& image, float exposure);

// --crf N (default 22, 0 = lossless) and the frame rate as the video writer's options.
tools::VideoOptions videoOptionsFromCli(const core::CliArgs& args, double fps);

// A progress bar on stderr when it is a terminal: "[####   ] 3/10 label".
void drawProgressBar(uint64_t done, uint64_t total, const char* unit);

}  // namespace idk::app
