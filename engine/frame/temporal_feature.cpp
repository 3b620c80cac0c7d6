// temporal_feature.cpp: Halton jitter of the projection, motion vectors (with the history copies of animated
// scene buffers; also for VRS alone, without jitter) and the TAA resolve (see temporal_feature.hpp).
#include "frame/temporal_feature.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "frame/frame_inputs.hpp"
#include "passes/temporal_passes.hpp"
#include "shared/temporal_types.h"
#include "vk/transfer.hpp"

namespace idk::frame {

float halton(uint32_t index, uint32_t base) {
    float f = 1.0f, r = 0.0f;
    while (index > 0) {
        f /= float(base);
        r += f * float(index % base);
        index /= base;
    }
    return r;
}

glm::vec2 jitterOffset(uint32_t frame, uint32_t phases) {
    const uint32_t i = frame % std::max(phases, 1u) + 1;  // + 1: Halton index 0 is (0, 0), a corner
    return {halton(i, 2) - 0.5f, halton(i, 3) - 0.5f};
}

glm::mat4 jitteredViewProjection(const glm::mat4& viewProjection, glm::vec2 offsetPixels, uint32_t width,
                                 uint32_t height) {
    // clip.xy -= 2 * offset / size * clip.w: the image moves by -offset, so each pixel centre sees the point that
    // was `offset` away from it. Vulkan NDC y grows down the image like pixel rows.
    const glm::vec2 ndc = -2.0f * offsetPixels / glm::vec2(float(width), float(height));
    return glm::translate(glm::mat4(1.0f), glm::vec3(ndc, 0.0f)) * viewProjection;
}

TemporalFeature::~TemporalFeature() {
    for (vk::Buffer& b : constants_) ctx_.destroy(b);
    if (captured_) ctx_.destroy(captured_);
}

std::vector<glm::vec2> TemporalFeature::capturedMotion() const {
    std::vector<glm::vec2> motion;
    if (!captured_) return motion;
    const auto bits = vk::downloadBuffer<uint32_t>(ctx_, captured_, size_t(capturedWidth_) * capturedHeight_);
    motion.reserve(bits.size());
    for (uint32_t b : bits) motion.push_back(glm::unpackHalf2x16(b));
    return motion;
}

std::vector<float> TemporalFeature::capturedDepth() const {
    if (!captured_) return {};
    const size_t count = size_t(capturedWidth_) * capturedHeight_;
    return vk::downloadBuffer<float>(ctx_, captured_, count, count * sizeof(float));
}

void TemporalFeature::addCapture(FrameContext& f) {
    const VkDeviceSize bytes = 2 * VkDeviceSize(f.width) * f.height * sizeof(uint32_t);  // motion, then depth
    if (!captured_ || captured_.size < bytes) {
        if (captured_) ctx_.destroyDeferred(captured_);
        vk::BufferDesc desc;
        desc.size = bytes;
        desc.memory = vk::MemoryUsage::Readback;
        desc.name = "captured motion vectors";
        desc.category = "readback";
        captured_ = ctx_.createBuffer(desc);
    }
    capturedWidth_ = f.width;
    capturedHeight_ = f.height;
    const graph::BufferHandle target = importBuffer(f.graph, "captured motion vectors", captured_);
    const graph::TextureHandle motion = f.motionVectors, depth = f.gbuffer.depth;
    const uint32_t width = f.width, height = f.height;
    f.graph.addPass(
        "motion_capture",
        [&](graph::PassBuilder& b) {
            b.read(motion, graph::Access::TransferSrc);
            b.read(depth, graph::Access::TransferSrc);
            b.write(target, graph::Access::TransferDst);
            b.sideEffect();
        },
        [motion, depth, target, width, height](graph::PassContext& pc) {
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {width, height, 1};
            vkCmdCopyImageToBuffer(pc.commandBuffer(), pc.image(motion), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   pc.vkBuffer(target), 1, &region);
            region.bufferOffset = VkDeviceSize(width) * height * sizeof(uint32_t);
            vkCmdCopyImageToBuffer(pc.commandBuffer(), pc.image(depth), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   pc.vkBuffer(target), 1, &region);
        });
}

bool TemporalFeature::enabled(const render::RenderSettings& s) {
    return s.temporal.aa == AntiAliasing::Taa || s.temporal.aa == AntiAliasing::Upscale;
}

uint32_t TemporalFeature::jitterPhases(const render::RenderSettings& s) {
    const uint32_t frames = std::max(s.temporal.frames, 1u);
    if (!upscalerRuns(s.temporal)) return frames;
    // The upscaler: 1 / S^2 times as many phases, so each output pixel gets `frames` samples near its centre
    // (FSR2 scales its Halton length by the same ratio).
    const float scale = std::clamp(s.temporal.upscale, 0.5f, 1.0f);
    return uint32_t(std::ceil(float(frames) / (scale * scale) - 1e-3f));
}

uint32_t TemporalFeature::stillFrames(const render::RenderSettings& s) { return enabled(s) ? jitterPhases(s) : 1u; }

bool TemporalFeature::motionVectorsNeeded(const render::RenderSettings& s) { return enabled(s) || s.vrs.enabled; }

void TemporalFeature::beginFrame(FrameContext& f) {
    if (!motionVectorsNeeded(f.settings)) {
        reset_ = true;  // switching TAA back on starts from a fresh history
        havePrevious_ = false;
        return;
    }
    const bool jitter = enabled(f.settings);
    if (previousWidth_ != f.width || previousHeight_ != f.height || jitter != jittered_) reset_ = true;
    jittered_ = jitter;
    if (reset_) {
        frameIndex_ = 0;
        havePrevious_ = false;
    }
    f.unjitteredViewProjection = f.viewProjection;
    if (jitter) {  // VRS alone (--aa none) needs the motion vectors but no jitter
        f.jitterPixels = jitterOffset(frameIndex_, jitterPhases(f.settings));
        f.viewProjection = jitteredViewProjection(f.viewProjection, f.jitterPixels, f.width, f.height);
    }

    if (constants_.empty()) {
        for (uint32_t i = 0; i < f.framesInFlight; ++i) {
            vk::BufferDesc desc;
            desc.size = sizeof(gpu::GpuTemporalFrame);
            desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
            desc.memory = vk::MemoryUsage::Upload;
            desc.name = "temporal constants " + std::to_string(i);
            desc.category = "frame constants";
            constants_.push_back(ctx_.createBuffer(desc));
        }
    }
    gpu::GpuTemporalFrame g{};
    g.viewProjection = f.viewProjection;
    g.unjittered = f.unjitteredViewProjection;
    g.inverseUnjittered = glm::inverse(f.unjitteredViewProjection);
    g.previous = havePrevious_ ? previous_ : f.unjitteredViewProjection;
    g.inversePrevious = glm::inverse(g.previous);
    g.cameraPosition = f.camera.position;
    g.jitterPixels = f.jitterPixels;
    g.previousJitter = havePrevious_ ? previousJitter_ : f.jitterPixels;
    g.extent = glm::uvec2(f.width, f.height);
    const vk::Buffer& buffer = constants_[f.slot % constants_.size()];
    vk::uploadBuffer(ctx_, buffer, &g, sizeof(g));  // host-visible; the frame ring waited for this slot
    frameConstants_ = importBuffer(f.graph, "temporal constants", buffer);
    f.temporalConstants = frameConstants_;

    f.temporalReset = reset_ || !havePrevious_;
    cameraStill_ = havePrevious_ && !reset_ && previous_ == f.unjitteredViewProjection;
    previous_ = f.unjitteredViewProjection;
    previousJitter_ = f.jitterPixels;
    previousWidth_ = f.width;
    previousHeight_ = f.height;
    havePrevious_ = true;
    reset_ = false;
    ++frameIndex_;
}

void TemporalFeature::addMotionVectors(FrameContext& f, render::GpuScene& scene) {
    if (!motionVectorsNeeded(f.settings)) return;
    // A static frame: the same camera, no pose uploaded or vertices deformed this frame (the animation passes
    // write new versions of the scene buffers only when the pose changed), the same lights.
    const bool lightsSame = f.lights && f.lights->size() == previousLights_.size() &&
                            (previousLights_.empty() ||  // memcmp's pointers must not be null, even for 0 bytes
                             std::memcmp(f.lights->data(), previousLights_.data(),
                                         previousLights_.size() * sizeof(gpu::GpuLight)) == 0);
    frameStatic_ = cameraStill_ && lightsSame && f.scene.vertices.version == 0 && f.scene.instances.version == 0;
    if (f.lights) previousLights_ = *f.lights;
    f.temporalStatic = frameStatic_;
    passes::MotionVectorInputs in;
    in.scene = f.scene;
    in.temporal = frameConstants_;
    in.depth = f.gbuffer.depth;
    in.prevVertices = f.scene.vertices;
    in.prevInstances = f.scene.instances;
    // Only animated scenes move instances or deform vertices: their last-frame copies are graph history (a real
    // GPU would copy only the deformed ranges; lavapipe's copy of the whole buffer is cheap next to the raster).
    if (scene.animation() && f.scene.drawCount > 0) {
        in.prevVertices = f.graph.historyBuffer("previous scene vertices");
        in.prevInstances = f.graph.historyBuffer("previous scene instances");
    }
    f.motionVectors = passes::addMotionVectorPass(f.graph, f.ctx, f.shaders, in, &f.log);
    if (capture_) addCapture(f);
    if (scene.animation() && f.scene.drawCount > 0) {
        passes::addBufferHistoryPass(f.graph, "keep_vertices", "previous scene vertices", f.scene.vertices,
                                     scene.vertices().size);
        passes::addBufferHistoryPass(f.graph, "keep_instances", "previous scene instances", f.scene.instances,
                                     scene.instances().size);
    }
}

void TemporalFeature::addResolve(FrameContext& f) {
    if (f.settings.temporal.aa != AntiAliasing::Taa || upscalerRuns(f.settings.temporal))
        return;  // the upscaler resolves in upscale_feature.cpp
    passes::TaaInputs in;
    in.temporal = frameConstants_;
    in.color = f.hdr;
    in.depth = f.gbuffer.depth;
    in.motion = f.motionVectors;
    in.reset = f.temporalReset;
    in.maxWeight = float(std::max(f.settings.temporal.frames, 1u));
    in.clipGamma = f.settings.temporal.clipGamma;
    in.clampHistory = f.settings.temporal.clampHistory;
    in.frameStatic = frameStatic_;
    f.hdr = passes::addTaaPasses(f.graph, f.ctx, f.shaders, in);
}

}  // namespace idk::frame
