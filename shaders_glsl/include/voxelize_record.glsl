// voxelize_record.glsl: the record append of the gl-interop rung of "vxgi-atomics" (layout: shared/vxgi_types.h,
// kVoxelRecord*). Include after voxelize_fragment.glsl (its push block `p`).
#ifndef IDK_VOXELIZE_RECORD_GLSL
#define IDK_VOXELIZE_RECORD_GLSL
#include "bindless.glsl"

IDK_BINDLESS_BUFFER(gVoxelRecords, uint);

void appendVoxelRecord(ivec3 voxel, vec3 radiance, vec4 facing) {
    // One atomic per fragment on one counter: on a GPU a subgroup would add its fragments' count once (fewer
    // atomics on the hot word); lavapipe runs few fragments at a time, so the plain form is kept.
    uint slot = atomicAdd(gVoxelRecords[p.accum[0]].data[0], 1u);
    if (slot >= p.accum[1]) return;  // past the capacity: counted, not written (the host grows the buffer)
    uint n = p.gridSize;
    uint base = kVoxelRecordHeaderWords + slot * kVoxelRecordWords;
    const float coverage = 1.0;  // a fragment covers its voxel (the float-add rung's count of 1)
    gVoxelRecords[p.accum[0]].data[base + 0u] = uint(voxel.x) + n * (uint(voxel.y) + n * uint(voxel.z));
    gVoxelRecords[p.accum[0]].data[base + 1u] = floatBitsToUint(radiance.r * coverage);
    gVoxelRecords[p.accum[0]].data[base + 2u] = floatBitsToUint(radiance.g * coverage);
    gVoxelRecords[p.accum[0]].data[base + 3u] = floatBitsToUint(radiance.b * coverage);
    gVoxelRecords[p.accum[0]].data[base + 4u] = floatBitsToUint(coverage);
    for (uint c = 0u; c < 4u; ++c) gVoxelRecords[p.accum[0]].data[base + 5u + c] = floatBitsToUint(facing[c]);
}

#endif
