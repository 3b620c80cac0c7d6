#version 460
// scan_add.comp.glsl: exclusive prefix scan (uint, modulo 2^32) of one 2048-element tile per workgroup, plus an
// optional per-tile offset: the last pass of the reduce-then-scan in engine/render/compute_primitives.cpp, and
// the whole scan when the input fits one tile. Each invocation owns 8 consecutive elements.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "interop.h"
#include "bindless.glsl"
#include "compute_push.h"

layout(local_size_x = kComputeGroupSize) in;
layout(constant_id = kSpecMinSubgroupSize) const uint kMinSubgroupSize = 1;
layout(push_constant, scalar) uniform Push { ScanPush p; };

IDK_BINDLESS_BUFFER(gUints, uint);

const uint kItems = kScanItemsPerInvocation;
const uint kTile = kComputeGroupSize * kItems;


#include "workgroup_scan.glsl"

void main() {
    uint first = gl_WorkGroupID.x * kTile + gl_LocalInvocationIndex * kItems;
    uint values[kItems];
    uint sum = 0;
    for (uint i = 0; i < kItems; ++i) {
        uint index = first + i;
        values[i] = index < p.count ? gUints[p.inputBuffer].data[p.inputOffset + index] : 0;
        sum += values[i];
    }
    // Every invocation has read its whole tile range before anything is written, and tiles do not overlap, so
    // input and output may be the same range (the recursive levels scan their block sums in place).
    uint running = workgroupExclusiveAdd(sum);
    if ((p.flags & kScanAddBlockOffsets) != 0) {
        running += gUints[p.blockOffsets].data[p.blockOffsetsOffset + gl_WorkGroupID.x];
    }
    for (uint i = 0; i < kItems; ++i) {
        uint index = first + i;
        if (index < p.count) gUints[p.outputBuffer].data[p.outputOffset + index] = running;
        running += values[i];
    }
}
