// vxgi_feature.cpp: the voxel grid's lifetime and placement, and the per-frame voxelization.
#include "frame/vxgi_feature.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/frame_inputs.hpp"
#include "frame/vxgi_memory.hpp"
#include "render/draw_bounds.hpp"
#include "shared/vxgi_types.h"
#include "vk/check.hpp"
#include "vk/transfer.hpp"

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

float voxelGridStep(const passes::VoxelGridBox& box) {
    return box.voxelSize * float(std::max(box.size / 8u, 1u));
}

passes::VoxelGridBox followCamera(const passes::VoxelGridBox& fit, glm::vec3 camera) {
    passes::VoxelGridBox box = fit;
    const double step = double(voxelGridStep(fit));
    const double half = 0.5 * double(fit.voxelSize) * double(fit.size);
    for (int a = 0; a < 3; ++a) box.gridMin[a] = float(std::floor((double(camera[a]) - half) / step) * step);
    return box;
}

VxgiFeature::~VxgiFeature() { release(); }

void VxgiFeature::release() {
    gl_.reset();
    for (vk::StorageBufferIndex i : coneParamsIndex_) ctx_.bindless().release(i);
    for (vk::Buffer& b : coneParams_) ctx_.destroy(b);
    coneParamsIndex_.clear();
    coneParams_.clear();
    releaseLists();
    if (!grid_.image.image) return;
    grid_.release(ctx_);
    for (DirectionVolume& d : directions_) d.release(ctx_);
    ctx_.bindless().release(sampler_);
}

void VxgiFeature::releaseLists() {
    for (uint32_t i = 0; i < 2; ++i) {
        if (!lists_[i]) continue;
        ctx_.bindless().release(listIndex_[i]);
        ctx_.destroy(lists_[i]);
    }
    listed_ = false;
}

void VxgiFeature::setVoxelListCapacity(uint32_t entries) {
    listCapacity_ = entries;
    releaseLists();
}

VkDeviceSize VxgiFeature::heldBytes() const noexcept {
    VkDeviceSize bytes = grid_.image.allocation.size;
    for (const DirectionVolume& d : directions_) bytes += d.bytes();
    for (const vk::Buffer& b : lists_)
        if (b) bytes += b.allocation.size;
    return bytes;
}

void VxgiFeature::setScene(const render::GpuScene& scene) {
    bounds_ = render::sceneBounds(scene.data(), render::meshBounds(scene.data()));
}

