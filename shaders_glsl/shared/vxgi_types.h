// vxgi_types.h: push blocks of the VXGI voxelization passes (engine/passes/vxgi_voxelize.cpp) and the grid's
// placement. Ports the uniforms of IDKEngine's VXGI/Voxelize shaders (GridMin/GridMax there).
#ifndef IDK_VXGI_TYPES_H
#define IDK_VXGI_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

// Write-conflict rungs (vk ladder "vxgi-atomics"): Native accumulates sum(rgb) and a fragment count with float
// image atomics (the merge averages); Fallback keeps the max of each channel in r32ui images (floatBitsToUint
// orders non-negative floats like the floats; stored + 1 so that 0 means "no fragment").
IDK_CONST(uint, kVoxelAtomicsFloatAdd, 0u);
IDK_CONST(uint, kVoxelAtomicsUintMax, 1u);
// GlInterop: the fragments append records to a buffer shared with OpenGL (voxelize_record.frag), a GL compute pass
// adds them into a shared float buffer with GL_NV_shader_atomic_float (engine/passes/vxgi_gl_accumulate.cpp) and
// the merge averages its sums like the float-add rung's.
IDK_CONST(uint, kVoxelAtomicsGlRecords, 2u);
// The record buffer: word 0 counts the fragments (all of them, also those past the capacity, so an overflow is
// measured), then kVoxelRecordWords words per record from word kVoxelRecordHeaderWords: the voxel's linear index
// (x + n (y + n z)) and its premultiplied rgba (rgb * coverage, coverage).
IDK_CONST(uint, kVoxelRecordHeaderWords, 4u);
IDK_CONST(uint, kVoxelRecordWords, 5u);
// The GL sums buffer: kVoxelSumWords floats per voxel: sum of premultiplied r, g, b, sum of coverage, count.
IDK_CONST(uint, kVoxelSumWords, 5u);
IDK_CONST(uint, kVoxelGroupSize, 4u);  // merge: 4x4x4 threads

// voxelize.vert / voxelize_*.frag: one draw per projection axis (0 x, 1 y, 2 z).
struct VoxelizePush {
    DeviceAddress frame;         // GpuFrame (lights)
    DeviceAddress vertices;      // GpuVertex[]
    DeviceAddress instances;     // GpuInstance[], indexed by gl_DrawID
    DeviceAddress meshes;        // GpuMesh[]
    DeviceAddress materials;     // GpuMaterial[]
    DeviceAddress colors;        // vec4[] per vertex, 0: none
    DeviceAddress uv1;           // vec2[] per vertex, 0: none
    DeviceAddress pointShadows;  // GpuPointShadow[lightCount], 0: no light casts one
    vec3 gridMin;                // world position of the grid's corner
    float voxelSize;             // world size of one voxel (the grid is a cube of gridSize voxels per side)
    uint gridSize;
    uint axis;                   // this draw's projection axis
    uint accum[4];               // bindless storage indices: r, g, b (and the count for kVoxelAtomicsFloatAdd);
                                 // kVoxelAtomicsGlRecords: [0] the record buffer's storage-buffer index, [1] its
                                 // capacity in records
};
IDK_GPU_SIZE(VoxelizePush, 104);

// merge.comp: accumulators -> the RGBA16F grid's mip 0 (rgb radiance, alpha coverage).
struct VoxelMergePush {
    uint accum[4];  // kVoxelAtomicsGlRecords: [0] the GL sums buffer's storage-buffer index
    uint grid;      // bindless storage index of the grid (mip 0 view)
    uint gridSize;
    uint mode;      // kVoxelAtomics*
    uint pad;
};
IDK_GPU_SIZE(VoxelMergePush, 32);

// mip.comp: one level of the anisotropic mip chain (Crassin et al. 2011): for each direction d of +x -x +y -y +z
// -z, a voxel of level L is its 2x2x2 children of level L - 1 (of direction d; the grid itself for L = 0)
// composited front to back in pairs along d, the four pairs averaged across. A thin wall thus stays opaque seen
// across it at every level, where an isotropic mean would fade it by half per level.
struct VoxelMipPush {
    uint src[6];   // storage indices of the source level per direction (all the grid's for L = 0)
    uint dst[6];   // storage indices of level L per direction
    uint dstSize;  // voxels per side of level L
    uint pad;
};
IDK_GPU_SIZE(VoxelMipPush, 56);

IDK_CONST(uint, kConeGroupSize, 8u);   // cone_trace: 8x8 pixels
IDK_CONST(uint, kNoVxgi, 0xFFFFFFFFu); // LightingPush::vxgiDiffuse when GI is off

// cone_trace.comp: per G-buffer pixel, the irradiance the diffuse cones gather and the radiance of the specular
// cone, written where the pixel lies inside the grid (alpha 1; alpha 0 outside: the SH ambient stays).
struct ConeTracePush {
    DeviceAddress frame;   // GpuFrame
    uint normal;           // G-buffer R32UI (octahedral)
    uint material;         // G-buffer RGBA8 (metallic, roughness, occlusion, lit)
    uint depth;            // G-buffer R32F
    uint diffuse;          // RGBA16F out: irradiance E (rgb), inside-grid flag (a)
    uint specular;         // RGBA16F out: radiance along the reflection cone (rgb)
    uint grid;             // sampled index of the grid (level 0)
    uint directions[6];    // sampled indices of the directional mips (+x -x +y -y +z -z)
    uint gridSampler;      // trilinear, clamp to edge
    uint ringCones;        // diffuse cones around the normal's cap cone
    vec3 gridMin;
    float voxelSize;
    uint gridSize;
    float maxLod;          // in grid levels: the directional mips' count
    float stepFactor;      // march step = sample diameter * stepFactor
    uint unmatchedOnly;    // 1: render resolution, only pixels whose diffuse alpha the upsample left at -1
};
IDK_GPU_SIZE(ConeTracePush, 96);

IDK_GPU_END
#endif
