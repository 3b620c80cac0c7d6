#version 460
// merge.comp.glsl: resolves the voxelization's accumulators into the RGBA16F grid (rgb = the voxel's radiance: mean
// of its fragments for the float-add and gl-interop rungs, per-channel max for the r32ui rung; alpha = coverage, 1
// where a fragment landed, 0 elsewhere) and into level 0 of the six directional volumes: the voxel seen travelling
// along each axis direction, by its mean facing (vxgiVoxelTowards, shared/vxgi_cone.h). Ports IDKEngine's
// VXGI/Voxelize merge compute shader (4x4x4 groups); its level 0 is isotropic.
#extension GL_GOOGLE_include_directive : require
#include "vxgi_types.h"
#include "vxgi_cone.h"
#include "voxel_images.glsl"

IDK_BINDLESS_BUFFER_READONLY(gVoxelSums, float);  // kVoxelAtomicsGlRecords: the GL pass's sums (kVoxelSumWords each)

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(push_constant, scalar) uniform Push { VoxelMergePush p; };

void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, ivec3(p.gridSize)))) return;
    vec4 value = vec4(0.0), facing = vec4(0.0);
    if (p.mode == kVoxelAtomicsFloatAdd) {
        float count = imageLoad(gVoxelsR32f[p.accum[kVoxelAccumCount]], voxel).r;
        if (count > 0.0) {
            value = vec4(imageLoad(gVoxelsR32f[p.accum[0]], voxel).r, imageLoad(gVoxelsR32f[p.accum[1]], voxel).r,
                         imageLoad(gVoxelsR32f[p.accum[2]], voxel).r, count) / count;
            for (uint c = 0u; c < 4u; ++c)
                facing[c] = imageLoad(gVoxelsR32f[p.accum[kVoxelAccumFacing + c]], voxel).r / count;
        }
    } else if (p.mode == kVoxelAtomicsGlRecords) {
        uint base = (uint(voxel.x) + p.gridSize * (uint(voxel.y) + p.gridSize * uint(voxel.z))) * kVoxelSumWords;
        float count = gVoxelSums[p.accum[0]].data[base + kVoxelSumCount];
        float coverage = gVoxelSums[p.accum[0]].data[base + 3u];
        if (count > 0.0 && coverage > 0.0) {
            // Premultiplied sums: rgb / coverage is the coverage-weighted mean, coverage / count the mean coverage
            // (1 with whole fragments: then exactly the float-add rung's mean).
            value = vec4(vec3(gVoxelSums[p.accum[0]].data[base], gVoxelSums[p.accum[0]].data[base + 1u],
                              gVoxelSums[p.accum[0]].data[base + 2u]) / coverage, coverage / count);
            for (uint c = 0u; c < 4u; ++c) facing[c] = gVoxelSums[p.accum[0]].data[base + 4u + c] / count;
        }
    } else {
        uvec3 bits = uvec3(imageLoad(gVoxelsR32ui[p.accum[0]], voxel).r, imageLoad(gVoxelsR32ui[p.accum[1]], voxel).r,
                           imageLoad(gVoxelsR32ui[p.accum[2]], voxel).r);
        if (bits.r != 0u) {
            value = vec4(uintBitsToFloat(bits - 1u), 1.0);
            for (uint c = 0u; c < 4u; ++c)
                facing[c] = uintBitsToFloat(imageLoad(gVoxelsR32ui[p.accum[kVoxelAccumFacing + c]], voxel).r) -
                            kVoxelFacingBias;
        }
    }
    imageStore(gVoxelsRgba16f[p.grid], voxel, value);
    for (uint k = 0u; k < 6u; ++k) imageStore(gVoxelsRgba16f[p.directions[k]], voxel, vxgiVoxelTowards(value, facing, k));
}
