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
