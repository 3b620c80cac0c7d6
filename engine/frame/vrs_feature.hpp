// vrs_feature.hpp: variable-rate shading (issue 14; IDKEngine's LightingShadingRateClassifier, reference 2.13).
// Each frame classifies 16x16 tiles of its lit image (mean speed from the temporal motion vectors: objects, skins
// and camera; luminance coefficient of variation) into a
// rate per tile; the NEXT frame's deferred lighting and sky shade at those rates. The "vrs" ladder picks how:
// the hardware rungs (VK_KHR_fragment_shading_rate attachment, VK_NV_shading_rate_image) light and draw the sky
// in one fragment pass at rates from a rate image (tile = the device's rate texel); the portable software rung
// (lavapipe and every device without them) shades one anchor pixel per coarse cell in the compute lighting and
// sky passes and reconstructs the rest edge-aware from the G-buffer. Resources exist only while VRS is on.
#pragma once
#include <cstdint>
#include <vector>

#include "frame/frame_context.hpp"
#include "passes/passes.hpp"
#include "vk/pipeline.hpp"
#include "vk/resources.hpp"

namespace idk::frame {

// What the classifier of one frame read and wrote (VrsFeature::captureClassification, tests).
struct VrsCapture {
    uint32_t width = 0, height = 0, tileSize = 0, tilesX = 0;
    std::vector<glm::vec4> lit;       // the lit image it classified (RGBA16F values)
    std::vector<glm::vec2> velocity;  // its per-pixel motion, UV units per frame
    std::vector<uint32_t> rates;      // the rates it wrote for the next frame
};

class VrsFeature {
public:
    explicit VrsFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~VrsFeature();
    VrsFeature(const VrsFeature&) = delete;
    VrsFeature& operator=(const VrsFeature&) = delete;

    // Before lighting: last frame's rates into f.vrsRates (invalid when VRS is off).
    void beginFrame(FrameContext& f);
    // Whether VRS on this device takes a hardware rung (its lighting renders the HDR target as a colour attachment).
    static bool usesHardwareRung(const vk::Context& ctx, const VrsSettings& s) {
        return s.enabled && !s.softwareRung && ctx.ladder("vrs").chosen == vk::Rung::Native;
    }
    // True when a hardware rung shades this frame's lighting and sky (addHardwareLighting replaces both passes).
    bool hardwareRung() const noexcept { return hardware_ != vk::ShadingRateSource::None; }
    // Hardware rungs: lighting + sky into `target` at the rates of f.vrsRates; returns the lit image.
    graph::TextureHandle addHardwareLighting(FrameContext& f, graph::TextureHandle target,
                                             const passes::LightingInputs& inputs);
    // After lighting and sky: the software rung's reconstruction of the pixels they skipped (into f.hdr).
    void addReconstructPass(FrameContext& f);
    // After the lit image is complete: the velocity from the motion vectors, the classifier (rates for the next
    // frame), the overlay.
    void addClassifyPasses(FrameContext& f);

    // Tests: copy each classifying frame's lit image, velocity and new rates to a host-visible buffer;
    // capturedClassification() returns the last completed frame's (empty before one has classified).
    void captureClassification(bool on) { capture_ = on; }
    VrsCapture capturedClassification() const;

    // Pixels lighting + sky shaded in the last frame recorded (read once that frame has completed): the anchors
    // its rates imply, or width * height with VRS off. The same count whatever the rung.
    uint64_t lastShadingInvocations() const;
    // The rates the last frame used (palette index per tile), empty with VRS off; for tests and the viewer.
    std::vector<uint32_t> lastRates() const;
    uint32_t tileSize() const noexcept { return tileSize_; }

private:
    void release();
    void addCapture(FrameContext& f, graph::BufferHandle velocity, graph::BufferHandle rates);

    vk::Context& ctx_;
    vk::Buffer rates_;                  // VrsRatesHeader + rates, persistent: written by frame N, read by N + 1
    std::vector<vk::Buffer> readback_;  // per frame slot: the rates that slot's frame used
    std::vector<vk::Buffer> invocationReadback_;  // hardware rungs, per frame slot: fragment invocations counted
    vk::ShadingRateSource hardware_ = vk::ShadingRateSource::None;
    uint32_t width_ = 0, height_ = 0, tileSize_ = 0, tiles_ = 0, tilesX_ = 0;
    uint32_t lastSlot_ = 0;
    bool lastEnabled_ = false;
    bool capture_ = false;
    vk::Buffer captured_;  // lit RGBA16F, velocity vec2, rate buffer (only while capturing)
    uint32_t capturedWidth_ = 0, capturedHeight_ = 0;
};

}  // namespace idk::frame
