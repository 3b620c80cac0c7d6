// vxgi_memory.hpp: the device memory a VXGI grid of a given size takes, computed from the same image descriptions
// its allocation uses (frame/voxel_volume.hpp, passes/vxgi_passes.hpp's accumulators, the gl-interop rung's
// shared buffers), and the check that refuses a grid the device-local budget (vk/memory_budget.hpp) cannot hold.
// The grid grows as N^3 (volumes with packed directions, "vxgi-volume-format" native: 85 MiB at 128^3, 677 MiB at
// 256^3, 5.3 GiB at 512^3; RGBA16F directions: 126 MiB, 1006 MiB, 7.9 GiB): refused before anything is released
// or allocated, so the scene and any grid already there stay as they were.
// Voxelization in z-slabs: the write-conflict accumulators and the depth keys cover n x n x n/S voxels and the
// passes from the clear to the merge repeat per slab (passes/vxgi_voxelize.cpp), so the merge's peak shrinks by S
// for them; the check takes the smallest S of kVoxelSlabCounts that fits the budget (1 whenever it does: small grids
// pay nothing), or the one --gi-slabs forces. 512^3 (packed directions, float-add rung): 10.38 GiB at S = 1,
// 6.00 GiB at S = 8 (the volumes and the touched-voxel lists alone 5.32 GiB).
#pragma once
#include <array>
#include <functional>
#include <stdexcept>
#include <string>

#include "frame/vxgi_settings.hpp"
#include "vk/context.hpp"
#include "vk/features.hpp"

namespace idk::frame {

struct VxgiMemory {
    VkDeviceSize volumes = 0;       // the grid, the six directional mip chains and the merge's two touched-voxel
                                    // lists (persistent; "vxgi" in --stats)
    VkDeviceSize accumulators = 0;  // the rung's write-conflict accumulators (transient images of one slab, or
                                    // GL's buffers), the merge's cell mask (transient, (n / 2)^3 x 4 bytes) and
                                    // the front-most rule's depth keys (transient, 2 n^3 / S x 4 bytes)
    VkDeviceSize total() const noexcept { return volumes + accumulators; }
};
VxgiMemory vxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics, uint32_t slabs = 1);

// The slab counts the check chooses from (--gi-slabs 1|2|4|8; n / 8 >= 8 voxels deep for the grid sizes allowed).
inline constexpr std::array<uint32_t, 4> kVoxelSlabCounts = {1, 2, 4, 8};

// The grid does not fit: the message names the grid size, the bytes needed, the budget and the largest --voxels
// that fits (or that none does).
class VxgiMemoryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The slab count of an n^3 grid: the smallest of kVoxelSlabCounts (or `forced`, when not 0) whose depth keys stay
// within `maxImageDimension3D` (their z extent is 2 n / S) and whose memory(S).total() is at most `available`; the
// gl-interop rung (`atomics`), whose GL buffers the slabs do not cover, has only S = 1. Throws VxgiMemoryError naming
// the grid size and the cause: the grid above maxImageDimension3D, a forced count the rung or the limit does not
// allow, or no count that fits (with the least memory any allowed count needs, and `budgetText`); the largest
// smaller --voxels that fits is named when `smallerFits` finds one (0: none).
uint32_t planVoxelSlabs(uint32_t voxels, vk::Rung atomics, uint32_t forced, uint32_t maxImageDimension3D,
                        VkDeviceSize available, const std::function<VxgiMemory(uint32_t slabs)>& memory,
                        const std::string& budgetText, const std::function<uint32_t()>& smallerFits);

// The slab count the grid uses (planVoxelSlabs with the device's limit and its device-local budget plus `released`,
// the bytes of a grid the new one replaces, freed first); throws VxgiMemoryError when none fits. `forcedSlabs`:
// VxgiSettings::slabs (0: the smallest that fits).
uint32_t checkVxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics, VkDeviceSize released = 0,
                         uint32_t forcedSlabs = 0);

// The viewer's guard, before a frame acts on a settings change: when `settings` asks for a new grid (another size,
// or VXGI turned on) that does not fit, restores `before`'s mode and size and returns the message; else "".
// `held`: the bytes of the grid there now (VxgiFeature::heldBytes), freed first by a resize.
std::string refuseVxgiChange(vk::Context& ctx, const VxgiSettings& before, VxgiSettings& settings, VkDeviceSize held);

}  // namespace idk::frame
