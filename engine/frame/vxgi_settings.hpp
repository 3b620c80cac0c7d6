// vxgi_settings.hpp: the options of voxel global illumination (frame/vxgi_feature.hpp), a member of
// render::RenderSettings; the rows of frame/settings_table.cpp set them (--gi, --voxels, --gi-grid, ...).
#pragma once
#include <cstdint>

namespace idk::frame {

enum class GiMode : uint8_t { None, Vxgi };

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

struct VxgiSettings {
    GiMode mode = GiMode::None;  // None: nothing allocated, compiled or dispatched
    uint32_t voxels = 128;       // grid size per side (64..512)
    uint32_t ringCones = 5;      // diffuse cones around the normal's cap cone (cosine-weighted set of 1 + ring)
    float stepFactor = 0.5f;     // cone march step in sampled cells (sampling only: opacity is step-corrected)
    VoxelRaster raster = VoxelRaster::Conservative;
    VoxelGridPlacement grid = VoxelGridPlacement::Fit;
    VoxelDraws draws = VoxelDraws::Three;
};

}  // namespace idk::frame
