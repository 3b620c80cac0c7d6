// vxgi_memory.cpp: see vxgi_memory.hpp.
#include "frame/vxgi_memory.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "frame/voxel_volume.hpp"
#include "passes/vxgi_gl_accumulate.hpp"
#include "passes/vxgi_passes.hpp"
#include "vk/memory_budget.hpp"

namespace idk::frame {

VxgiMemory vxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics, uint32_t slabs) {
    const uint32_t depth = voxels / std::max(slabs, 1u);
    VxgiMemory m;
    // The grid (one level) and the six directional volumes (full chains: colour, and opacity where the
    // "vxgi-volume-format" rung keeps it apart), as VxgiFeature::addPasses creates them.
    const VoxelDirectionFormat format = voxelDirectionFormat(ctx.ladder("vxgi-volume-format").chosen);
    const uint32_t levels = voxelMipLevels(voxels);
    VkDeviceSize direction = vk::imageBytes(ctx, voxelVolumeDesc("vxgi mips", voxels, levels, format.colour));
    if (format.opacity != VK_FORMAT_UNDEFINED)
        direction += vk::imageBytes(ctx, voxelVolumeDesc("vxgi mips opacity", voxels, levels, format.opacity));
    m.volumes = vk::imageBytes(ctx, voxelVolumeDesc("vxgi voxel grid", voxels, 1)) + 6 * direction;
    // The merge's two touched-voxel lists (persistent buffers; not on the gl-interop rung).
    if (atomics != vk::Rung::GlInterop) m.volumes += 2 * passes::voxelListBytes(voxels);
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
    keys.extent = passes::voxelDepthKeyExtent(voxels, depth);
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
        desc.extent = {voxels, voxels, depth};
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        m.accumulators += acc.count * vk::imageBytes(ctx, desc);
    }
    return m;
}

namespace {
std::string slabText(uint32_t slabs) { return std::to_string(slabs) + (slabs == 1 ? " slab" : " slabs"); }

// The slab counts an n^3 grid may use, fewest first: `forced` (0: every count of kVoxelSlabCounts), only one on the
// gl-interop rung, and only those whose depth keys (z extent 2 n / S) stay within maxImageDimension3D; none for a
// grid above the limit.
std::vector<uint32_t> allowedSlabCounts(uint32_t voxels, vk::Rung atomics, uint32_t forced,
                                        uint32_t maxImageDimension3D) {
    std::vector<uint32_t> allowed;
    if (voxels > maxImageDimension3D) return allowed;
    for (uint32_t s : kVoxelSlabCounts) {
        if (forced != 0 && s != forced) continue;
        if (atomics == vk::Rung::GlInterop && s != 1) continue;
        if (voxels % s != 0 || 2 * (voxels / s) > maxImageDimension3D) continue;
        allowed.push_back(s);
    }
    return allowed;
}
}  // namespace

uint32_t planVoxelSlabs(uint32_t voxels, vk::Rung atomics, uint32_t forced, uint32_t maxImageDimension3D,
                        VkDeviceSize available, const std::function<VxgiMemory(uint32_t slabs)>& memory,
                        const std::string& budgetText, const std::function<uint32_t()>& smallerFits) {
    const std::string n = std::to_string(voxels);
    const std::string grid = "--voxels " + n + ": the " + n + "^3 VXGI grid";
    const std::string limit = "the device's maxImageDimension3D (" + std::to_string(maxImageDimension3D) + ")";
    if (voxels > maxImageDimension3D) throw VxgiMemoryError(grid + " exceeds " + limit);
    const std::vector<uint32_t> allowed = allowedSlabCounts(voxels, atomics, forced, maxImageDimension3D);
    if (allowed.empty()) {
        if (forced != 0 && atomics == vk::Rung::GlInterop)
            throw VxgiMemoryError(grid + ": --gi-slabs " + std::to_string(forced) +
                                  ": the gl-interop rung of vxgi-atomics voxelizes in one slab (its GL sums cover "
                                  "the whole grid)");
        // The keys of the thinnest slab the rung (or --gi-slabs) allows.
        const uint32_t thinnest = forced ? forced : (atomics == vk::Rung::GlInterop ? 1 : kVoxelSlabCounts.back());
        throw VxgiMemoryError(grid + (forced ? " in " + slabText(forced) : std::string()) + ": its depth keys (" +
                              n + " x " + n + " x " + std::to_string(2 * voxels / thinnest) + " texels) exceed " +
                              limit);
    }
    for (uint32_t s : allowed)
        if (memory(s).total() <= available) return s;
    const uint32_t least = allowed.back();
    const VxgiMemory need = memory(least);
    const uint32_t fits = smallerFits ? smallerFits() : 0;
    throw VxgiMemoryError(grid + " needs " + vk::bytesText(need.total()) + ": volumes " +
                          std::to_string(need.volumes) + " + accumulators " + std::to_string(need.accumulators) +
                          " bytes (in " + slabText(least) + "), but the device-local memory budget has " + budgetText + "; " +
                          (fits ? "the largest --voxels that fits is " + std::to_string(fits)
                                : std::string("no --voxels fits: use --gi none")));
}

uint32_t checkVxgiMemory(vk::Context& ctx, uint32_t voxels, vk::Rung atomics, VkDeviceSize released,
                         uint32_t forcedSlabs) {
    const vk::DeviceMemoryBudget budget = vk::deviceLocalBudget(ctx);
    const VkDeviceSize available = budget.available + released;
    const uint32_t maxDim = ctx.info().limits.maxImageDimension3D;
    auto smallerFits = [&]() -> uint32_t {
        uint32_t fits = 0;
        for (uint32_t n : kVoxelGridSizes) {
            if (n >= voxels) continue;
            for (uint32_t s : allowedSlabCounts(n, atomics, 0, maxDim))
                if (vxgiMemory(ctx, n, atomics, s).total() <= available) fits = n;
        }
        return fits;
    };
    const std::string budgetText =
        vk::bytesText(available) + " free (" + budget.source +
        (released ? ", with the " + std::to_string(released) + " bytes of the grid it replaces" : "") + ")";
    auto memory = [&](uint32_t s) { return vxgiMemory(ctx, voxels, atomics, s); };
    return planVoxelSlabs(voxels, atomics, forcedSlabs, maxDim, available, memory, budgetText, smallerFits);
}

std::string refuseVxgiChange(vk::Context& ctx, const VxgiSettings& before, VxgiSettings& settings, VkDeviceSize held) {
    const bool newGrid =
        settings.voxels != before.voxels || before.mode != GiMode::Vxgi || settings.slabs != before.slabs;
    if (settings.mode != GiMode::Vxgi || !newGrid) return {};
    try {
        checkVxgiMemory(ctx, settings.voxels, ctx.ladder("vxgi-atomics").chosen, held, settings.slabs);
        return {};
    } catch (const VxgiMemoryError& e) {
        settings.voxels = before.voxels;
        settings.mode = before.mode;
        settings.slabs = before.slabs;
        return e.what();
    }
}

}  // namespace idk::frame
