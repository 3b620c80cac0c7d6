// vxgi_feature.cpp: the voxel grid's lifetime and placement, and the per-frame voxelization.
#include "frame/vxgi_feature.hpp"

#include <algorithm>

#include "render/draw_bounds.hpp"

namespace idk::frame {

passes::VoxelGridBox fitVoxelGrid(const scene::Aabb& bounds, uint32_t n) {
    passes::VoxelGridBox box;
    box.size = n;
    if (bounds.empty()) return box;
    const glm::vec3 extent = bounds.max - bounds.min;
    const float side = std::max({extent.x, extent.y, extent.z, 1e-3f}) * float(n) / float(n - 1);
    box.voxelSize = side / float(n);
    box.gridMin = (bounds.min + bounds.max) * 0.5f - glm::vec3(side * 0.5f);
    return box;
}

VxgiFeature::~VxgiFeature() { release(); }

void VxgiFeature::release() {
    if (!grid_.image) return;
    ctx_.bindless().release(storage_);
    ctx_.bindless().release(sampled_);
    ctx_.destroyDeferred(grid_);
    grid_ = {};
    written_ = false;
}

void VxgiFeature::setScene(const render::GpuScene& scene) {
    bounds_ = render::sceneBounds(scene.data(), render::meshBounds(scene.data()));
}

void VxgiFeature::addPasses(FrameContext& f) {
    const VxgiSettings& s = f.settings.vxgi;
    if (s.mode != GiMode::Vxgi) {
        release();  // --gi none holds nothing
        return;
    }
    if (grid_.image && grid_.extent.width != s.voxels) release();
    if (!grid_.image) {
        vk::ImageDesc desc;
        desc.type = VK_IMAGE_TYPE_3D;
        desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        desc.extent = {s.voxels, s.voxels, s.voxels};
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        desc.name = "vxgi voxel grid";
        desc.category = "vxgi";
        grid_ = ctx_.createImage(desc);
        storage_ = ctx_.bindless().addStorage(grid_.view);
        sampled_ = ctx_.bindless().addSampled(grid_.view);
    }
    box_ = fitVoxelGrid(bounds_, s.voxels);

    graph::PhysicalTexture p;
    p.image = grid_.image;
    p.view = grid_.view;
    p.format = grid_.format;
    p.extent = grid_.extent;
    p.storageIndex = storage_.value;
    p.sampledIndex = sampled_.value;
    // Each frame rewrites the whole grid, so its previous contents never matter; it ends in GENERAL (storage)
    // where the last frame's merge left it.
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    graph::ResourceState state;
    if (written_) state = graph::stateAfterAccess(graph::Access::StorageWrite, graph::ResourceKind::Image, kCs);
    written_ = true;
    graph::TextureHandle grid =
        f.graph.importTexture("vxgi voxel grid", p, state, graph::FinalUse{graph::Access::StorageWrite, kCs});

    passes::VoxelizeInputs in{f.scene, f.frameConstants, f.pointShadows, box_,
                              f.ctx.ladder("vxgi-atomics").chosen};
    f.voxelGrid = passes::addVoxelizePasses(f.graph, f.ctx, f.shaders, in, grid, &f.log);
    f.voxelBox = box_;
}

}  // namespace idk::frame
