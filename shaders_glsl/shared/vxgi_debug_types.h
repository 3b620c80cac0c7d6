// vxgi_debug_types.h: the push block of the voxel debug view (shaders_glsl/vxgi/debug_voxels.comp.glsl,
// engine/passes/vxgi_debug_view.cpp). Ports the role of IDKEngine's VXGI/Voxelize/DebugVisualization/compute.glsl
// (its grid-configure view, idkengine-internals.md 1.5 step 4) with an exact cell walk (DDA) of one level.
#ifndef IDK_VXGI_DEBUG_TYPES_H
#define IDK_VXGI_DEBUG_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

// A cell is hit when its coverage (alpha) exceeds this: half the cell's volume or projected area is surface.
IDK_CONST(float, kVxgiDebugCoverage, 0.5f);

struct VxgiDebugPush {
    DeviceAddress frame;  // GpuFrame (inverse view-projection, camera position)
    uint target;          // RGBA16F storage index: the final HDR colour, overwritten (rgb radiance; a: distance to the
                          // middle of the ray's stretch in the hit cell, 0 on a miss)
    uint level;           // 0: the grid (isotropic); L >= 1: the directional volumes' level L
    uint volumes[6];      // storage indices of level L: the grid's in [0] (L = 0), else +x -x +y -y +z -z
    vec3 gridMin;
    float voxelSize;      // of level 0
    uint gridSize;        // level 0 cells per side
    uint pad;
    uint opacity[6];      // L >= 1: storage indices of the directions' opacity images (== volumes[k]: RGBA16F)
};
IDK_GPU_SIZE(VxgiDebugPush, 88);

IDK_GPU_END
#endif
