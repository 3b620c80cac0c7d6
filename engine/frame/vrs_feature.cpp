// vrs_feature.cpp: variable-rate shading's per-frame work: the persistent rate buffer (this frame's classifier
// writes it, the next frame's lighting and sky read it), a copy of the rates in use for the invocation count,
// the velocity field from the temporal motion vectors, the classifier and the overlay (and the tests' capture of
// the classifier's inputs and output). The classifier's reduction takes subgroup
// arithmetic where the "subgroup-arithmetic" ladder allows, else the shared-memory tree.
#include "frame/vrs_feature.hpp"

#include <glm/gtc/packing.hpp>

#include <memory>

#include "frame/frame_inputs.hpp"
#include "frame/vrs_oracle.hpp"
#include "passes/vrs_passes.hpp"
#include "shared/deferred_types.h"
#include "vk/shading_rate.hpp"
#include "vk/transfer.hpp"

namespace idk::frame {

// The software rung packs each 8x8 lighting/sky workgroup's anchors (include/vrs_rates.glsl): one rate per group.
static_assert(gpu::kVrsDefaultTileSize % gpu::kLightingGroupSize == 0 && gpu::kLightingGroupSize == 8);

VrsFeature::~VrsFeature() { release(); }

void VrsFeature::release() {
    if (rates_) ctx_.destroyDeferred(rates_);
    if (captured_) ctx_.destroyDeferred(captured_);
    captured_ = {};
    for (vk::Buffer& b : readback_) ctx_.destroyDeferred(b);
    for (vk::Buffer& b : invocationReadback_) ctx_.destroyDeferred(b);
    readback_.clear();
    invocationReadback_.clear();
    rates_ = {};
}

void VrsFeature::beginFrame(FrameContext& f) {
    lastEnabled_ = f.settings.vrs.enabled;
    width_ = f.width;
    height_ = f.height;
    hardware_ = vk::ShadingRateSource::None;
    if (!lastEnabled_) {
        release();
        return;
    }
    // Consulting the ladder also puts it in --json's "rungs". A hardware rung's tile is the device's rate texel
    // (vk/shading_rate.hpp; the ladder offers the rung only where one fits the classifier); the software rung's is
    // the original's 16x16.
    const vk::Ladder& ladder = f.ctx.ladder("vrs");
    const vk::DeviceCapabilities& caps = f.ctx.capabilities();
    uint32_t tileSize = gpu::kVrsDefaultTileSize;
    if (usesHardwareRung(f.ctx, f.settings.vrs)) {
        const bool nv = ladder.chosenMechanism == "VK_NV_shading_rate_image";
        hardware_ = nv ? vk::ShadingRateSource::NvImage : vk::ShadingRateSource::KhrAttachment;
        tileSize = nv ? vk::nvShadingRateTile(caps.shadingRateTexelNv).size
                      : vk::khrShadingRateTile(caps.shadingRateAttachmentTexel).size;
    }
    const uint32_t tilesX = (f.width + tileSize - 1) / tileSize, tilesY = (f.height + tileSize - 1) / tileSize;
    if (!rates_ || tilesX * tilesY != tiles_ || tilesX != tilesX_ || tileSize != tileSize_ ||
        readback_.size() != f.framesInFlight || invocationReadback_.size() != (hardwareRung() ? f.framesInFlight : 0)) {
        release();
        tileSize_ = tileSize;
        tilesX_ = tilesX;
        tiles_ = tilesX * tilesY;
        // Header + all tiles at 1x1: the first frame shades fully (there is nothing to classify yet).
        std::vector<uint32_t> init(4 + tiles_, 0u);
        init[0] = tileSize;
        init[1] = tilesX;
        init[2] = tilesY;
        const VkDeviceSize bytes = init.size() * sizeof(uint32_t);
        rates_ = vk::createBufferWithData(ctx_, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly,
                                                 "vrs rates", "vrs"}, init.data(), bytes);
        for (uint32_t i = 0; i < f.framesInFlight; ++i) {
            readback_.push_back(ctx_.createBuffer({bytes, 0, vk::MemoryUsage::Readback, "vrs rates readback", "vrs"}));
            if (hardwareRung())
                invocationReadback_.push_back(
                    ctx_.createBuffer({4, 0, vk::MemoryUsage::Readback, "vrs invocations readback", "vrs"}));
        }
    }
    // Last written by the previous frame's classifier (a compute storage write).
    f.vrsRates = importBuffer(f.graph, "vrs rates", rates_,
                              graph::stateAfterAccess(graph::Access::StorageReadWrite, graph::ResourceKind::Buffer,
                                                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT));
    // The rates this frame uses, for the shading-invocation count once the frame has completed.
    lastSlot_ = f.slot;
    graph::PhysicalBuffer p;
    p.buffer = readback_[f.slot].buffer;
    p.size = readback_[f.slot].size;
    p.address = readback_[f.slot].address;
    graph::BufferHandle copy = f.graph.importBuffer("vrs rates readback", p, graph::ResourceState{},
                                                    graph::FinalUse{graph::Access::HostRead});
    auto copied = std::make_shared<graph::BufferHandle>();
    const graph::BufferHandle rates = f.vrsRates;
    f.graph.addPass(
        "vrs_rates_readback",
        [&](graph::PassBuilder& b) {
            b.read(rates, graph::Access::TransferSrc);
            *copied = b.write(copy, graph::Access::TransferDst);
        },
        [rates, copied](graph::PassContext& pc) {
            VkBufferCopy region{0, 0, pc.buffer(rates).size};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(rates), pc.vkBuffer(*copied), 1, &region);
        });
    f.graph.markOutput(*copied);
    if (f.settings.vrs.testShadedOnly && f.settings.output == render::OutputKind::Hdr && !hardwareRung())
        f.output = passes::addVrsReconstructPass(f.graph, f.ctx, f.shaders, f.gbuffer, f.frameConstants, f.vrsRates,
                                                 f.output, true);
}