void VxgiFeature::addPasses(FrameContext& f, const std::optional<passes::VoxelShadowRays>& rays) {
    const VxgiSettings& s = f.settings.vxgi;
    if (s.mode != GiMode::Vxgi) {
        release();  // --gi none holds nothing
        return;
    }
    const vk::Rung atomics = f.ctx.ladder("vxgi-atomics").chosen;
    const VoxelDirectionFormat format = voxelDirectionFormat(f.ctx.ladder("vxgi-volume-format").chosen);
    const bool newGrid = !grid_.image.image || grid_.image.extent.width != s.voxels;
    if (newGrid || s.slabs != slabsAsked_) {  // a new grid, or new slabs for this one (its accumulators' size)
        // Refused before the old grid is released: the frame fails with the message, nothing is lost.
        slabs_ = checkVxgiMemory(ctx_, s.voxels, atomics, heldBytes(), s.slabs);
        slabsAsked_ = s.slabs;
        if (newGrid) release();
    }
    if (!grid_.image.image) {
        grid_.create(ctx_, "vxgi voxel grid", s.voxels, 1);
        // Directional volumes of the grid's size: level 0 is the voxels seen along each direction (anisotropic
        // from the start, by the surfaces' facing), levels up to 1^3. 6 x 5 bytes x 8/7 per voxel packed (6 x 8 in
        // RGBA16F): 512^3 takes 4.3 GiB (6.9 GiB).
        const uint32_t levels = voxelMipLevels(s.voxels);
        const char* names[6] = {"vxgi mips +x", "vxgi mips -x", "vxgi mips +y", "vxgi mips -y", "vxgi mips +z",
                                "vxgi mips -z"};
        for (uint32_t d = 0; d < 6; ++d) directions_[d].create(ctx_, names[d], s.voxels, levels, format);
        vk::SamplerDesc sampler;
        // Clamp to edge: a coarse cell holding a wall on the grid's bounds reads as that wall up to the march's end
        // (one cell outside), where a transparent border would blend it away by up to half.
        sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        sampler_ = ctx_.bindless().addSampler(sampler);
    }
    box_ = fitVoxelGrid(bounds_, s.voxels);
    if (s.grid == VoxelGridPlacement::Camera) box_ = followCamera(box_, f.camera.position);

    // The grid ends each frame in GENERAL (storage) where the merge and the mip passes used it; tests read it
    // back from there. The directional mips end where the cone tracer sampled them.
    constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    // A grid no frame has used yet holds undefined contents: its first merge stores every voxel; later merges
    // skip the voxels that stay empty (their zeros are already there).
    const bool fullMerge = !grid_.written;
    graph::TextureHandle grid = grid_.import(f.graph, "vxgi voxel grid", {graph::Access::StorageRead, kCs});
    const char* names[12] = {"vxgi mips +x",         "vxgi mips -x",         "vxgi mips +y",
                             "vxgi mips -y",         "vxgi mips +z",         "vxgi mips -z",
                             "vxgi mips +x opacity", "vxgi mips -x opacity", "vxgi mips +y opacity",
                             "vxgi mips -y opacity", "vxgi mips +z opacity", "vxgi mips -z opacity"};
    for (uint32_t d = 0; d < 6; ++d) {
        directionHandles_[d] = directions_[d].colour.import(f.graph, names[d], {graph::Access::SampledRead, kCs});
        directionHandles_[6 + d] =
            directions_[d].packed()
                ? directions_[d].opacity.import(f.graph, names[6 + d], {graph::Access::SampledRead, kCs})
                : graph::TextureHandle{};
    }

    passes::VoxelizeInputs in{f.scene, f.frameConstants, f.pointShadows, box_, atomics};
    if (in.atomics == vk::Rung::GlInterop) {  // the GL pass's shared buffers live across frames
        const passes::VxgiGlProgram program = f.ctx.ladder("vxgi-gl-accumulate").chosen == vk::Rung::Native
                                                  ? passes::VxgiGlProgram::Fp16Vector
                                                  : passes::VxgiGlProgram::Float;
        if (gl_ && gl_->program() != program) gl_.reset();
        if (!gl_) gl_ = std::make_unique<passes::VxgiGlAccumulator>(ctx_, program);
        gl_->prepare(s.voxels);
        in.gl = gl_.get();
    } else {
        gl_.reset();
    }
    if (f.settings.vxgi.raster == VoxelRaster::Conservative)
        in.conservative = f.ctx.ladder("conservative-raster").chosen;
    for (uint32_t d = 0; d < 6; ++d) {
        in.directionLevel0[d] = directions_[d].colourStorage(0);
        in.directionLevel0[6 + d] = directions_[d].opacityStorage(0);
    }
    in.fullMerge = fullMerge;
    in.slabs = slabs_;
    if (atomics != vk::Rung::GlInterop) {
        if (!lists_[0]) {
            for (uint32_t i = 0; i < 2; ++i) {
                vk::BufferDesc desc;
                desc.size = listCapacity_ ? (gpu::kVoxelListHeaderWords + VkDeviceSize(listCapacity_)) * 4
                                          : passes::voxelListBytes(s.voxels);
                desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
                desc.name = "vxgi voxel list " + std::to_string(i);
                desc.category = "vxgi";
                lists_[i] = ctx_.createBuffer(desc);
                listIndex_[i] = ctx_.bindless().addBuffer(lists_[i].buffer);
            }
        }
        // Last written two frames ago (appends, the args pass) and read by the last frame's merge as the previous
        // list; the previous one written and read in the last frame: each waits on all of that.
        graph::ResourceState state;
        state.writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        state.unflushedWrites = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
        state.lastWriteAccess = state.unflushedWrites;
        state.readStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        list_ ^= 1u;
        passes::VoxelizeInputs::Lists lists;
        lists.current = importBuffer(f.graph, "vxgi voxel list", lists_[list_], state);
        lists.currentIndex = listIndex_[list_].value;
        if (listed_ && !fullMerge) {
            lists.previous = importBuffer(f.graph, "vxgi voxel list previous", lists_[list_ ^ 1u], state);
            lists.previousIndex = listIndex_[list_ ^ 1u].value;
        }
        in.lists = lists;
        listed_ = true;
    } else {
        releaseLists();
    }
    in.shadowRays = rays;
    // The single draw's projection follows "voxel-single-draw", except under the dilation fallback, whose geometry
    // shader projects each triangle itself (a passthrough shader could not dilate): the ladder is then not consulted.
    if (s.draws == VoxelDraws::Single)
        in.singleDraw = in.conservative == vk::Rung::Fallback ? vk::Rung::Fallback
                                                              : f.ctx.ladder("voxel-single-draw").chosen;
    f.voxelGrid = passes::addVoxelizePasses(f.graph, f.ctx, f.shaders, in, grid, directionHandles_, cells_, &f.log);
    f.voxelBox = box_;
}

