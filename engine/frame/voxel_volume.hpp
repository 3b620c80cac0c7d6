// voxel_volume.hpp: one persistent RGBA16F 3D image of VXGI (the voxel grid, or one direction of the anisotropic
// mip chain) with a storage view per mip level (a storage view holds one level) and a sampled view of all levels,
// imported into each frame's graph in the state the previous frame left it.
#pragma once
#include <vector>

#include "graph/render_graph.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/resources.hpp"

namespace idk::frame {

// The image a volume of `size`^3 voxels and `levels` mip levels allocates (RGBA16F, storage + sampled; category
// "vxgi"): create() uses it, and so does the memory check (frame/vxgi_memory.hpp), so the two cannot drift.
vk::ImageDesc voxelVolumeDesc(const char* name, uint32_t size, uint32_t levels);
// Levels of a full mip chain of `size` (down to 1^3): the directional volumes' count.
uint32_t voxelMipLevels(uint32_t size);

struct VoxelVolume {
    vk::Image image;
    std::vector<VkImageView> levelViews;
    std::vector<vk::StorageImageIndex> levelStorage;
    vk::SampledIndex sampled;
    bool written = false;  // a frame has used it: its layout is the one `finalUse` left

    void create(vk::Context& ctx, const char* name, uint32_t size, uint32_t levels);
    void release(vk::Context& ctx);
    // Imported with final use `finalUse` (the state the next frame starts from).
    graph::TextureHandle import(graph::RenderGraph& graph, const char* name, graph::FinalUse finalUse);
};

}  // namespace idk::frame
