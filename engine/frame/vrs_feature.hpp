// vrs_feature.hpp: variable-rate shading (issue 14; IDKEngine's LightingShadingRateClassifier, reference 2.13).
// Each frame classifies 16x16 tiles of its lit image (mean speed, luminance coefficient of variation) into a
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

class VrsFeature {
public:
    explicit VrsFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~VrsFeature();
    VrsFeature(const VrsFeature&) = delete;
    VrsFeature& operator=(const VrsFeature&) = delete;

    // Before lighting: last frame's rates into f.vrsRates (invalid when VRS is off).
    void beginFrame(FrameContext& f);
    // Whether VRS on this device takes a hardware rung (its lighting renders the HDR target as a colour attachment).
    static bool usesHardwareRung(const vk::Context& ctx) { return ctx.ladder("vrs").chosen == vk::Rung::Native; }
    // True when a hardware rung shades this frame's lighting and sky (addHardwareLighting replaces both passes).
    bool hardwareRung() const noexcept { return hardware_ != vk::ShadingRateSource::None; }
    // Hardware rungs: lighting + sky into `target` at the rates of f.vrsRates; returns the lit image.
    graph::TextureHandle addHardwareLighting(FrameContext& f, graph::TextureHandle target,
                                             const passes::LightingInputs& inputs);
    // After lighting and sky: the software rung's reconstruction of the pixels they skipped (into f.hdr).
    void addReconstructPass(FrameContext& f);
    // After the lit image is complete: camera motion, the classifier (rates for the next frame), the overlay.
    void addClassifyPasses(FrameContext& f);

    // Pixels lighting + sky shaded in the last frame recorded (read once that frame has completed): the anchors
    // its rates imply, or width * height with VRS off. The same count whatever the rung.
    uint64_t lastShadingInvocations() const;
    // The rates the last frame used (palette index per tile), empty with VRS off; for tests and the viewer.
    std::vector<uint32_t> lastRates() const;
    uint32_t tileSize() const noexcept { return tileSize_; }

private:
    void release();

    vk::Context& ctx_;
    vk::Buffer rates_;                  // VrsRatesHeader + rates, persistent: written by frame N, read by N + 1
    std::vector<vk::Buffer> readback_;  // per frame slot: the rates that slot's frame used
    std::vector<vk::Buffer> invocationReadback_;  // hardware rungs, per frame slot: fragment invocations counted
    vk::ShadingRateSource hardware_ = vk::ShadingRateSource::None;
    uint32_t width_ = 0, height_ = 0, tileSize_ = 0, tiles_ = 0, tilesX_ = 0;
    uint32_t lastSlot_ = 0;
    bool lastEnabled_ = false;
    glm::mat4 previousViewProjection_{1.0f};
    bool hasPrevious_ = false;
};

}  // namespace idk::frame
