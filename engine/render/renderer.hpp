// renderer.hpp: renders one frame of a scene into an offscreen image and reads it back (the headless path of
// `idk render` and of the GPU tests), or into a caller's image without readback (the viewer's swapchain path:
// renderFrame, one code path with the same passes, plus the caller's own passes such as the UI). Builds the frame's render graph from the settings and the scene's
// features, executes it in a frame slot, waits, and returns the pixels with the passes that ran, their GPU
// times and the indirect draws they recorded. Ports the role of IDKEngine's RasterPipeline.Render.
#pragma once
// Frames (RenderSettings::shading):
//   Pbr (default): the frame recipe of engine/frame/frame_recipe.cpp (one line per feature, in frame order)
//   Lambert:       lambert (the foundation's forward pass; linear HDR output)
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image_file.hpp"
#include "frame/frame_recipe.hpp"
#include "graph/resource_pool.hpp"
#include "passes/passes.hpp"
#include "render/gpu_scene.hpp"
#include "render/lambert_scene.hpp"
#include "render/render_settings.hpp"
#include "render/vk_graph_backend.hpp"
#include "scene/camera.hpp"
#include "vk/frames.hpp"
#include "vk/shader_library.hpp"

namespace idk::render {

struct FrameResult {
    // Hdr: linear radiance, alpha = coverage (1 geometry, 0 sky). Lambert: linear radiance, alpha 1.
    // Display: the displayed values decoded to linear, so core::writeImage(.png) re-encodes exactly `display`.
    core::ImageRgba32f image;
    std::vector<uint8_t> display;            // Display: RGBA8 sRGB-encoded, row-major, top row first
    std::vector<std::string> passesRun;      // execution order after culling
    std::vector<vk::ScopeTiming> passTimes;  // GPU time per pass
    std::vector<passes::IndirectDrawLog::Entry> indirectDraws;  // per pass: vkCmdDraw*Indirect calls and draws
    std::string graphText;                   // RenderGraph::toText() of the frame
    std::string graphDot;                    // RenderGraph::toGraphviz() of the frame
    // PBR: pixels shaded by the passes VRS applies to (deferred lighting + sky): width * height with VRS off,
    // the coarse cells' anchors with VRS on (frame/vrs_feature.hpp), whatever the rung. 0 for Lambert.
    uint64_t shadingInvocations = 0;
    std::vector<passes::CullingViewStats> culling;  // GPU culling's counters per view (empty: culling off)
    std::string geometryPath;  // PBR: the camera G-buffer's path, frame::CullingFeature::lastGeometryPath()
    // `--sky atmosphere`: sky bakes so far by this renderer (once per sun move). The bake is one immediate submission
    // outside the frame's graph (its map is read back for the CPU's SH and mip tables), so it is not in passesRun.
    uint32_t skyBakes = 0;
};

// renderFrame's target: the caller's colour image (e.g. a swapchain image). The frame is rendered exactly as
// renderOffscreen renders it (Display output) into the renderer's own RGBA8 scene image, which is blitted into
// the target; then `addPasses` (the UI) may draw over the target in the same graph.
struct FrameTarget {
    graph::PhysicalTexture image;                 // needs TRANSFER_DST usage (plus what addPasses needs)
    graph::ResourceState initial;                 // state when the frame starts (UNDEFINED: contents discarded)
    graph::FinalUse finalUse{graph::Access::Present};
    // Returns the target's last version; gets the version the blit wrote. Runs while the graph is built.
    std::function<graph::TextureHandle(graph::RenderGraph&, graph::TextureHandle target)> addPasses;
    std::vector<VkSemaphoreSubmitInfo> waits;     // e.g. the swapchain's acquire semaphore
    std::vector<VkSemaphoreSubmitInfo> signals;   // e.g. the semaphore present waits on
};

struct FrameInfo {
    std::vector<std::string> passesRun;      // this frame's execution order after culling
    std::vector<vk::ScopeTiming> passTimes;  // GPU time per pass of the PREVIOUS frame (empty for the first)
    uint64_t timelineValue = 0;              // signalled when this frame's commands completed
    // GPU culling's counters per view of the PREVIOUS frame (empty for the first, or when it did not cull) and
    // the geometry path its camera G-buffer took (FrameResult's fields, one frame later).
    std::vector<passes::CullingViewStats> culling;
    std::string geometryPath;
};

class Renderer {
public:
    Renderer(vk::Context& ctx, vk::ShaderLibrary& shaders, RenderSettings settings = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    void setScene(const scene::Scene& scene);  // packs and uploads; replaces the previous scene
    // The scene as posed now (after scene::evaluateAnimations): instance transforms, joint matrices and morph
    // weights reach the next frame (pose_upload and skinning passes, only when something changed).
    void setPose(const scene::Scene& scene);
    // Builds what needs the source scene and was off at setScene (the ray-traced shadows' geometry, once that mode is
    // switched on; frame/rt_shadow_feature.hpp); a cheap no-op otherwise. Callers that change settings between
    // frames (the viewer) call it before each frame with the scene given to setScene.
    void prepareSourceScene(const scene::Scene& scene);
    FrameResult renderOffscreen(const scene::CameraView& camera, uint32_t width, uint32_t height);
    // A still image: with temporal anti-aliasing, a fresh history and settings.temporal.frames jittered frames of
    // the unmoving camera (the last one is returned); otherwise one renderOffscreen. With --culling hiz the frame
    // is preceded by warm-up frames up to the G-buffer (two frames in all before it), so its early phase draws
    // what is visible (the image is the same either way; the counters show two-phase occlusion, as in the
    // viewer's steady state).
    FrameResult renderStill(const scene::CameraView& camera, uint32_t width, uint32_t height);
    // The surface-ID buffer of the unculled G-buffer (PBR): per pixel, row-major from the top, the GpuScene draw and
    // its triangle (gl_PrimitiveID) that the depth test kept, {~0u, ~0u} for the background. The ground truth of
    // which draws and triangles are visible (culling benchmarks). Needs the geometryShader feature.
    std::vector<glm::uvec2> renderSurfaceIds(const scene::CameraView& camera, uint32_t width, uint32_t height);
    // GPU culling's per-draw visibility bits (two-phase occlusion: what the last late phase found visible; empty
    // before a culled frame). Valid once that frame has finished.
    std::vector<uint32_t> cullingVisibility() const { return features_.culling.visibilityBits(); }
    std::vector<uint32_t> cullingMeshletVisibility() const { return features_.culling.meshletVisibilityBits(); }
    // Conformance: keep each Hiz frame's early Hi-Z pyramid (what the late phase tested against) for readback.
    void captureCullingPyramid(bool on) { features_.culling.capturePyramid(on); }
    std::vector<float> cullingEarlyPyramid() const { return features_.culling.earlyPyramid(); }
    // Renders into target.image (size = its extent) and submits without waiting for the GPU (PBR shading,
    // Display output; throws std::logic_error otherwise). Before recording it waits for this renderer's previous
    // frame, so that frame's pass timings can be read and its resources reused.
    FrameInfo renderFrame(const scene::CameraView& camera, const FrameTarget& target);
    // The last renderFrame's image before the caller's passes (RGBA8 sRGB-encoded, top row first, as
    // FrameResult::display): waits for that frame. Empty before the first renderFrame.
    std::vector<uint8_t> readLastFrame(uint32_t& width, uint32_t& height);

    // Lights that are not part of the scene (the viewer's shot lights), appended to the scene's lights from the
    // next frame on; they light, cast point shadows (PointShadowSettings) and move as the caller updates them.
    void setExtraLights(std::vector<gpu::GpuLight> lights) { features_.inputs.setExtraLights(std::move(lights)); }
    // Everything but `shading` may change between frames.
    RenderSettings& settings() noexcept { return settings_; }
    // The PBR path's GPU scene (nullptr for Lambert or before setScene): the texture streamer's setTexture.
    GpuScene* gpuScene() noexcept { return gpuScene_.get(); }
    // The point-shadow cubes of the last frame (nullptr when no light cast one): tests read them back.
    const PointShadowMaps* pointShadowMaps() const noexcept { return features_.pointShadows.maps(); }
    // Variable-rate shading's state (the rates the last frame used): tests and the viewer's overlay read it.
    const frame::VrsFeature& vrs() const noexcept { return features_.vrs; }
    frame::VrsFeature& vrs() noexcept { return features_.vrs; }  // tests: captureClassification
    // Jitter, motion vectors and TAA (tests capture the motion vectors through it).
    frame::TemporalFeature& temporal() noexcept { return features_.temporal; }
    frame::SsaoFeature& ssao() noexcept { return features_.ssao; }  // tests capture its inputs and output
    // The VXGI voxel grid of the last frame and its features (nullptr with --gi none): tests read it back.
    const frame::VxgiFeature& vxgi() const noexcept { return features_.vxgi; }
    frame::VxgiFeature& vxgi() noexcept { return features_.vxgi; }  // tests: setVoxelListCapacity
    // The frame's environment map (tests count the atmosphere's sky bakes: once per sun move).
    const frame::EnvironmentFeature& environment() const noexcept { return features_.environment; }
    // The directional cascades and spot maps of the last frame (nullptr when no light rendered one).
    const LightShadowMaps* lightShadowMaps() const noexcept { return features_.pointShadows.lightMaps(); }
    // Runs inside each frame's command buffer before the frame's graph is built (TextureStreamer::pump goes
    // here: textures it makes ready reach this frame's materials through the scene_update pass).
    void setBeforeFrame(std::function<void(VkCommandBuffer)> hook) { beforeFrame_ = std::move(hook); }

private:
    // Imports `target` as the frame's output and records the frame recipe; returns the output's last version
    // (already marked as the graph's output).
    graph::TextureHandle renderPbr(graph::RenderGraph& graph, const scene::CameraView& camera, uint32_t width,
                                   uint32_t height, const vk::Image& target, passes::IndirectDrawLog& log);
    frame::FrameContext frameContext(graph::RenderGraph& graph, const scene::CameraView& camera, uint32_t width,
                                     uint32_t height, passes::IndirectDrawLog& log);
    // renderStill's warm-up for --culling hiz: the frame up to the G-buffer (frame::recordCullingWarmup).
    // The culling counters of the last frame (camera, then point-shadow faces); valid once it has finished.
    std::vector<passes::CullingViewStats> cullingStats() const;
    std::vector<std::string> warmUpCulling(const scene::CameraView& camera, uint32_t width, uint32_t height);
    std::vector<std::string> runPartialFrame(const scene::CameraView& camera, uint32_t width, uint32_t height,
                         const std::function<void(frame::FrameContext&)>& record);

    vk::Context& ctx_;
    vk::ShaderLibrary& shaders_;
    RenderSettings settings_;
    VkGraphBackend backend_;
    graph::ResourcePool pool_;
    vk::FrameRing frames_;
    GpuLambertScene lambertScene_;
    bool hasLambertScene_ = false;
    std::unique_ptr<GpuScene> gpuScene_;
    frame::Features features_;            // the PBR frame's features and their persistent resources
    vk::StorageImageIndex outputStorage_;  // the frame's output image while it renders
    std::function<void(VkCommandBuffer)> beforeFrame_;
    vk::Image sceneImage_;            // renderFrame's pre-UI image (recreated when the size changes)
    uint64_t lastFrameValue_ = 0;     // timeline value of the last renderFrame
    bool hasTimings_ = false;         // the backend's timestamps belong to a completed renderFrame
};

}  // namespace idk::render
