// temporal_feature.hpp: sub-pixel jitter, motion vectors and temporal anti-aliasing. beginFrame jitters this
// frame's projection (Halton 2,3) before the frame constants are written; addMotionVectors draws the G-buffer's
// surfaces with this and last frame's transforms (FrameContext::motionVectors, read by TAA and by VRS);
// addResolve blends the lit image with the reprojected history (passes/taa.cpp). Last frame's instances and
// (skinned/morphed) vertices, colour, depth and motion are graph history resources; the camera matrices of the
// last frame are kept here. With --aa none and --vrs on, only the motion vectors (and the last-frame copies of
// animated scene buffers they need) are made, unjittered, for the VRS classifier: no TAA history; with both off,
// nothing is allocated or dispatched. Ports IDKEngine's TAAResolve
// and the jitter/velocity parts of RasterPipeline (reference 2.5).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "frame/frame_context.hpp"
#include "render/gpu_scene.hpp"

namespace idk::frame {

// Halton sequence value of `index` (>= 1) in `base`: the low-discrepancy jitter phases.
float halton(uint32_t index, uint32_t base);
// The sample offset from the pixel centre (pixels, in [-0.5, 0.5)) of jitter phase `frame` of `phases`.
glm::vec2 jitterOffset(uint32_t frame, uint32_t phases);
// `viewProjection` moved so that pixel centres sample the points `offsetPixels` away (in pixels, +x right,
// +y down the image) at a width x height render.
glm::mat4 jitteredViewProjection(const glm::mat4& viewProjection, glm::vec2 offsetPixels, uint32_t width,
                                 uint32_t height);

class TemporalFeature {
public:
    explicit TemporalFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~TemporalFeature();
    TemporalFeature(const TemporalFeature&) = delete;
    TemporalFeature& operator=(const TemporalFeature&) = delete;

    static bool enabled(const render::RenderSettings& s);  // --aa taa or upscale: jitter and motion vectors
    // Motion vectors this frame: TAA and the upscaler, or VRS (its classifier's speed; frame/vrs_feature.hpp).
    static bool motionVectorsNeeded(const render::RenderSettings& s);
    // Length of the Halton jitter sequence: --temporal-frames, or for the upscaler that / S^2.
    static uint32_t jitterPhases(const render::RenderSettings& s);
    // Frames a still needs (the jitter phases with TAA on, else 1).
    static uint32_t stillFrames(const render::RenderSettings& s);
    // The next frame starts a fresh history (a new still, a camera cut) at jitter phase 0.
    void resetHistory() { reset_ = true; }

    // Tests: copy each frame's motion vectors (and depth) into a host-visible buffer; capturedMotion() returns the last
    // completed frame's (uv units, row-major, top row first; zero on background pixels).
    void captureMotion(bool on) { capture_ = on; }
    std::vector<glm::vec2> capturedMotion() const;
    std::vector<float> capturedDepth() const;  // the same frame's G-buffer depth


    void beginFrame(FrameContext& f);                                    // jitter; f.viewProjection, f.jitter...
    void addMotionVectors(FrameContext& f, render::GpuScene& scene);  // f.motionVectors
    void addResolve(FrameContext& f);                                    // f.hdr

private:
    void addCapture(FrameContext& f);

    vk::Context& ctx_;
    std::vector<vk::Buffer> constants_;  // GpuTemporalFrame per frame slot (host-visible)
    graph::BufferHandle frameConstants_;  // this frame's, imported
    uint32_t frameIndex_ = 0;
    bool reset_ = true;
    bool havePrevious_ = false;
    bool jittered_ = false;              // the last frame was jittered (TAA/upscaler), not motion vectors for VRS alone
    glm::mat4 previous_{1.0f};           // last frame's unjittered view-projection
    glm::vec2 previousJitter_{0.0f};
    uint32_t previousWidth_ = 0, previousHeight_ = 0;
    bool cameraStill_ = false;           // this frame's camera equals last frame's
    bool frameStatic_ = false;           // ... and no pose or light changed either
    std::vector<gpu::GpuLight> previousLights_;
    bool capture_ = false;
    vk::Buffer captured_;                // host-visible copy of the motion vectors (only while capturing)
    uint32_t capturedWidth_ = 0, capturedHeight_ = 0;
};

}  // namespace idk::frame
