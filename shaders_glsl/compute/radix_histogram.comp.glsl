#version 460
// radix_histogram.comp.glsl: one LSD radix-sort pass, step 1: each workgroup counts the 8-bit digits
// (key >> shift) & 255 of its 2048-key tile and writes the 256 counts digit-major (digit * blockCount + block),
// ready for the exclusive scan that turns them into stable output positions.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bindless.glsl"
#include "compute_push.h"

layout(local_size_x = kComputeGroupSize) in;
layout(push_constant, scalar) uniform Push { RadixPush p; };

IDK_BINDLESS_BUFFER(gUints, uint);

const uint kItems = kSortItemsPerInvocation;
const uint kTile = kComputeGroupSize * kItems;

// kRadixDigits == kComputeGroupSize (checked on the C++ side): invocation i owns counter i.
shared uint sCounts[kRadixDigits];

void main() {
    uint local = gl_LocalInvocationIndex;
    sCounts[local] = 0;
    // SYNC: counters are cleared before any invocation increments them.
    barrier();
    uint tileStart = gl_WorkGroupID.x * kTile;
    for (uint i = 0; i < kItems; ++i) {
        // Strided, so neighbouring invocations read neighbouring keys; the order of counting does not matter.
        uint index = tileStart + i * gl_WorkGroupSize.x + local;
        if (index < p.count) {
            uint key = gUints[p.keysIn].data[p.keysInOffset + index];
            atomicAdd(sCounts[(key >> p.shift) & (kRadixDigits - 1)], 1u);
        }
    }
    // SYNC: all increments land before the counts are read.
    barrier();
    gUints[p.histograms].data[p.histogramsOffset + local * p.blockCount + gl_WorkGroupID.x] = sCounts[local];
}
