// vrs_rate_image.cpp: the hardware VRS rungs' rate image (vrs/rate_image.comp.glsl): the classifier's palette
// indices converted to one R8_UINT texel per tile in the rung's encoding (KHR attachment texel or NV palette
// index), written to a staging buffer by compute and copied into the image, which the lighting pass then reads
// as its shading-rate attachment / shading-rate image. Texel = tile, so the image is tilesX x tilesY.
#include <memory>

#include "passes/vrs_passes.hpp"
#include "shared/vrs_hardware_types.h"

namespace idk::passes {

void recordVrsRateTexels(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, VkDeviceAddress rates,
                         VkDeviceAddress texels, uint32_t tiles, bool nvEncoding) {
    vk::ComputePipelineDesc desc;
    desc.shader = vk::ShaderId::vrs_rate_image_comp;
    desc.pushBytes = sizeof(gpu::VrsRateImagePush);
    desc.localSize = {gpu::kVrsRateImageGroupSize, 1, 1};
    vk::bindPipeline(cmd, shaders.compute(desc));
    gpu::VrsRateImagePush push{};
    push.rates = rates;
    push.texels = texels;
    push.tiles = tiles;
    push.encoding = nvEncoding ? gpu::kVrsEncodingNv : gpu::kVrsEncodingKhr;
    vk::pushConstants(cmd, ctx, push);
    vkCmdDispatch(cmd, vk::groupCount((tiles + 3) / 4, gpu::kVrsRateImageGroupSize), 1, 1);
}

graph::TextureHandle addVrsRateImagePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         graph::BufferHandle rates, uint32_t tilesX, uint32_t tilesY, bool nvEncoding) {
    const uint32_t tiles = tilesX * tilesY, words = (tiles + 3) / 4;
    graph::BufferDesc staging;
    staging.size = VkDeviceSize(words) * 4;
    graph::BufferHandle texels = graph.createBuffer("vrs rate texels", staging);
    auto packed = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "vrs_rate_texels",
        [&](graph::PassBuilder& b) {
            b.read(rates, graph::Access::StorageRead);
            *packed = b.write(texels, graph::Access::StorageWrite);
        },
        [&ctx, &shaders, rates, packed, tiles, nvEncoding](graph::PassContext& pc) {
            recordVrsRateTexels(pc.commandBuffer(), ctx, shaders, pc.buffer(rates).address, pc.buffer(*packed).address,
                                tiles, nvEncoding);
        });

    graph::TextureDesc desc;
    desc.format = VK_FORMAT_R8_UINT;  // the format both extensions read (KHR requires it to support the attachment)
    desc.sizeMode = graph::SizeMode::Absolute;
    desc.extent = {tilesX, tilesY, 1};
    graph::TextureHandle image = graph.createTexture("vrs rate image", desc);
    auto copied = std::make_shared<graph::TextureHandle>();
    const graph::BufferHandle source = *packed;
    graph.addPass(
        "vrs_rate_image_copy",
        [&](graph::PassBuilder& b) {
            b.read(source, graph::Access::TransferSrc);
            *copied = b.write(image, graph::Access::TransferDst);
        },
        [source, copied, tilesX, tilesY](graph::PassContext& pc) {
            VkBufferImageCopy region{};
            region.bufferRowLength = tilesX;  // texels are tightly packed in tile order
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {tilesX, tilesY, 1};
            vkCmdCopyBufferToImage(pc.commandBuffer(), pc.vkBuffer(source), pc.image(*copied),
                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        });
    return *copied;
}

}  // namespace idk::passes
