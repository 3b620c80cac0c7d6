// compute_push.h: push-constant blocks, specialization-constant ids and tile sizes of the compute primitives
// (workgroup sum, exclusive scan, LSD radix sort), shared by engine/render/compute_primitives.cpp and
// shaders_glsl/conformance/{workgroup_sum,scan_add,radix_histogram,radix_scatter,subgroup_probe}.comp.glsl.
// Every array argument is a bindless storage-buffer index plus an offset counted in 32-bit elements.
#ifndef IDK_COMPUTE_PUSH_H
#define IDK_COMPUTE_PUSH_H
#include "interop.h"

IDK_GPU_BEGIN
IDK_CONST(uint, kComputeGroupSize, 256);        // invocations per workgroup of every primitive
IDK_CONST(uint, kScanItemsPerInvocation, 8);    // scan tile = 2048 elements (also the scan's reduce tile)
IDK_CONST(uint, kSortItemsPerInvocation, 8);    // radix sort tile = 2048 keys
IDK_CONST(uint, kRadixBits, 8);                 // bits per LSD pass
IDK_CONST(uint, kRadixDigits, 256);             // 1 << kRadixBits, one shared counter per invocation

// Specialization-constant ids (layout(constant_id = ...)).
// kSpecMinSubgroupSize sizes the per-subgroup shared slots as kComputeGroupSize / kSpecMinSubgroupSize: it must
// not exceed the smallest subgroup the device can run (VkPhysicalDeviceSubgroupSizeControlProperties::
// minSubgroupSize), because SPIR-V 1.6 pipelines may run with any size in [min, max]. 1 is always safe.
IDK_CONST(uint, kSpecMinSubgroupSize, 0);
IDK_CONST(uint, kSpecSumElement, 1);            // workgroup_sum: 0 = uint (mod 2^32), 1 = float
IDK_CONST(uint, kSpecSumItemsPerInvocation, 2); // workgroup_sum: elements summed by each invocation
IDK_CONST(uint, kSpecSortWithValues, 3);        // radix_scatter: 1 = move a 32-bit value with each key

IDK_CONST(uint, kSumElementUint, 0);
IDK_CONST(uint, kSumElementFloat, 1);
IDK_CONST(uint, kScanAddBlockOffsets, 1);       // ScanPush::flags: add blockOffsets[workgroup] to the tile

// workgroup_sum: outputBuffer[outputOffset + g] = sum of inputBuffer[inputOffset + g * tile ...] (tile elements,
// clamped to count).
struct SumPush {
    uint inputBuffer;
    uint inputOffset;
    uint outputBuffer;
    uint outputOffset;
    uint count;
};
IDK_GPU_SIZE(SumPush, 20);

// scan_add: outputBuffer = exclusive scan of inputBuffer within each 2048-element tile, plus blockOffsets[workgroup]
// when flags has kScanAddBlockOffsets. input and output may be the same range.
struct ScanPush {
    uint inputBuffer;
    uint inputOffset;
    uint outputBuffer;
    uint outputOffset;
    uint blockOffsets;
    uint blockOffsetsOffset;
    uint count;
    uint flags;
};
IDK_GPU_SIZE(ScanPush, 32);

// radix_histogram / radix_scatter: one LSD pass over bits [shift, shift + kRadixBits). histograms holds
// kRadixDigits * blockCount counters, digit-major (digit * blockCount + block), so that its exclusive scan gives
// every (digit, block) pair its first output position and the scatter stays stable.
struct RadixPush {
    uint keysIn;
    uint keysInOffset;
    uint keysOut;
    uint keysOutOffset;
    uint valuesIn;
    uint valuesInOffset;
    uint valuesOut;
    uint valuesOutOffset;
    uint histograms;
    uint histogramsOffset;
    uint count;
    uint shift;
    uint blockCount;
};
IDK_GPU_SIZE(RadixPush, 52);

// subgroup_probe: one record per invocation of one 256-invocation workgroup.
struct SubgroupProbeRecord {
    uint subgroupSize;
    uint subgroupId;
    uint numSubgroups;
    uint subgroupInvocationId;
    uint subgroupSum;  // subgroupAdd(1): the number of active invocations in this subgroup
};
IDK_GPU_SIZE(SubgroupProbeRecord, 20);

struct ProbePush {
    uint records;
    uint recordsOffset;
};
IDK_GPU_SIZE(ProbePush, 8);
IDK_GPU_END

#endif
