// vxgi_memory.hpp: the device memory a VXGI grid of a given size takes, computed from the same image descriptions
// its allocation uses (frame/voxel_volume.hpp, passes/vxgi_passes.hpp's accumulators, the gl-interop rung's
// shared buffers), and the check that refuses a grid the device-local budget (vk/memory_budget.hpp) cannot hold.
// The grid grows as N^3 (volumes with packed directions, "vxgi-volume-format" native: 85 MiB at 128^3, 677 MiB at
// 256^3, 5.3 GiB at 512^3; RGBA16F directions: 126 MiB, 1006 MiB, 7.9 GiB): refused before anything is released
// or allocated, so the scene and any grid already there stay as they were.
#pragma once
#include <stdexcept>
#include <string>

#include "frame/vxgi_settings.hpp"
#include "vk/context.hpp"
#include "vk/features.hpp"

namespace idk::frame {

struct VxgiMemory {
    VkDeviceSize volumes = 0;       // the grid and the six directional mip chains (persistent; "vxgi" in --stats)
    VkDeviceSize accumulators = 0;  // the rung's write-conflict accumulators (transient images, or GL's buffers)
                                    // the merge's cell mask (transient, (n / 2)^3 x 4 bytes) and the front-most
                                    // rule's depth keys (transient, 2 n^3 x 4 bytes)
    VkDeviceSize total() const noexcept { return volumes + accumulators; }
};
VxgiMemory vxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics);

// The grid does not fit: the message names the grid size, the bytes needed, the budget and the largest --voxels
// that fits (or that none does).
class VxgiMemoryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws VxgiMemoryError when vxgiMemory(voxels) exceeds the device-local budget plus `released` (the bytes of a
// grid the new one replaces, freed first).
void checkVxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics, VkDeviceSize released = 0);

// The viewer's guard, before a frame acts on a settings change: when `settings` asks for a new grid (another size,
// or VXGI turned on) that does not fit, restores `before`'s mode and size and returns the message; else "".
// `held`: the bytes of the grid there now (VxgiFeature::heldBytes), freed first by a resize.
std::string refuseVxgiChange(vk::Context& ctx, const VxgiSettings& before, VxgiSettings& settings, VkDeviceSize held);

}  // namespace idk::frame
