// texture_stream_support.cpp: the streaming oracle and helpers of texture_stream_support.hpp (moved from
// tests/conformance/textures/ so that the registry check and the asset tests run the same comparison).
#include "conformance/texture_stream_support.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <thread>

#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/frames.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {

const scene::DecodedTexture& ReferenceDecodes::get(uint32_t texture, bool srgb) {
    const auto key = std::make_pair(texture, srgb);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    const auto& image = scene_.textures.at(texture).image;
    scene::DecodedTexture t = image ? scene::decodeImage(scene_.images[*image], srgb, scene::imageLabel(scene_, *image))
                                    : scene::decodeImage(scene::Image{}, srgb, "no source");
    return cache_.emplace(key, std::move(t)).first->second;
}

std::vector<uint8_t> readMips(vk::Context& ctx, const vk::Image& image) {
    std::vector<VkBufferImageCopy> regions;
    VkDeviceSize size = 0;
    for (uint32_t level = 0; level < image.mipLevels; ++level) {
        VkBufferImageCopy r{};
        r.bufferOffset = size;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        r.imageExtent = {std::max(1u, image.extent.width >> level), std::max(1u, image.extent.height >> level), 1};
        regions.push_back(r);
        size += VkDeviceSize(r.imageExtent.width) * r.imageExtent.height * 4;
    }
    vk::BufferDesc desc;
    desc.size = size;
    desc.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    desc.memory = vk::MemoryUsage::Readback;
    desc.name = "texture mips readback";
    vk::Buffer buffer = ctx.createBuffer(desc);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer,
                               uint32_t(regions.size()), regions.data());
        vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        // The host reads the copy after the wait: make the transfer writes available to it.
        VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        b.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        b.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &b;
        vkCmdPipelineBarrier2(cmd, &dep);
    });
    if (!buffer.allocation.hostCoherent) {
        VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
        range.memory = buffer.allocation.memory;
        range.size = VK_WHOLE_SIZE;
        vkInvalidateMappedMemoryRanges(ctx.device(), 1, &range);
    }
    std::vector<uint8_t> out(size);
    std::memcpy(out.data(), buffer.mapped(), size);
    ctx.destroy(buffer);
    return out;
}

render::TextureStreamer::ReadyCallback ReadyLog::callback() {
    return [this](uint32_t t, vk::SampledIndex s, vk::SamplerIndex smp) {
        if (t >= calls.size()) {
            ++outOfRange;
            return;
        }
        ++calls[t];
        sampled[t] = s;
        samplers[t] = smp;
        frameOfCall[t] = frame;
    };
}

StreamResult pumpUntilReady(vk::Context& ctx, const std::vector<render::TextureStreamer*>& streamers,
                            const std::vector<ReadyLog*>& logs,
                            const std::function<void(VkCommandBuffer, uint64_t)>& perFrame) {
    vk::FrameRing frames(ctx, 2);
    StreamResult result;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    for (;;) {
        bool all = true;
        for (render::TextureStreamer* s : streamers) all = all && s->allReady();
        if (all) break;
        if (std::chrono::steady_clock::now() > deadline) {
            result.timedOut = true;
            break;
        }
        VkCommandBuffer cmd = frames.begin();
        for (ReadyLog* l : logs) l->frame = result.frames;
        for (render::TextureStreamer* s : streamers) s->pump(cmd);
        if (perFrame) perFrame(cmd, result.frames);
        frames.end();
        ++result.frames;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));  // a frame's worth of other work
    }
    return result;
}

void expectStreamedExactly(Verdict& v, vk::Context& ctx, const scene::Scene& scene, ReferenceDecodes& reference,
                           const render::TextureStreamer& streamer, const ReadyLog& log) {
    if (!v.expect(streamer.allReady(), "the stream did not finish")) return;
    v.expectEq(log.outOfRange, 0u, "onReady calls for textures the scene lacks");
    const auto spaces = streamer.colorSpaces();
    const uint32_t sampledCapacity = ctx.bindless().capacity(0);
    for (uint32_t t = 0; t < scene.textures.size(); ++t) {
        const std::string what = "texture " + std::to_string(t);
        if (spaces[t] == scene::TextureColorSpace::Unused) {
            v.expectEq(log.calls[t], 0u, what + " (unused): onReady calls");
            v.expect(streamer.image(t) == nullptr, what + " (unused) has an image");
            continue;
        }
        v.expectEq(log.calls[t], 1u, what + ": onReady calls");
        v.expect(log.sampled[t].value < sampledCapacity, what + ": sampled index out of the bindless table");
        v.expect(log.samplers[t].value != UINT32_MAX, what + ": no sampler index");
        const bool srgb = spaces[t] != scene::TextureColorSpace::Linear;
        const vk::Image* image = streamer.image(t);
        if (!v.expect(image != nullptr, what + ": no image")) continue;
        v.expect(image->format == (srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM), what + ": format");
        const scene::DecodedTexture& ref = reference.get(t, srgb);
        if (!v.expectEq(image->extent.width, ref.width, what + ": width") ||
            !v.expectEq(image->extent.height, ref.height, what + ": height") ||
            !v.expectEq(size_t(image->mipLevels), ref.mips.size(), what + ": mip levels"))
            continue;
        const std::vector<uint8_t> gpu = readMips(ctx, *image);
        if (!v.expectEq(gpu.size(), ref.texels.size(), what + ": bytes")) continue;
        for (size_t level = 0; level < ref.mips.size(); ++level) {
            const scene::MipLevel& m = ref.mips[level];
            v.expect(std::memcmp(gpu.data() + m.offset, ref.texels.data() + m.offset, m.size) == 0,
                     what + ": mip " + std::to_string(level) + " differs from the CPU decode");
        }
    }
}

}  // namespace idk::conformance
