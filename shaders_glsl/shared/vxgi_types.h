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
// (x + n (y + n z)), its premultiplied rgba (rgb * coverage, coverage) and its facing (see below).
IDK_CONST(uint, kVoxelRecordHeaderWords, 4u);
IDK_CONST(uint, kVoxelRecordWords, 9u);
// The GL sums buffer: kVoxelSumWords floats per voxel: sum of premultiplied r, g, b, sum of coverage, sums of the
// facing's four components, and (word kVoxelSumCount) the count.
IDK_CONST(uint, kVoxelSumWords, 9u);
IDK_CONST(uint, kVoxelSumCount, 8u);
IDK_CONST(uint, kVoxelGroupSize, 4u);  // merge: 4x4x4 threads

// A fragment's facing (vec4): xyz the unit geometric normal of the side it radiates from (the side with the
// more radiance), w the ratio of the other side's radiance to it (0 for single-sided surfaces, 1 for a
// double-sided emitter). The accumulators average it per voxel like the radiance (the r32ui rung keeps the max
// of each component + 2); the merge turns it into the six directional level-0 voxels (vxgiVoxelTowards,
// shared/vxgi_cone.h). Accumulator slots: 0..2 radiance, kVoxelAccumFacing..+3 the facing, kVoxelAccumCount the
// float-add rung's count.
IDK_CONST(uint, kVoxelAccumFacing, 3u);
IDK_CONST(uint, kVoxelAccumCount, 7u);
IDK_CONST(float, kVoxelFacingBias, 2.0f);  // r32ui rung: facing + 2 is positive, so its float bits order like it

// voxelize.vert / voxelize_*.frag: one draw per projection axis (0 x, 1 y, 2 z), or one draw with axis
// kVoxelAxisDominant whose geometry shader projects each triangle along its own dominant axis (--gi-voxel-draws).
IDK_CONST(uint, kVoxelAxisDominant, 3u);
// The single draw's native rung (voxelize_passthrough.geom, passes/vxgi_axis_swizzle.hpp): voxelize.vert emits the
// unswizzled grid coordinates, the passthrough geometry shader picks a viewport per triangle, whose swizzle projects.
IDK_CONST(uint, kVoxelAxisSwizzled, 4u);
// VoxelizePush::axis packs the draw's slab too: bits 0..7 the axis above, bits 8..19 the slab's first voxel z,
// bits 20..31 its depth in voxels (frame/vxgi_memory.hpp: the accumulators and keys cover one z-slab of the grid,
// the draws repeat per slab). A fragment is kept in the slab holding floor(its grid z), the same integer voxel it
// writes with one slab, so each fragment lands in exactly one slab whatever its position on a slab boundary.
IDK_CONST(uint, kVoxelAxisMask, 0xFFu);
IDK_CONST(uint, kVoxelSlabZShift, 8u);
IDK_CONST(uint, kVoxelSlabDepthShift, 20u);
IDK_CONST(uint, kVoxelSlabMask, 0xFFFu);
struct VoxelizePush {
    DeviceAddress frame;         // GpuFrame (lights)
    DeviceAddress vertices;      // GpuVertex[]
    DeviceAddress instances;     // GpuInstance[], indexed by gl_DrawID
    DeviceAddress meshes;        // GpuMesh[]
    DeviceAddress materials;     // GpuMaterial[]
    DeviceAddress colors;        // vec4[] per vertex, 0: none
    DeviceAddress uv1;           // vec2[] per vertex, 0: none
    DeviceAddress pointShadows;  // GpuPointShadow[lightCount], 0: no light casts one; with rayShadows > 0 the
                                 // ray-traced shadows' scene instead (GpuPtSceneDesc: our BVH)
    vec3 gridMin;                // world position of the grid's corner
    float voxelSize;             // world size of one voxel (the grid is a cube of gridSize voxels per side)
    uint gridSize;
    uint axis;                   // this draw's projection axis, or kVoxelAxisDominant / kVoxelAxisSwizzled, and
                                 // its slab (kVoxelSlab*)
    uint accum[8];               // bindless storage indices: r, g, b, the facing's 4 (kVoxelAccumFacing) and the
                                 // count for kVoxelAtomicsFloatAdd (kVoxelAccumCount); kVoxelAtomicsGlRecords:
                                 // [0] the record buffer's storage-buffer index, [1] its capacity in records
    uint rayShadows;             // --shadows raytraced: the first rayShadows lights of nonzero intensity (the
                                 // mask pass's casters) are shadowed by a ray through the BVH; 0: by the table
    uint depthKeys;              // bits 0..15: bindless storage index of the front-most rule's key image
                                 // (voxelize_key.glsl); bits 16..31 (kVoxelListShift): the accumulating draw's
                                 // touched-voxel list, its storage-buffer index + 1, 0 for none (no push word is
                                 // left on the float-add rung; both bindless tables hold at most 4096 entries)
};
IDK_GPU_SIZE(VoxelizePush, 128);  // Vulkan's guaranteed push-constant size: nothing more fits