void VrsFeature::addReconstructPass(FrameContext& f) {
    if (!f.vrsRates.valid() || f.settings.vrs.testShadedOnly || hardwareRung()) return;
    f.hdr = passes::addVrsReconstructPass(f.graph, f.ctx, f.shaders, f.gbuffer, f.frameConstants, f.vrsRates, f.hdr);
}

void VrsFeature::addClassifyPasses(FrameContext& f) {
    if (!f.vrsRates.valid()) return;
    if (f.settings.vrs.fixedRate >= 0) {
        // Every tile at one rate: the rates part of the buffer filled with the palette index.
        graph::BufferHandle rates = f.vrsRates;
        auto written = std::make_shared<graph::BufferHandle>();
        const uint32_t rate = uint32_t(f.settings.vrs.fixedRate), tiles = tiles_;
        f.graph.addPass(
            "vrs_fixed_rates", [&](graph::PassBuilder& b) { *written = b.write(rates, graph::Access::TransferDst); },
            [written, rate, tiles](graph::PassContext& pc) {
                vkCmdFillBuffer(pc.commandBuffer(), pc.vkBuffer(*written), sizeof(gpu::VrsRatesHeader),
                                VkDeviceSize(tiles) * 4, rate);
            });
        f.graph.markOutput(*written);
        if (f.settings.vrs.debug) f.hdr = passes::addVrsOverlayPass(f.graph, f.ctx, f.shaders, *written, f.hdr);
        return;
    }
    // Speed from the temporal motion vectors (the temporal feature makes them whenever VRS is on): object, skinned
    // and camera motion; the background moves with the camera. Zero on a first frame or after a reset.
    const graph::BufferHandle velocity = passes::addVrsVelocityPass(f.graph, f.ctx, f.shaders, f.temporalConstants,
                                                                    f.motionVectors, f.gbuffer.depth);
    passes::VrsClassifyParams params;
    params.tileSize = tileSize_;
    params.subgroupReduce = f.ctx.ladder("subgroup-arithmetic").chosen == vk::Rung::Native;
    params.frameSeconds = f.settings.vrs.frameSeconds;
    params.speedFactor = f.settings.vrs.speedFactor;
    params.lumVarianceFactor = f.settings.vrs.lumVarianceFactor;
    graph::BufferHandle next = passes::addVrsClassifyPass(f.graph, f.ctx, f.shaders, params, f.hdr, velocity, f.vrsRates);
    f.graph.markOutput(next);
    if (capture_) addCapture(f, velocity, next);
    if (f.settings.vrs.debug) f.hdr = passes::addVrsOverlayPass(f.graph, f.ctx, f.shaders, next, f.hdr);
}

