#version 460
// workgroup_sum.comp.glsl: each workgroup sums one tile of kItems * 256 elements (uint modulo 2^32, or float) and
// writes one value; repeated passes reduce to a single value. The IDKEngine VRS-article pattern: subgroupAdd,
// one shared slot per subgroup, then the first subgroup combines the slots with another subgroupAdd.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "interop.h"
#include "bindless.glsl"
#include "compute_push.h"

layout(local_size_x = kComputeGroupSize) in;
layout(constant_id = kSpecMinSubgroupSize) const uint kMinSubgroupSize = 1;
layout(constant_id = kSpecSumElement) const uint kElement = kSumElementUint;
layout(constant_id = kSpecSumItemsPerInvocation) const uint kItems = 4;
layout(push_constant, scalar) uniform Push { SumPush p; };

IDK_BINDLESS_BUFFER(gUints, uint);
IDK_BINDLESS_BUFFER(gFloats, float);

// One slot per subgroup. The subgroup size is not a compile-time fact (lavapipe runs 8, NVIDIA 32, AMD 32 or 64,
// and SPIR-V 1.6 lets a pipeline vary within [min, max]), so the array is sized for the smallest subgroup the
// device may use, which the C++ side passes as kMinSubgroupSize (1 = no assumption at all). Subgroups of a 256-wide
// workgroup are packed in order, so gl_SubgroupID < gl_NumSubgroups <= 256 / gl_SubgroupSize <= the slot count;
// the subgroup_probe conformance test checks this on the device in use.
shared uint sSlots[(gl_WorkGroupSize.x + kMinSubgroupSize - 1) / kMinSubgroupSize];

uint tileSumUint(uint tileStart) {
    uint acc = 0;
    for (uint i = 0; i < kItems; ++i) {
        // Strided within the tile so neighbouring invocations read neighbouring elements.
        uint index = tileStart + i * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        if (index < p.count) acc += gUints[p.inputBuffer].data[p.inputOffset + index];
    }
    acc = subgroupAdd(acc);
    if (subgroupElect()) sSlots[gl_SubgroupID] = acc;
    // SYNC: barrier() orders the shared-memory slot writes before the first subgroup reads them.
    barrier();
    acc = 0;
    if (gl_SubgroupID == 0) {
        // Tree-combine the slots inside one subgroup (a few serial steps when there are more slots than lanes).
        for (uint s = gl_SubgroupInvocationID; s < gl_NumSubgroups; s += gl_SubgroupSize) acc += sSlots[s];
        acc = subgroupAdd(acc);
    }
    return acc;
}

float tileSumFloat(uint tileStart) {
    float acc = 0.0;
    for (uint i = 0; i < kItems; ++i) {
        uint index = tileStart + i * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        if (index < p.count) acc += gFloats[p.inputBuffer].data[p.inputOffset + index];
    }
    acc = subgroupAdd(acc);
    if (subgroupElect()) sSlots[gl_SubgroupID] = floatBitsToUint(acc);
    // SYNC: as above.
    barrier();
    acc = 0.0;
    if (gl_SubgroupID == 0) {
        for (uint s = gl_SubgroupInvocationID; s < gl_NumSubgroups; s += gl_SubgroupSize) {
            acc += uintBitsToFloat(sSlots[s]);
        }
        acc = subgroupAdd(acc);
    }
    return acc;
}

void main() {
    uint tileStart = gl_WorkGroupID.x * kItems * gl_WorkGroupSize.x;
    uint outIndex = p.outputOffset + gl_WorkGroupID.x;
    // The combined sum lives in the first subgroup (every invocation of the workgroup reaches this point).
    if (kElement == kSumElementFloat) {
        float sum = tileSumFloat(tileStart);
        if (gl_SubgroupID == 0 && subgroupElect()) gFloats[p.outputBuffer].data[outIndex] = sum;
    } else {
        uint sum = tileSumUint(tileStart);
        if (gl_SubgroupID == 0 && subgroupElect()) gUints[p.outputBuffer].data[outIndex] = sum;
    }
}
