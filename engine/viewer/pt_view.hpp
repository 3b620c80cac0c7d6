// pt_view.hpp: the viewer's path-traced mode (key P, --pathtrace): the GPU wavefront path tracer
// (render/path_tracer.hpp) accumulates progressively, a few samples per frame, and restarts whenever what it
// converges to changes (camera, window size, the time of an animated scene, a path-tracing setting, the
// environment); the mean so far, optionally denoised, is shown with the raster's display transform (exposure, AgX).
// Ports the role of IDKEngine's render-mode switch (Application.cs: rasterizer / path tracer).
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graph/render_graph.hpp"
#include "render/atmosphere.hpp"
#include "render/path_tracer.hpp"
#include "render/render_settings.hpp"
#include "scene/camera.hpp"
#include "scene/scene.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::viewer {

struct PtViewSettings {
    bool enabled = false;          // P, --pathtrace
    bool denoise = false;          // --denoise: show the a-trous denoiser's output
    uint32_t maxDepth = 8;         // --max-depth (ray segments, as `idk render --pathtrace`)
    uint32_t seed = 0;             // --seed: the same seed and sample count give `idk render --pathtrace`'s image
    uint32_t samplesPerFrame = 1;  // panel only: more converges faster per frame, each frame takes longer
};

class PtView {
public:
    PtView(vk::Context& ctx, vk::ShaderLibrary& shaders) : ctx_(ctx), shaders_(shaders) {}
    ~PtView();
    PtView(const PtView&) = delete;
    PtView& operator=(const PtView&) = delete;

    // One frame: waits for the frame `previousFrame` (a timeline value: it may still read the displayed image),
    // restarts the accumulation if anything it depends on changed, adds settings.samplesPerFrame samples,
    // resolves and uploads the displayed image. `scene` is posed at `sceneTime` (scene::evaluateAnimations).
    void update(const scene::Scene& scene, double sceneTime, const scene::CameraView& camera, uint32_t width,
                uint32_t height, const PtViewSettings& settings, const render::RenderSettings& raster,
                uint64_t previousFrame);
    // Copies the displayed image over `target` (a pass of the viewer's frame graph, before the UI).
    graph::TextureHandle addPass(graph::RenderGraph& graph, graph::TextureHandle target) const;

    uint32_t samples() const noexcept { return samples_; }    // accumulated since the last restart
    uint32_t restarts() const noexcept { return restarts_; }  // accumulations begun (the first included)
    const std::string& error() const noexcept { return error_; }  // a pose the tracer refused (panel)
    // The displayed RGBA8 sRGB bytes, top row first (the screenshot in this mode).
    const std::vector<uint8_t>& displayed(uint32_t& width, uint32_t& height) const;

private:
    // What the tracer is built with: a change rebuilds it (PathTracerOptions are fixed per tracer).
    struct TracerKey {
        bool denoise = false;
        std::optional<std::filesystem::path> environment;
        float environmentIntensity = 1.0f;
        render::AtmosphereSettings atmosphere;
    };
    // What one accumulation converges to: a change restarts it.
    struct ImageKey {
        scene::CameraView camera;
        uint32_t width = 0, height = 0;
        double sceneTime = 0.0;
        uint32_t maxDepth = 0, seed = 0;
    };
    static bool same(const TracerKey& a, const TracerKey& b);
    static bool same(const ImageKey& a, const ImageKey& b);

    vk::Context& ctx_;
    vk::ShaderLibrary& shaders_;
    std::unique_ptr<render::PathTracer> tracer_;
    TracerKey tracerKey_;
    std::optional<ImageKey> imageKey_;
    uint32_t samples_ = 0, restarts_ = 0;
    std::string error_;
    vk::Image image_;  // the displayed image (RGBA8, TRANSFER_SRC_OPTIMAL between frames)
    std::vector<uint8_t> bytes_;
};

}  // namespace idk::viewer
