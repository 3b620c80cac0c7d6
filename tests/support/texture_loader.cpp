// texture_loader.cpp: a 1x1 RGBA8 texture in SHADER_READ_ONLY layout for GpuScene::setTexture tests.
#include "support/texture_loader.hpp"

#include "vk/transfer.hpp"

namespace idk::test {

vk::Image makeSolidTexture(vk::Context& ctx, const uint8_t rgba[4], bool srgb) {
    vk::ImageDesc desc;
    desc.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    desc.extent = {1, 1, 1};
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = "solid test texture";
    desc.category = "textures";
    vk::Image image = ctx.createImage(desc);
    vk::uploadImage(ctx, image, rgba, 4, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    return image;
}

}  // namespace idk::test