void VrsFeature::addCapture(FrameContext& f, graph::BufferHandle velocity, graph::BufferHandle rates) {
    const VkDeviceSize pixels = VkDeviceSize(f.width) * f.height, litBytes = pixels * 8, velocityBytes = pixels * 8;
    const VkDeviceSize bytes = litBytes + velocityBytes + (4 + VkDeviceSize(tiles_)) * sizeof(uint32_t);
    if (!captured_ || captured_.size < bytes) {
        if (captured_) ctx_.destroyDeferred(captured_);
        captured_ = ctx_.createBuffer({bytes, 0, vk::MemoryUsage::Readback, "vrs classifier capture", "readback"});
    }
    capturedWidth_ = f.width;
    capturedHeight_ = f.height;
    const graph::BufferHandle target = importBuffer(f.graph, "vrs classifier capture", captured_);
    const graph::TextureHandle lit = f.hdr;
    const uint32_t width = f.width, height = f.height;
    f.graph.addPass(
        "vrs_capture",
        [&](graph::PassBuilder& b) {
            b.read(lit, graph::Access::TransferSrc);
            b.read(velocity, graph::Access::TransferSrc);
            b.read(rates, graph::Access::TransferSrc);
            b.write(target, graph::Access::TransferDst);
            b.sideEffect();
        },
        [lit, velocity, rates, target, width, height, litBytes, velocityBytes](graph::PassContext& pc) {
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {width, height, 1};
            vkCmdCopyImageToBuffer(pc.commandBuffer(), pc.image(lit), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   pc.vkBuffer(target), 1, &region);
            const VkBufferCopy v{0, litBytes, velocityBytes};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(velocity), pc.vkBuffer(target), 1, &v);
            const VkBufferCopy r{0, litBytes + velocityBytes, pc.buffer(rates).size};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(rates), pc.vkBuffer(target), 1, &r);
        });
}

VrsCapture VrsFeature::capturedClassification() const {
    VrsCapture c;
    if (!captured_) return c;
    c.width = capturedWidth_;
    c.height = capturedHeight_;
    const size_t pixels = size_t(c.width) * c.height;
    const std::vector<uint16_t> halves = vk::downloadBuffer<uint16_t>(ctx_, captured_, pixels * 4);
    for (size_t i = 0; i < pixels; ++i)
        c.lit.emplace_back(glm::unpackHalf1x16(halves[i * 4]), glm::unpackHalf1x16(halves[i * 4 + 1]),
                           glm::unpackHalf1x16(halves[i * 4 + 2]), glm::unpackHalf1x16(halves[i * 4 + 3]));
    c.velocity = vk::downloadBuffer<glm::vec2>(ctx_, captured_, pixels, pixels * 8);
    const std::vector<uint32_t> rates = vk::downloadBuffer<uint32_t>(ctx_, captured_, 4 + tiles_, pixels * 16);
    c.tileSize = rates[0];
    c.tilesX = rates[1];
    c.rates.assign(rates.begin() + 4, rates.end());
    return c;
}

std::vector<uint32_t> VrsFeature::lastRates() const {
    if (!lastEnabled_ || readback_.empty()) return {};
    std::vector<uint32_t> all = vk::downloadBuffer<uint32_t>(ctx_, readback_[lastSlot_], 4 + tiles_);
    return std::vector<uint32_t>(all.begin() + 4, all.end());
}

uint64_t VrsFeature::lastShadingInvocations() const {
    if (!lastEnabled_) return uint64_t(width_) * height_;
    if (hardwareRung()) return vk::downloadBuffer<uint32_t>(ctx_, invocationReadback_[lastSlot_], 1)[0];
    return vrsShadingInvocations(lastRates(), tilesX_, tileSize_, width_, height_);
}

}  // namespace idk::frame
