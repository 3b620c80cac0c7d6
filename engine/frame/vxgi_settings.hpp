// vxgi_settings.hpp: the options of voxel global illumination (frame/vxgi_feature.hpp), a member of
// render::RenderSettings; the rows of frame/settings_table.cpp set them (--gi, --voxels, --gi-grid, ...).
#pragma once
#include <array>
#include <cstdint>

namespace idk::frame {

enum class GiMode : uint8_t { None, Vxgi };

// The grid sizes --voxels accepts (the settings table's choices; the memory check names the largest that fits).
inline constexpr std::array<uint32_t, 5> kVoxelGridSizes = {64, 128, 256, 384, 512};

// How voxelization rasterizes: Conservative (every voxel a triangle touches, by the "conservative-raster" ladder:
// VK_EXT_conservative_rasterization or geometry-shader dilation; thin walls never leak) or Centre (only voxels
// whose centre the triangle covers in its dominant projection: thin, as the CPU oracle of the conformance test).
enum class VoxelRaster : uint8_t { Conservative, Centre };

// Where the grid's cube lies: Fit (around the scene's bounds) or Camera (the same size, centred on the camera and
// snapped to whole steps of the coarsest cell the cones read, gridSize / 8 voxels: static geometry voxelizes
// identically while the camera moves within a step, and a step moves the grid by whole coarse cells, so every
// level the cones read shifts by whole cells too; the original's quantised follow).
enum class VoxelGridPlacement : uint8_t { Fit, Camera };

// How voxelization projects triangles: Three draws, one per axis, each keeping its axis's triangles (IDKEngine's
// measured-fastest fallback), or a Single draw whose geometry shader projects each triangle along its dominant axis.
enum class VoxelDraws : uint8_t { Three, Single };

// Where the cones are traced: Full (every pixel) or Half (one pixel per 2x2 block, then the edge-aware upsample of
// passes/vxgi_upsample.cpp and a full-resolution trace of the pixels it has no sample for). Half is the default:
// on the Cornell box at 128^3 it halves the frame (cone passes 1078 -> 352 ms on lavapipe) at the same error
// against the path tracer (indirect rel. L1 0.395 full, 0.394 half; BM_VxgiCornellResolution).
enum class GiResolution : uint8_t { Full, Half };

// The voxel debug view (passes/vxgi_debug_view.cpp): Off, or Voxels: the final colour shows the first cell of
// level debugLevel each camera ray meets (needs --gi vxgi).
enum class GiDebug : uint8_t { Off, Voxels };

struct VxgiSettings {
    GiMode mode = GiMode::None;  // None: nothing allocated, compiled or dispatched
    uint32_t voxels = 128;       // grid size per side (64..512)
    uint32_t ringCones = 5;      // diffuse cones around the normal's cap cone (cosine-weighted set of 1 + ring)
    // Each diffuse cone traced as 1, 4 or 7 narrower cones across its footprint (shared/vxgi_cone.h,
    // vxgiFootprintCone; --gi-footprint). 4 by the numbers (BM_VxgiCornellCones, Cornell indirect rel. L1 at
    // 64/128/256^3): 1: 0.440/0.438/0.484; 4: 0.330/0.328/0.294; 7: 0.316/0.315 at 1.8x the cones of 4, and it leaks
    // more through one-voxel walls (VxgiFootprintConeTest). At equal cone counts footprints beat a wider ring:
    // 1 + 3 cones x 4 (16 cones) 0.345 against 1 + 16 cones 0.372 at 64^3. The cone trace costs about 3.5x that of 1.
    uint32_t footprintCones = 4;
    float stepFactor = 0.5f;     // cone march step in sampled cells (sampling only: opacity is step-corrected)
    GiResolution resolution = GiResolution::Half;
    VoxelRaster raster = VoxelRaster::Conservative;
    VoxelGridPlacement grid = VoxelGridPlacement::Fit;
    VoxelDraws draws = VoxelDraws::Three;
    GiDebug debug = GiDebug::Off;  // Off: nothing allocated or dispatched
    uint32_t debugLevel = 0;       // 0: the grid; L >= 1: the directional volumes' level L (up to log2 voxels)
    // Voxelization in z-slabs (frame/vxgi_memory.hpp): 0 the smallest count of 1, 2, 4, 8 that fits the memory
    // budget, else that count (--gi-slabs; tests compare the counts' grids).
    uint32_t slabs = 0;
};

}  // namespace idk::frame
