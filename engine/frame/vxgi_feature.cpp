// vxgi_feature.cpp: the voxel grid's lifetime and placement, and the per-frame voxelization.
#include "frame/vxgi_feature.hpp"

#include <algorithm>

#include "render/draw_bounds.hpp"
#include "vk/check.hpp"

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
    for (vk::StorageImageIndex s : mipStorage_) ctx_.bindless().release(s);
    ctx_.bindless().release(sampled_);
    ctx_.bindless().release(sampler_);
    VkDevice device = ctx_.device();
    ctx_.destroyDeferred([device, views = mipViews_] {
        for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
    });
    ctx_.destroyDeferred(grid_);
    grid_ = {};
    mipViews_.clear();
    mipStorage_.clear();
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
        uint32_t levels = 1;
        while ((s.voxels >> levels) > 0) ++levels;
        desc.mipLevels = levels;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        desc.name = "vxgi voxel grid";
        desc.category = "vxgi";
        grid_ = ctx_.createImage(desc);
        for (uint32_t level = 0; level < levels; ++level) {
            VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
            view.image = grid_.image;
            view.viewType = VK_IMAGE_VIEW_TYPE_3D;
            view.format = desc.format;
            view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1};
            VkImageView v = VK_NULL_HANDLE;
            vk::check(vkCreateImageView(ctx_.device(), &view, nullptr, &v));
            mipViews_.push_back(v);
            mipStorage_.push_back(ctx_.bindless().addStorage(v));
        }
        sampled_ = ctx_.bindless().addSampled(grid_.view);
        vk::SamplerDesc sampler;
        sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;  // transparent black: outside = empty
        sampler_ = ctx_.bindless().addSampler(sampler);
    }
    box_ = fitVoxelGrid(bounds_, s.voxels);

    graph::PhysicalTexture p;
    p.image = grid_.image;
    p.view = grid_.view;
    p.format = grid_.format;
    p.extent = grid_.extent;
    p.mips = uint32_t(mipViews_.size());
    p.storageIndex = mipStorage_[0].value;  // the merge writes level 0
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

void VxgiFeature::addConeTracing(FrameContext& f) {
    if (!f.voxelGrid.valid()) return;
    passes::ConeTraceInputs in;
    in.gbuffer = f.gbuffer;
    in.frame = f.frameConstants;
    in.environment = f.environment;
    in.grid = f.voxelGrid;
    for (vk::StorageImageIndex s : mipStorage_) in.mipViews.push_back(s.value);
    in.gridSampler = sampler_.value;
    in.box = box_;
    in.ringCones = f.settings.vxgi.ringCones;
    in.stepFactor = f.settings.vxgi.stepFactor;
    f.indirectLight = passes::addConeTracePasses(f.graph, f.ctx, f.shaders, in);
}

}  // namespace idk::frame
