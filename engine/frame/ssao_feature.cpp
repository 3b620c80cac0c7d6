// ssao_feature.cpp: adds the SSAO pass when --ssao is on (and the test capture of its inputs and output).
#include "frame/ssao_feature.hpp"

#include <memory>

#include "frame/frame_inputs.hpp"
#include "passes/ssao.hpp"
#include "vk/transfer.hpp"

namespace idk::frame {

SsaoFeature::~SsaoFeature() {
    if (captured_) ctx_.destroy(captured_);
}

std::vector<uint32_t> SsaoFeature::captured() const {
    if (!captured_) return {};
    return vk::downloadBuffer<uint32_t>(ctx_, captured_, size_t(capturedPixels_) * 3);
}

void SsaoFeature::addPasses(FrameContext& f) {
    const SsaoSettings& s = f.settings.ssao;
    if (!s.enabled) return;
    f.ambientOcclusion = passes::addSsaoPass(f.graph, f.ctx, f.shaders, f.gbuffer, f.frameConstants,
                                             {s.radius, s.samples, frameIndex_++});
    if (!capture_) return;
    capturedPixels_ = f.width * f.height;
    const VkDeviceSize bytes = VkDeviceSize(capturedPixels_) * 3 * sizeof(uint32_t);
    if (!captured_ || captured_.size < bytes) {
        if (captured_) ctx_.destroyDeferred(captured_);
        vk::BufferDesc desc;
        desc.size = bytes;
        desc.memory = vk::MemoryUsage::Readback;
        desc.name = "captured ssao";
        desc.category = "readback";
        captured_ = ctx_.createBuffer(desc);
    }
    const graph::BufferHandle target = importBuffer(f.graph, "captured ssao", captured_);
    const graph::TextureHandle images[3] = {f.ambientOcclusion, f.gbuffer.depth, f.gbuffer.normal};
    const uint32_t width = f.width, height = f.height;
    f.graph.addPass(
        "ssao_capture",
        [&](graph::PassBuilder& b) {
            for (graph::TextureHandle t : images) b.read(t, graph::Access::TransferSrc);
            b.write(target, graph::Access::TransferDst);
            b.sideEffect();
        },
        [images, target, width, height](graph::PassContext& pc) {
            for (int i = 0; i < 3; ++i) {
                VkBufferImageCopy region{};
                region.bufferOffset = VkDeviceSize(i) * width * height * sizeof(uint32_t);
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.imageExtent = {width, height, 1};
                vkCmdCopyImageToBuffer(pc.commandBuffer(), pc.image(images[i]), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                       pc.vkBuffer(target), 1, &region);
            }
        });
}

}  // namespace idk::frame
