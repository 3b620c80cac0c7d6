// voxel_volume.cpp: creation, release and per-frame import of a VXGI volume.
#include "frame/voxel_volume.hpp"

#include <string>

#include "vk/check.hpp"

namespace idk::frame {

vk::ImageDesc voxelVolumeDesc(const char* name, uint32_t size, uint32_t levels, VkFormat format) {
    vk::ImageDesc desc;
    desc.type = VK_IMAGE_TYPE_3D;
    desc.format = format;
    desc.extent = {size, size, size};
    desc.mipLevels = levels;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = name;
    desc.category = "vxgi";
    return desc;
}

VoxelDirectionFormat voxelDirectionFormat(vk::Rung rung) {
    if (rung == vk::Rung::Native) return {VK_FORMAT_B10G11R11_UFLOAT_PACK32, VK_FORMAT_R8_UNORM};
    return {};
}

uint32_t voxelMipLevels(uint32_t size) {
    uint32_t levels = 1;
    while ((size >> levels) > 0) ++levels;
    return levels;
}

void VoxelVolume::create(vk::Context& ctx, const char* name, uint32_t size, uint32_t levels, VkFormat format) {
    const vk::ImageDesc desc = voxelVolumeDesc(name, size, levels, format);
    image = ctx.createImage(desc);
    for (uint32_t level = 0; level < levels; ++level) {
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = image.image;
        view.viewType = VK_IMAGE_VIEW_TYPE_3D;
        view.format = desc.format;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1};
        VkImageView v = VK_NULL_HANDLE;
        vk::check(vkCreateImageView(ctx.device(), &view, nullptr, &v));
        levelViews.push_back(v);
        levelStorage.push_back(ctx.bindless().addStorage(v));
    }
    sampled = ctx.bindless().addSampled(image.view);
    written = false;
}

void VoxelVolume::release(vk::Context& ctx) {
    if (!image.image) return;
    for (vk::StorageImageIndex s : levelStorage) ctx.bindless().release(s);
    ctx.bindless().release(sampled);
    VkDevice device = ctx.device();
    ctx.destroyDeferred([device, views = levelViews] {
        for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
    });
    ctx.destroyDeferred(image);
    image = {};
    levelViews.clear();
    levelStorage.clear();
    written = false;
}

graph::TextureHandle VoxelVolume::import(graph::RenderGraph& graph, const char* name, graph::FinalUse finalUse) {
    graph::PhysicalTexture p;
    p.image = image.image;
    p.view = image.view;
    p.format = image.format;
    p.extent = image.extent;
    p.mips = uint32_t(levelViews.size());
    p.storageIndex = levelStorage[0].value;
    p.sampledIndex = sampled.value;
    // The layout the previous frame left (contents are kept: the merge skips voxels that stay empty, whose zeros are
    // there from an earlier frame; before the first frame they are undefined and the first merge stores them all).
    graph::ResourceState state;
    if (written) state = graph::stateAfterAccess(finalUse.access, graph::ResourceKind::Image, finalUse.stages);
    written = true;
    return graph.importTexture(name, p, state, finalUse);
}

void DirectionVolume::create(vk::Context& ctx, const char* name, uint32_t size, uint32_t levels,
                             VoxelDirectionFormat format) {
    colour.create(ctx, name, size, levels, format.colour);
    if (format.opacity != VK_FORMAT_UNDEFINED)
        opacity.create(ctx, (std::string(name) + " opacity").c_str(), size, levels, format.opacity);
}

void DirectionVolume::release(vk::Context& ctx) {
    colour.release(ctx);
    opacity.release(ctx);
}

}  // namespace idk::frame
