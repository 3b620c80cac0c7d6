// vrs_feature.cpp: variable-rate shading's per-frame work: the persistent rate buffer (this frame's classifier
// writes it, the next frame's lighting and sky read it), a copy of the rates in use for the invocation count,
// the camera-motion stand-in, the classifier and the overlay. The classifier's reduction takes subgroup
// arithmetic where the "subgroup-arithmetic" ladder allows, else the shared-memory tree.
#include "frame/vrs_feature.hpp"

#include <glm/gtc/matrix_inverse.hpp>

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
        hasPrevious_ = false;
        return;
    }
    // Consulting the ladder also puts it in --json's "rungs". A hardware rung's tile is the device's rate texel
    // (vk/shading_rate.hpp; the ladder offers the rung only where one fits the classifier); the software rung's is
    // the original's 16x16.
    const vk::Ladder& ladder = f.ctx.ladder("vrs");
    const vk::DeviceCapabilities& caps = f.ctx.capabilities();
    uint32_t tileSize = gpu::kVrsDefaultTileSize;
    if (ladder.chosen == vk::Rung::Native && ladder.chosenMechanism == "VK_NV_shading_rate_image") {
        hardware_ = vk::ShadingRateSource::NvImage;
        tileSize = vk::nvShadingRateTile(caps.shadingRateTexelNv).size;
    } else if (ladder.chosen == vk::Rung::Native) {
        hardware_ = vk::ShadingRateSource::KhrAttachment;
        tileSize = vk::khrShadingRateTile(caps.shadingRateAttachmentTexel).size;
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
    // Camera motion only (stand-in for issue 12's motion vectors); none on the first frame.
    graph::BufferHandle velocity;
    if (hasPrevious_)
        velocity = passes::addVrsCameraMotionPass(f.graph, f.ctx, f.shaders, f.gbuffer.depth,
                                                  previousViewProjection_ * glm::inverse(f.viewProjection));
    previousViewProjection_ = f.viewProjection;
    hasPrevious_ = true;

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
    passes::VrsClassifyParams params;
    params.tileSize = tileSize_;
    params.subgroupReduce = f.ctx.ladder("subgroup-arithmetic").chosen == vk::Rung::Native;
    params.frameSeconds = f.settings.vrs.frameSeconds;
    params.speedFactor = f.settings.vrs.speedFactor;
    params.lumVarianceFactor = f.settings.vrs.lumVarianceFactor;
    graph::BufferHandle next = passes::addVrsClassifyPass(f.graph, f.ctx, f.shaders, params, f.hdr, velocity, f.vrsRates);
    f.graph.markOutput(next);
    if (f.settings.vrs.debug) f.hdr = passes::addVrsOverlayPass(f.graph, f.ctx, f.shaders, next, f.hdr);
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