// merge.comp: accumulators -> the RGBA16F grid (rgb radiance, alpha coverage, seen from every side) and level 0 of
// the six directional volumes (the voxel seen travelling along +x -x +y -y +z -z: vxgiVoxelTowards).
struct VoxelMergePush {
    uint accum[8];       // as VoxelizePush::accum; kVoxelAtomicsGlRecords: [0] the GL sums buffer's index
    uint grid;           // bindless storage index of the grid (mip 0 view)
    uint directions[6];  // storage indices of the directional volumes' level 0
    uint gridSize;
    uint mode;           // kVoxelAtomics*
    uint full;           // 1: store every voxel (the volumes are new: their contents undefined); 0: skip the empty
                         // voxels whose grid voxel is already all-zero bits (merge.comp.glsl says why that is exact)
    uint cells;          // storage index of the frame's cell mask (R32UI, (size / 2)^3, cleared to 0): the merge
                         // sets 1 in the level-1 cell of every occupied voxel, the level-1 mip skips the others
    uint opacity[6];     // storage indices of the directions' opacity images' level 0 (R8), or directions[k] where
                         // one RGBA16F image holds both (ladder "vxgi-volume-format": include/voxel_images.glsl)
    uint slabZ;          // the slab this merge resolves: voxels z in [slabZ, slabZ + slabDepth) of the grid, at
    uint slabDepth;      // z - slabZ in the accumulators (which cover one slab)
    uint list;           // storage-buffer indices of this frame's touched-voxel list and the previous frame's
    uint prevList;       // (kVoxelNoList: none; the merge then visits the slab's every voxel)
};
IDK_GPU_SIZE(VoxelMergePush, 116);

// The touched-voxel list (engine/passes/vxgi_merge.cpp, include/voxel_list.glsl): the accumulating draw appends a
// voxel at its first fragment of the frame (the float-add count's add that returns 0, the r32ui red's max that
// returns 0), packed x | y << 10 | z << 20 in grid coordinates (grids of at most 1024^3). Word 0 counts the appends,
// also those past the capacity (the list is then incomplete: the merge visits every voxel); the entries follow from
// word kVoxelListHeaderWords, as many as the buffer holds.
IDK_CONST(uint, kVoxelListHeaderWords, 4u);
IDK_CONST(uint, kVoxelListShift, 16u);
IDK_CONST(uint, kVoxelListKeyMask, 0xFFFFu);
IDK_CONST(uint, kVoxelNoList, 0xFFFFFFFFu);
IDK_CONST(uint, kVoxelListGroup, 64u);  // merge invocations per workgroup in either dispatch (4x4x4)

// merge_args.comp: a slab's merge dispatch (VkDispatchIndirectCommand at `args`): over the two lists' entries, or,
// where they are incomplete (include/voxel_list.glsl voxelListsComplete), over the slab's every voxel.
struct VoxelMergeArgsPush {
    DeviceAddress args;
    uint list;       // as VoxelMergePush
    uint prevList;
    uint gridSize;
    uint slabDepth;
};
IDK_GPU_SIZE(VoxelMergeArgsPush, 24);

// mip.comp: one level of the anisotropic mip chain (Crassin et al. 2011): for each direction d of +x -x +y -y +z
// -z, a voxel of level L >= 1 is its 2x2x2 children of level L - 1 of direction d (level 0: the merge's)
// composited front to back in pairs along d, the four pairs averaged across. A thin wall thus stays opaque seen
// across it at every level, where an isotropic mean would fade it by half per level.
struct VoxelMipPush {
    uint src[6];   // storage indices of the source level per direction (all the grid's for L = 0)
    uint dst[6];   // storage indices of level L per direction
    uint dstSize;  // voxels per side of level L
    uint cells;    // L = 1: storage index of the merge's cell mask (VoxelMergePush::cells), 0 where none of the
                   // cell's eight voxels is occupied (mip.comp.glsl); kVoxelNoCells for L >= 2
    uint srcOpacity[6];  // the opacity images of src and dst (== src / dst: one RGBA16F image holds both)
    uint dstOpacity[6];
};
IDK_GPU_SIZE(VoxelMipPush, 104);
IDK_CONST(uint, kVoxelNoCells, 0xFFFFFFFFu);

// The cone tracer's parameters (include/cone_trace.glsl). The G-buffer pass has them in its push block
// (ConeTracePush); the forward pass of transparent surfaces (transparency/forward_body.h), whose push block has no
// room left, reads them from a small storage buffer the VXGI feature writes once per frame (its bindless index in
// TransparencyPush::vxgiCones).
struct VxgiConeParams {
    vec3 gridMin;
    float voxelSize;
    uint gridSize;
    float maxLod;          // the directional volumes' top level (log2 gridSize)
    float stepFactor;      // march step = sample diameter * stepFactor
    uint ringCones;        // diffuse cones around the normal's cap cone
    uint directions[6];    // sampled indices of the directional volumes (+x -x +y -y +z -z), levels 0..maxLod
    uint gridSampler;      // trilinear, clamp to edge
    uint footprintCones;   // narrower cones each diffuse cone is traced as (1, 4, 7; vxgiFootprintCone)
    uint opacity[6];       // sampled indices of their opacity volumes (== directions[k]: one RGBA16F image)
};
IDK_GPU_SIZE(VxgiConeParams, 88);

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
    uint grid;             // sampled index of the grid (level 0 seen from every side; the cones do not sample it)
    uint directions[6];    // sampled indices of the directional volumes (+x -x +y -y +z -z), levels 0..maxLod
    uint gridSampler;      // trilinear, clamp to edge
    uint ringCones;        // diffuse cones around the normal's cap cone
    vec3 gridMin;
    float voxelSize;
    uint gridSize;
    float maxLod;          // the directional volumes' top level (log2 gridSize)
    float stepFactor;      // march step = sample diameter * stepFactor
    uint unmatchedOnly;    // 1: render resolution, only pixels whose diffuse alpha the upsample left at -1
    uint opacity[6];       // sampled indices of the directions' opacity volumes (VxgiConeParams::opacity)
    uint footprintCones;   // narrower cones each diffuse cone is traced as (1, 4, 7; vxgiFootprintCone)
    uint pad;              // the size a multiple of the frame address' 8 bytes
};
IDK_GPU_SIZE(ConeTracePush, 128);  // the whole of Vulkan's guaranteed push-constant range

IDK_GPU_END
#endif
