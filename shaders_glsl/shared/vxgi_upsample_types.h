// vxgi_upsample_types.h: the half-resolution cone trace's sample layout and the push block of its edge-aware
// upsample (shaders_glsl/vxgi/upsample.comp.glsl, engine/passes/vxgi_upsample.cpp). No IDKEngine counterpart (its
// cone tracer writes at render resolution).
#ifndef IDK_VXGI_UPSAMPLE_TYPES_H
#define IDK_VXGI_UPSAMPLE_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

// Half resolution: half pixel h traces the G-buffer pixel 2h + o of its 2x2 block, o = (0,0) where h.x + h.y is
// even and (1,1) where it is odd (a quincunx over the full-resolution image: every full pixel has a sample within
// one pixel on each axis, and a one-pixel-wide feature is sampled on every other block). Clamped to the image.
IDK_CONST(uint, kVxgiHalfResOddOffset, 1u);

struct VxgiUpsamplePush {
    DeviceAddress frame;  // GpuFrame (camera, extent)
    uint normal;          // G-buffer R32UI (octahedral), full resolution
    uint depth;           // G-buffer R32F, full resolution
    uint halfDiffuse;     // RGBA16F, the half-resolution trace: irradiance (rgb), inside-grid flag (a)
    uint halfSpecular;    // RGBA16F, the half-resolution trace: reflection-cone radiance (rgb)
    uint diffuse;         // RGBA16F out, full resolution (the cone trace's layout)
    uint specular;        // RGBA16F out, full resolution
    vec3 gridMin;         // the grid's box: pixels outside it get alpha 0 as the full-resolution trace gives them
    float voxelSize;
    uint gridSize;
    uint pad;
};
IDK_GPU_SIZE(VxgiUpsamplePush, 56);

IDK_GPU_END
#endif
