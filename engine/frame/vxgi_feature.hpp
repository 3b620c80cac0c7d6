// vxgi_feature.hpp: voxel global illumination. Owns the persistent RGBA16F voxel grid and its six directional mip
// volumes (created only while --gi vxgi is on, re-created when the size changes) whose cube fits the scene's
// bounds; adds the voxelization passes before the G-buffer and the mip + cone-tracing passes after it
// (passes/vxgi_passes.hpp); fills FrameContext::voxelGrid / voxelBox / indirectLight / vxgiCones (the cone
// parameters for the forward pass of transparent surfaces, written once per frame). Ports IDKEngine's
// VXGI/Voxelizer.cs (its grid box is set by hand or follows the camera; here it fits the scene or follows the camera
// in quantised steps, --gi-grid).
#pragma once
#include "frame/frame_context.hpp"
#include "frame/voxel_volume.hpp"
#include "passes/vxgi_gl_accumulate.hpp"
#include "passes/vxgi_passes.hpp"
#include "render/gpu_scene.hpp"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

#include <array>
#include <memory>
#include <vector>

namespace idk::frame {

// The grid's cube around `bounds`: centred on it, side = its largest extent * n / (n - 1), i.e. half a voxel of
// margin on each side so that surfaces on the bounds lie on voxel centres, not on voxel faces. (The cone tracer
// samples with clamp-to-edge, so a wall on the bounds does not fade into the border at coarse levels.)
passes::VoxelGridBox fitVoxelGrid(const scene::Aabb& bounds, uint32_t n);

// --gi-grid camera: `fit`'s cube (its size and voxel size) centred on `camera`, its corner snapped down to a whole
// multiple of the step (fit.size / 8 voxels, the coarsest cell the cones read; vxgiMarchNext's lod cap), computed
// in double from the world origin so that equal steps give equal corners.
passes::VoxelGridBox followCamera(const passes::VoxelGridBox& fit, glm::vec3 camera);
// The step (world units) the camera-following grid moves by.
float voxelGridStep(const passes::VoxelGridBox& box);

class VxgiFeature {
public:
    explicit VxgiFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~VxgiFeature();
    VxgiFeature(const VxgiFeature&) = delete;
    VxgiFeature& operator=(const VxgiFeature&) = delete;

    void setScene(const render::GpuScene& scene);
    // Voxelization; nothing unless settings.vxgi.mode == Vxgi. `rays`: --shadows raytraced's BVH (the lights are
    // then shadowed by rays, there being no shadow table yet).
    // Before (re)creating the grid, checks it fits the device-local memory budget (frame/vxgi_memory.hpp): throws
    // VxgiMemoryError naming the size, the bytes, the budget and the largest size that fits, the old grid kept.
    void addPasses(FrameContext& f, const std::optional<passes::VoxelShadowRays>& rays = std::nullopt);
    void addConeTracing(FrameContext& f);  // after the G-buffer: mips + cone tracing into f.indirectLight
    // --gi-debug voxels: after everything else lit f.hdr, overwrites it with the voxel debug view (nothing when off).
    void addDebugView(FrameContext& f);
    // The grid of the last frame (RGBA16F, size^3; left in GENERAL layout) or nullptr: tests read it back.
    const vk::Image* grid() const noexcept { return grid_.image.image ? &grid_.image : nullptr; }
    const passes::VoxelGridBox& box() const noexcept { return box_; }
    // The z-slabs the voxelization runs in (frame/vxgi_memory.hpp), chosen with the grid; 0 before the first frame.
    uint32_t slabs() const noexcept { return slabs_; }
    // Device bytes the grid and its directional volumes hold now (0 when none): what a resize frees first.
    VkDeviceSize heldBytes() const noexcept;
    // The gl-interop rung's state (record capacity, last frame's overflow) or nullptr on the other rungs.
    passes::VxgiGlAccumulator* glAccumulator() const noexcept { return gl_.get(); }
    // The six directional volumes (+x -x +y -y +z -z, level 0 the voxels seen along each; colour and opacity in the
    // formats of ladder "vxgi-volume-format"; left where the cone tracer sampled them): tests read them back for the
    // CPU cone tracer.
    const std::array<DirectionVolume, 6>& directions() const noexcept { return directions_; }
    // Tests: the touched-voxel lists' capacity in entries (0: passes::voxelListBytes's), from the next frame on, so
    // that a list overflows and the merge's fallback to every voxel runs.
    void setVoxelListCapacity(uint32_t entries);
    // The touched-voxel list the last frame filled (`previous`: the one before it), or nullptr (gl-interop rung, or
    // none yet): tests read its append count (word 0).
    const vk::Buffer* voxelList(bool previous = false) const noexcept {
        const vk::Buffer& b = lists_[previous ? list_ ^ 1u : list_];
        return b ? &b : nullptr;
    }

private:
    void release();
    vk::Context& ctx_;
    scene::Aabb bounds_;
    passes::VoxelGridBox box_;
    uint32_t slabs_ = 0, slabsAsked_ = 0;  // the chosen count, and VxgiSettings::slabs it was chosen for
    VoxelVolume grid_;                      // level 0: the voxelized radiance and coverage
    std::array<DirectionVolume, 6> directions_;  // anisotropic volumes (+x -x +y -y +z -z), levels 0 .. log2(size)
    vk::SamplerIndex sampler_;
    passes::VxgiDirectionHandles directionHandles_;  // this frame's imports
    graph::TextureHandle cells_;                // this frame's cell mask (the merge's, for the level-1 mip)
    passes::VxgiDirectionHandles mipped_;  // this frame's directional volumes after the mip passes
    std::unique_ptr<passes::VxgiGlAccumulator> gl_;  // "vxgi-atomics" gl-interop rung only
    // The merge's touched-voxel lists (passes::VoxelizeInputs::lists; not on the gl-interop rung): this frame's is
    // lists_[list_], the previous frame's the other; `listed_`: the other holds the previous frame's list (it ran with
    // lists on this grid).
    std::array<vk::Buffer, 2> lists_;
    std::array<vk::StorageBufferIndex, 2> listIndex_;
    uint32_t list_ = 0, listCapacity_ = 0;
    bool listed_ = false;
    void releaseLists();
    // The cone parameters for forward passes (gpu::VxgiConeParams), one host-visible buffer per frame in flight.
    std::vector<vk::Buffer> coneParams_;
    std::vector<vk::StorageBufferIndex> coneParamsIndex_;
};

}  // namespace idk::frame
