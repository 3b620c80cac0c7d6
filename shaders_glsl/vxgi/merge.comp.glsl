#version 460
// merge.comp.glsl: resolves the voxelization's accumulators into the RGBA16F grid (rgb = the voxel's radiance: mean
// of its fragments for the float-add and gl-interop rungs, per-channel max for the r32ui rung; alpha = coverage, 1
// where a fragment landed, 0 elsewhere) and into level 0 of the six directional volumes: the voxel seen travelling
// along each axis direction, by its mean facing (vxgiVoxelTowards, shared/vxgi_cone.h). Ports IDKEngine's
// VXGI/Voxelize merge compute shader (4x4x4 groups); its level 0 is isotropic.
// Empty voxels are skipped where the grid already holds zero bits there (push `full` 0): the seven stores of 8 bytes
// are most of the pass, and most of a grid is air (surfaces fill O(N^2) of its N^3 voxels).
// Exact: a voxel of zero grid bits has zero bits in every direction too, as the merge writes them (empty: all zero;
// else each directional channel is at most the grid's, rgb * coverage * shown and coverage * opacity with coverage,
// shown and opacity in [0, 1]: a channel that rounds to zero in RGBA16F is below 2^-25, and rounds to zero in the
// directions' formats too, RGBA16F, the 10/11-bit floats (smallest step 2^-20) and R8_UNORM (1/255)), so skipping
// leaves what a store would write.
// On a GPU the saving is bandwidth: an empty voxel reads 12 bytes (its count, its grid texel) where it read 4 and
// wrote 56; whole 4x4x4 groups of air take the same path, so divergence stays at surfaces. Lavapipe, which runs the
// invocations on CPU cores and prices loads and stores alike, measured 3-5x less merge time (128^3, 256^3).
// With the touched-voxel lists (engine/passes/vxgi_merge.cpp) the dispatch visits only the voxels occupied this
// frame or the last one (slabVoxel) instead of the slab's every voxel.
#extension GL_GOOGLE_include_directive : require
#include "vxgi_types.h"
#include "vxgi_cone.h"
#include "voxel_images.glsl"
#include "voxel_list.glsl"

IDK_BINDLESS_BUFFER_READONLY(gVoxelSums, float);  // kVoxelAtomicsGlRecords: the GL pass's sums (kVoxelSumWords each)

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(push_constant, scalar) uniform Push { VoxelMergePush p; };

// This invocation's voxel of the slab, in the accumulators' coordinates (one z-slab); false: none. `previous`: it
// comes from the previous frame's list.
// List dispatch (merge_args.comp chose it alike): entry i of the previous frame's list then of this frame's, each a
// grid voxel some fragment touched, kept where it lies in this slab: the voxels occupied now, and those occupied
// last frame (which the merge empties where no fragment touched them now; main leaves those occupied now to their
// entry in this frame's list, so no voxel is stored twice). Every other voxel was empty last frame and is still:
// its zero bits are already in the grid and the volumes. Else the dispatch covers the slab's every voxel.
bool slabVoxel(out ivec3 local, out bool previous) {
    previous = false;
    if (voxelListsComplete(p.list, p.prevList)) {
        uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kVoxelListGroup +
                 gl_LocalInvocationIndex;
        uint before = voxelListCount(p.prevList);
        if (i >= before && i - before >= voxelListCount(p.list)) return false;
        previous = i < before;
        local = (previous ? voxelListEntry(p.prevList, i) : voxelListEntry(p.list, i - before)) -
                ivec3(0, 0, int(p.slabZ));
        return local.z >= 0 && local.z < int(p.slabDepth);
    }
    local = ivec3(gl_GlobalInvocationID);
    return all(lessThan(local, ivec3(p.gridSize, p.gridSize, p.slabDepth)));
}

void main() {
    // The slab's voxel: `local` in the accumulators (one z-slab), `voxel` in the grid, the volumes and the mask.
    ivec3 local;
    bool previous;
    if (!slabVoxel(local, previous)) return;
    ivec3 voxel = local + ivec3(0, 0, int(p.slabZ));
    vec4 value = vec4(0.0), facing = vec4(0.0);
    bool occupied = false;
    if (p.mode == kVoxelAtomicsFloatAdd) {
        float count = imageLoad(gVoxelsR32f[p.accum[kVoxelAccumCount]], local).r;
        occupied = count > 0.0;
        if (occupied) {
            value = vec4(imageLoad(gVoxelsR32f[p.accum[0]], local).r, imageLoad(gVoxelsR32f[p.accum[1]], local).r,
                         imageLoad(gVoxelsR32f[p.accum[2]], local).r, count) / count;
            for (uint c = 0u; c < 4u; ++c)
                facing[c] = imageLoad(gVoxelsR32f[p.accum[kVoxelAccumFacing + c]], local).r / count;
        }
    } else if (p.mode == kVoxelAtomicsGlRecords) {
        uint base = (uint(local.x) + p.gridSize * (uint(local.y) + p.gridSize * uint(local.z))) * kVoxelSumWords;
        float count = gVoxelSums[p.accum[0]].data[base + kVoxelSumCount];
        float coverage = gVoxelSums[p.accum[0]].data[base + 3u];
        occupied = count > 0.0 && coverage > 0.0;
        if (occupied) {
            // Premultiplied sums: rgb / coverage is the coverage-weighted mean, coverage / count the mean coverage
            // (1 with whole fragments: then exactly the float-add rung's mean).
            value = vec4(vec3(gVoxelSums[p.accum[0]].data[base], gVoxelSums[p.accum[0]].data[base + 1u],
                              gVoxelSums[p.accum[0]].data[base + 2u]) / coverage, coverage / count);
            for (uint c = 0u; c < 4u; ++c) facing[c] = gVoxelSums[p.accum[0]].data[base + 4u + c] / count;
        }
    } else {
        uint red = imageLoad(gVoxelsR32ui[p.accum[0]], local).r;
        occupied = red != 0u;
        if (occupied) {
            uvec3 bits = uvec3(red, imageLoad(gVoxelsR32ui[p.accum[1]], local).r,
                               imageLoad(gVoxelsR32ui[p.accum[2]], local).r);
            value = vec4(uintBitsToFloat(bits - 1u), 1.0);
            for (uint c = 0u; c < 4u; ++c)
                facing[c] = uintBitsToFloat(imageLoad(gVoxelsR32ui[p.accum[kVoxelAccumFacing + c]], local).r) -
                            kVoxelFacingBias;
        }
    }
    if (occupied && previous) return;  // its entry in this frame's list stores it
    if (occupied) imageStore(gVoxelsR32ui[p.cells], voxel >> 1, uvec4(1u));  // every writer stores the same 1
    if (!occupied && p.full == 0u && all(equal(floatBitsToUint(imageLoad(gVoxelsRgba16f[p.grid], voxel)), uvec4(0u))))
        return;
    imageStore(gVoxelsRgba16f[p.grid], voxel, value);
    for (uint k = 0u; k < 6u; ++k)
        storeDirectionVoxel(p.directions[k], p.opacity[k], voxel, vxgiVoxelTowards(value, facing, k));
}
