// texture_loader.cpp: OpenImageIO decode (memory or file) -> RGBA8 + box-filtered mips -> staged upload ->
// bindless -> GpuScene::setTexture. A synchronous stand-in for IDKEngine's async texture loading (tests only).
#include "support/texture_loader.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

bool decode(const scene::Image& image, std::vector<uint8_t>& rgba, uint32_t& w, uint32_t& h) {
    std::unique_ptr<OIIO::ImageInput> in;
    OIIO::Filesystem::IOMemReader reader(image.encoded.data(), image.encoded.size());
    if (!image.encoded.empty()) {
        std::string hint = image.mimeType == "image/jpeg" ? "embedded.jpg" : "embedded.png";
        in = OIIO::ImageInput::open(hint, nullptr, &reader);
    } else if (!image.path.empty()) {
        in = OIIO::ImageInput::open(image.path.string());
    }
    if (!in) return false;
    const OIIO::ImageSpec& spec = in->spec();
    w = uint32_t(spec.width);
    h = uint32_t(spec.height);
    std::vector<uint8_t> raw(size_t(w) * h * spec.nchannels);
    bool ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, raw.data());
    in->close();
    if (!ok) return false;
    rgba.assign(size_t(w) * h * 4, 255);
    for (size_t p = 0; p < size_t(w) * h; ++p)
        for (int c = 0; c < std::min(spec.nchannels, 4); ++c) rgba[p * 4 + c] = raw[p * spec.nchannels + c];
    if (spec.nchannels < 3)
        for (size_t p = 0; p < size_t(w) * h; ++p) rgba[p * 4 + 1] = rgba[p * 4 + 2] = rgba[p * 4];
    return true;
}

// Uploads level 0 and a 2x2 box-filtered mip chain (averaged in the stored encoding: good enough for tests).
vk::Image upload(vk::Context& ctx, const std::vector<uint8_t>& rgba, uint32_t w, uint32_t h, bool srgb,
                 const std::string& name) {
    std::vector<std::vector<uint8_t>> mips{rgba};
    std::vector<VkExtent3D> extents{{w, h, 1}};
    while (extents.back().width > 1 || extents.back().height > 1) {
        VkExtent3D s = extents.back(), d{std::max(1u, s.width / 2), std::max(1u, s.height / 2), 1};
        const std::vector<uint8_t>& src = mips.back();
        std::vector<uint8_t> dst(size_t(d.width) * d.height * 4);
        for (uint32_t y = 0; y < d.height; ++y)
            for (uint32_t x = 0; x < d.width; ++x)
                for (int c = 0; c < 4; ++c) {
                    uint32_t x0 = std::min(2 * x, s.width - 1), x1 = std::min(2 * x + 1, s.width - 1);
                    uint32_t y0 = std::min(2 * y, s.height - 1), y1 = std::min(2 * y + 1, s.height - 1);
                    uint32_t sum = src[(size_t(y0) * s.width + x0) * 4 + c] + src[(size_t(y0) * s.width + x1) * 4 + c] +
                                   src[(size_t(y1) * s.width + x0) * 4 + c] + src[(size_t(y1) * s.width + x1) * 4 + c];
                    dst[(size_t(y) * d.width + x) * 4 + c] = uint8_t((sum + 2) / 4);
                }
        mips.push_back(std::move(dst));
        extents.push_back(d);
    }
    vk::ImageDesc desc;
    desc.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    desc.extent = {w, h, 1};
    desc.mipLevels = uint32_t(mips.size());
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = name;
    desc.category = "textures";
    vk::Image image = ctx.createImage(desc);

    std::vector<uint8_t> bytes;
    std::vector<VkBufferImageCopy> copies;
    for (uint32_t level = 0; level < mips.size(); ++level) {
        VkBufferImageCopy copy{};
        copy.bufferOffset = bytes.size();
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        copy.imageExtent = extents[level];
        copies.push_back(copy);
        bytes.insert(bytes.end(), mips[level].begin(), mips[level].end());
    }
    vk::BufferDesc staging;
    staging.size = bytes.size();
    staging.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    staging.memory = vk::MemoryUsage::Upload;
    staging.name = "test texture staging";
    staging.category = "staging";
    vk::Buffer buffer = ctx.createBuffer(staging);
    vk::uploadBuffer(ctx, buffer, bytes.data(), bytes.size());
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(cmd, buffer.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(copies.size()), copies.data());
        vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    ctx.destroy(buffer);
    return image;
}

}  // namespace

vk::Image makeSolidTexture(vk::Context& ctx, const uint8_t rgba[4], bool srgb) {
    std::vector<uint8_t> texels(rgba, rgba + 4);
    return upload(ctx, texels, 1, 1, srgb, "solid test texture");
}

SyncTextures::SyncTextures(vk::Context& ctx, const scene::Scene& scene, render::GpuScene& gpuScene) : ctx_(ctx) {
    for (uint32_t t = 0; t < scene.textures.size(); ++t) {
        const scene::Texture& texture = scene.textures[t];
        if (!texture.image || *texture.image >= scene.images.size()) continue;
        std::vector<uint8_t> rgba;
        uint32_t w = 0, h = 0;
        if (!decode(scene.images[*texture.image], rgba, w, h)) continue;
        // A texture used both as colour and as data would need two views; the colour view wins here.
        bool srgb = gpuScene.textureIsColor(t);
        images_.push_back(upload(ctx, rgba, w, h, srgb, "test texture " + std::to_string(t)));
        indices_.push_back(ctx.bindless().addSampled(images_.back().view));
        gpuScene.setTexture(t, indices_.back());
        ++loaded_;
    }
}

SyncTextures::~SyncTextures() {
    for (vk::SampledIndex i : indices_) ctx_.bindless().release(i);
    for (vk::Image& image : images_) ctx_.destroyDeferred(image);
}

}  // namespace idk::test
