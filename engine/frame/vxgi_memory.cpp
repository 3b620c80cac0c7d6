// vxgi_memory.cpp: see vxgi_memory.hpp.
#include "frame/vxgi_memory.hpp"

#include <string>

#include "frame/voxel_volume.hpp"
#include "passes/vxgi_gl_accumulate.hpp"
#include "passes/vxgi_passes.hpp"
#include "vk/memory_budget.hpp"

namespace idk::frame {

VxgiMemory vxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics) {
    VxgiMemory m;
    // The grid (one level) and the six directional volumes (full chains: colour, and opacity where the
    // "vxgi-volume-format" rung keeps it apart), as VxgiFeature::addPasses creates them.
    const VoxelDirectionFormat format = voxelDirectionFormat(ctx.ladder("vxgi-volume-format").chosen);
    const uint32_t levels = voxelMipLevels(voxels);
    VkDeviceSize direction = vk::imageBytes(ctx, voxelVolumeDesc("vxgi mips", voxels, levels, format.colour));
    if (format.opacity != VK_FORMAT_UNDEFINED)
        direction += vk::imageBytes(ctx, voxelVolumeDesc("vxgi mips opacity", voxels, levels, format.opacity));
    m.volumes = vk::imageBytes(ctx, voxelVolumeDesc("vxgi voxel grid", voxels, 1)) + 6 * direction;
    // The merge's cell mask (transient, every rung).
    vk::ImageDesc cells;
    cells.type = VK_IMAGE_TYPE_3D;
    cells.format = passes::kVoxelCellMaskFormat;
    const uint32_t c = passes::voxelCellMaskSize(voxels);
    cells.extent = {c, c, c};
    cells.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    m.accumulators = vk::imageBytes(ctx, cells);
    vk::ImageDesc keys = cells;  // the front-most rule's depth keys (transient, every rung)
    keys.format = passes::kVoxelDepthKeyFormat;
    keys.extent = passes::voxelDepthKeyExtent(voxels);
    m.accumulators += vk::imageBytes(ctx, keys);
    const passes::VoxelAccumulatorImages acc = passes::voxelAccumulatorImages(atomics);
    if (acc.count == 0) {
        m.accumulators += passes::VxgiGlAccumulator::firstFrameBytes(voxels);
    } else {
        // The graph's transient images: storage, cleared by a transfer. (Placed in the graph's aliased heaps,
        // whose alignment may add a little on top.)
        vk::ImageDesc desc;
        desc.type = VK_IMAGE_TYPE_3D;
        desc.format = acc.format;
        desc.extent = {voxels, voxels, voxels};
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        m.accumulators += acc.count * vk::imageBytes(ctx, desc);
    }
    return m;
}

void checkVxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics, VkDeviceSize released) {
    const vk::DeviceMemoryBudget budget = vk::deviceLocalBudget(ctx);
    const VkDeviceSize available = budget.available + released;
    const VxgiMemory need = vxgiMemory(ctx, voxels, atomics);
    if (need.total() <= available) return;
    uint32_t fits = 0;
    for (uint32_t n : kVoxelGridSizes)
        if (n < voxels && vxgiMemory(ctx, n, atomics).total() <= available) fits = n;
    const std::string n = std::to_string(voxels);
    throw VxgiMemoryError("--voxels " + n + ": the " + n + "^3 VXGI grid needs " + vk::bytesText(need.total()) +
                          ": volumes " + std::to_string(need.volumes) + " + accumulators " +
                          std::to_string(need.accumulators) + " bytes, but the device-local memory budget has " +
                          vk::bytesText(available) + " free (" + budget.source +
                          (released ? ", with the " + std::to_string(released) + " bytes of the grid it replaces" : "") +
                          "); " +
                          (fits ? "the largest --voxels that fits is " + std::to_string(fits)
                                : std::string("no --voxels fits: use --gi none")));
}

std::string refuseVxgiChange(vk::Context& ctx, const VxgiSettings& before, VxgiSettings& settings, VkDeviceSize held) {
    const bool newGrid = settings.voxels != before.voxels || before.mode != GiMode::Vxgi;
    if (settings.mode != GiMode::Vxgi || !newGrid) return {};
    try {
        checkVxgiMemory(ctx, settings.voxels, ctx.ladder("vxgi-atomics").chosen, held);
        return {};
    } catch (const VxgiMemoryError& e) {
        settings.voxels = before.voxels;
        settings.mode = before.mode;
        return e.what();
    }
}

}  // namespace idk::frame
