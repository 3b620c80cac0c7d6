// voxel_volume.hpp: one persistent 3D image of VXGI (the RGBA16F voxel grid, or one image of a direction of the
// anisotropic mip chain) with a storage view per mip level (a storage view holds one level) and a sampled view of
// all levels, imported into each frame's graph in the state the previous frame left it; and a direction's volume:
// its colour and opacity images in the formats of ladder "vxgi-volume-format".
#pragma once
#include <vector>

#include "graph/render_graph.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/features.hpp"
#include "vk/resources.hpp"

namespace idk::frame {

// The image a volume of `size`^3 voxels and `levels` mip levels allocates (storage + sampled; category "vxgi"):
// create() uses it, and so does the memory check (frame/vxgi_memory.hpp), so the two cannot drift.
vk::ImageDesc voxelVolumeDesc(const char* name, uint32_t size, uint32_t levels,
                              VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT);

// The formats of a directional volume on a rung of "vxgi-volume-format". Native: premultiplied rgb in
// B10G11R11_UFLOAT (4 bytes) plus coverage in R8_UNORM (1 byte), 5 bytes per voxel and level; Fallback: RGBA16F
// (8 bytes), coverage in its alpha (`opacity` VK_FORMAT_UNDEFINED: no second image). Both formats are filterable,
// sampled and (with shaderStorageImageExtendedFormats) storable on the native rung: vk/context.cpp checks them.
struct VoxelDirectionFormat {
    VkFormat colour = VK_FORMAT_R16G16B16A16_SFLOAT;
    VkFormat opacity = VK_FORMAT_UNDEFINED;
};
VoxelDirectionFormat voxelDirectionFormat(vk::Rung rung);
// Levels of a full mip chain of `size` (down to 1^3): the directional volumes' count.
uint32_t voxelMipLevels(uint32_t size);

struct VoxelVolume {
    vk::Image image;
    std::vector<VkImageView> levelViews;
    std::vector<vk::StorageImageIndex> levelStorage;
    vk::SampledIndex sampled;
    bool written = false;  // a frame has used it: its layout is the one `finalUse` left

    void create(vk::Context& ctx, const char* name, uint32_t size, uint32_t levels,
                VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT);
    void release(vk::Context& ctx);
    // Imported with final use `finalUse` (the state the next frame starts from).
    graph::TextureHandle import(graph::RenderGraph& graph, const char* name, graph::FinalUse finalUse);
};

// One direction (+x -x +y -y +z -z) of the anisotropic mip chain: `colour` holds the premultiplied radiance seen
// along it, `opacity` its coverage; on the fallback rung `opacity` is not created and `colour` (RGBA16F) holds both.
// Shaders tell the two apart by the indices (include/voxel_images.glsl): opacity index == colour index means one
// RGBA16F image.
struct DirectionVolume {
    VoxelVolume colour;
    VoxelVolume opacity;

    bool packed() const noexcept { return opacity.image.image != VK_NULL_HANDLE; }
    uint32_t levels() const noexcept { return uint32_t(colour.levelViews.size()); }
    uint32_t colourStorage(uint32_t level) const { return colour.levelStorage[level].value; }
    uint32_t opacityStorage(uint32_t level) const {
        return (packed() ? opacity : colour).levelStorage[level].value;
    }
    uint32_t colourSampled() const { return colour.sampled.value; }
    uint32_t opacitySampled() const { return (packed() ? opacity : colour).sampled.value; }
    VkDeviceSize bytes() const noexcept { return colour.image.allocation.size + opacity.image.allocation.size; }

    void create(vk::Context& ctx, const char* name, uint32_t size, uint32_t levels, VoxelDirectionFormat format);
    void release(vk::Context& ctx);
};

}  // namespace idk::frame
