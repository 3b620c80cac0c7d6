// vrs_hardware.cpp: VrsFeature's hardware rungs (VK_KHR_fragment_shading_rate, VK_NV_shading_rate_image): this
// frame's rates (f.vrsRates, classified last frame) become a rate image, lighting and sky run as one fragment pass
// at those rates, and its fragment invocations are counted on the GPU and read back for --stats --json's
// shadingInvocations. The software rung's anchors and reconstruction are not used. Lavapipe has neither
// extension, so on this project's CI the ladder never picks these rungs (tests/unit/app/ladder_test.cpp).
// A real GPU would rather count with a FRAGMENT_SHADER_INVOCATIONS pipeline-statistics query (no atomic
// traffic: one global atomic per fragment contends on hardware); the atomic keeps the count exact and
// independent of query support.
#include <memory>

#include "frame/vrs_feature.hpp"
#include "passes/vrs_passes.hpp"

namespace idk::frame {

graph::TextureHandle VrsFeature::addHardwareLighting(FrameContext& f, graph::TextureHandle target,
                                                     const passes::LightingInputs& inputs) {
    passes::VrsHardwareLighting h;
    h.gbuffer = f.gbuffer;
    h.frame = f.frameConstants;
    h.lights = f.scene.lights;
    h.environment = f.environment;
    h.inputs = inputs;
    h.inputs.vrsRates = f.vrsRates;
    h.rateImage = passes::addVrsRateImagePass(f.graph, f.ctx, f.shaders, f.vrsRates, tilesX_, tiles_ / tilesX_,
                                              hardware_ == vk::ShadingRateSource::NvImage);
    h.texelSize = tileSize_;
    h.source = hardware_;

    // The invocation counter: a transient uint zeroed each frame, copied to this slot's readback after lighting.
    graph::BufferDesc counterDesc;
    counterDesc.size = sizeof(uint32_t);
    const graph::BufferHandle counter = f.graph.createBuffer("vrs invocations", counterDesc);
    auto zeroed = std::make_shared<graph::BufferHandle>();
    f.graph.addPass(
        "vrs_invocations_clear", [&](graph::PassBuilder& b) { *zeroed = b.write(counter, graph::Access::TransferDst); },
        [zeroed](graph::PassContext& pc) { vkCmdFillBuffer(pc.commandBuffer(), pc.vkBuffer(*zeroed), 0, 4, 0u); });
    h.invocations = *zeroed;
    graph::BufferHandle counted;
    const graph::TextureHandle lit = passes::addVrsLightingRatePass(f.graph, f.ctx, f.shaders, h, target, counted);

    graph::PhysicalBuffer p;
    p.buffer = invocationReadback_[f.slot].buffer;
    p.size = invocationReadback_[f.slot].size;
    p.address = invocationReadback_[f.slot].address;
    const graph::BufferHandle readback = f.graph.importBuffer("vrs invocations readback", p, graph::ResourceState{},
                                                              graph::FinalUse{graph::Access::HostRead});
    auto copied = std::make_shared<graph::BufferHandle>();
    f.graph.addPass(
        "vrs_invocations_readback",
        [&](graph::PassBuilder& b) {
            b.read(counted, graph::Access::TransferSrc);
            *copied = b.write(readback, graph::Access::TransferDst);
        },
        [counted, copied](graph::PassContext& pc) {
            const VkBufferCopy region{0, 0, sizeof(uint32_t)};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(counted), pc.vkBuffer(*copied), 1, &region);
        });
    f.graph.markOutput(*copied);
    return lit;
}

}  // namespace idk::frame