void VxgiFeature::addConeTracing(FrameContext& f) {
    if (!f.voxelGrid.valid()) return;
    passes::ConeTraceInputs in;
    in.gbuffer = f.gbuffer;
    in.frame = f.frameConstants;
    in.environment = f.environment;
    in.grid = f.voxelGrid;
    in.directions = directionHandles_;
    for (uint32_t d = 0; d < 6; ++d) {
        in.directionSampled[d] = directions_[d].colourSampled();
        in.directionSampled[6 + d] = directions_[d].opacitySampled();
    }
    in.gridStorage = grid_.levelStorage[0].value;
    in.gridSampled = grid_.sampled.value;
    for (uint32_t level = 0; level < directions_[0].levels(); ++level) {
        passes::VxgiDirectionIndices views{};
        for (uint32_t d = 0; d < 6; ++d) {
            views[d] = directions_[d].colourStorage(level);
            views[6 + d] = directions_[d].opacityStorage(level);
        }
        in.directionLevels.push_back(views);
    }
    in.gridSampler = sampler_.value;
    in.cells = cells_;
    in.box = box_;
    in.ringCones = f.settings.vxgi.ringCones;
    in.footprintCones = f.settings.vxgi.footprintCones;
    in.stepFactor = f.settings.vxgi.stepFactor;
    in.halfResolution = f.settings.vxgi.resolution == GiResolution::Half;
    in.mipped = &mipped_;
    f.indirectLight = passes::addConeTracePasses(f.graph, f.ctx, f.shaders, in);

    // The same parameters for forward passes (transparent surfaces trace per fragment), in this frame slot's
    // host-visible buffer: the frame ring has waited until the GPU finished the slot's previous frame.
    if (coneParams_.empty()) {
        for (uint32_t i = 0; i < f.framesInFlight; ++i) {
            vk::BufferDesc desc;
            desc.size = sizeof(gpu::VxgiConeParams);
            desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
            desc.memory = vk::MemoryUsage::Upload;
            desc.name = "vxgi cone parameters " + std::to_string(i);
            desc.category = "frame constants";
            coneParams_.push_back(ctx_.createBuffer(desc));
            coneParamsIndex_.push_back(ctx_.bindless().addBuffer(coneParams_.back().buffer));
        }
    }
    gpu::VxgiConeParams c{};
    c.gridMin = box_.gridMin;
    c.voxelSize = box_.voxelSize;
    c.gridSize = box_.size;
    c.maxLod = float(directions_[0].levels() - 1);
    c.stepFactor = in.stepFactor;
    c.ringCones = in.ringCones;
    c.footprintCones = in.footprintCones;
    for (uint32_t d = 0; d < 6; ++d) {
        c.directions[d] = in.directionSampled[d];
        c.opacity[d] = in.directionSampled[6 + d];
    }
    c.gridSampler = in.gridSampler;
    const uint32_t slot = f.slot % uint32_t(coneParams_.size());
    vk::uploadBuffer(ctx_, coneParams_[slot], &c, sizeof(c));
    f.vxgiCones.params = importBuffer(f.graph, "vxgi cone parameters", coneParams_[slot]);
    f.vxgiCones.paramsIndex = coneParamsIndex_[slot].value;
    f.vxgiCones.volumes = mipped_;
    f.vxgiCones.grid = f.voxelGrid;
}

void VxgiFeature::addDebugView(FrameContext& f) {
    if (!f.voxelGrid.valid() || f.settings.vxgi.debug != GiDebug::Voxels) return;
    passes::VxgiDebugViewInputs in;
    in.frame = f.frameConstants;
    in.target = f.hdr;
    in.grid = f.voxelGrid;
    in.directions = mipped_;
    // The viewer can ask for a level past the chain's end (the CLI refuses one): show the coarsest instead.
    // The directional volumes hold levels 0 .. log2(voxels) (level L: cells of 2^L voxels, as the grid's).
    const uint32_t levels = directions_[0].levels();
    in.level = std::min(f.settings.vxgi.debugLevel, levels - 1);
    if (in.level == 0) in.volumeStorage[0] = grid_.levelStorage[0].value;
    else
        for (uint32_t d = 0; d < 6; ++d) {
            in.volumeStorage[d] = directions_[d].colourStorage(in.level);
            in.volumeStorage[6 + d] = directions_[d].opacityStorage(in.level);
        }
    in.box = box_;
    f.hdr = passes::addVxgiDebugViewPass(f.graph, f.ctx, f.shaders, in);
}

}  // namespace idk::frame
