#version 460
// radix_scatter.comp.glsl: one LSD radix-sort pass, step 3: each workgroup stably sorts its 2048-key tile by the
// 8-bit digit in shared memory (eight 1-bit splits, each a workgroup-wide scan), then writes every key (and value)
// to scannedHistogram[digit * blockCount + block] + its rank among the tile's keys with that digit. Stable: keys
// with equal digits keep their tile order, and tiles are placed in block order.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "interop.h"
#include "bindless.glsl"
#include "compute_push.h"

layout(local_size_x = kComputeGroupSize) in;
layout(constant_id = kSpecMinSubgroupSize) const uint kMinSubgroupSize = 1;
layout(constant_id = kSpecSortWithValues) const uint kWithValues = 0;
layout(push_constant, scalar) uniform Push { RadixPush p; };

IDK_BINDLESS_BUFFER(gUints, uint);

const uint kItems = kSortItemsPerInvocation;
const uint kTile = kComputeGroupSize * kItems;
const uint kDigitMask = kRadixDigits - 1;

shared uint sKeys[kTile];
shared uint sValues[kWithValues != 0 ? kTile : 1];
shared uint sDigitStart[kRadixDigits];

#include "workgroup_scan.glsl"

uint digitOf(uint key) { return (key >> p.shift) & kDigitMask; }

void main() {
    uint tileStart = gl_WorkGroupID.x * kTile;
    uint validCount = min(p.count - tileStart, kTile);
    uint first = gl_LocalInvocationIndex * kItems;  // this invocation owns tile positions [first, first + kItems)
    uint keys[kItems];
    uint values[kItems];
    for (uint i = 0; i < kItems; ++i) {
        uint index = tileStart + first + i;
        bool valid = index < p.count;
        // Past the end: all-ones keys have digit 255 in every pass and start behind every real key, so the stable
        // local sort keeps them last in the tile, behind the real digit-255 keys; they are never written.
        keys[i] = valid ? gUints[p.keysIn].data[p.keysInOffset + index] : 0xFFFFFFFFu;
        values[i] = (kWithValues != 0 && valid) ? gUints[p.valuesIn].data[p.valuesInOffset + index] : 0u;
    }

    // Stable local sort by the digit, least significant bit first: zeros keep their order in front, ones behind.
    for (uint bit = 0; bit < kRadixBits; ++bit) {
        uint shift = p.shift + bit;
        uint zeros = 0;
        for (uint i = 0; i < kItems; ++i) zeros += ((keys[i] >> shift) & 1u) ^ 1u;
        uint totalZeros;
        uint zeroRank = workgroupExclusiveAdd(zeros, totalZeros);
        uint oneRank = totalZeros + (first - zeroRank);
        // No barrier needed before the writes: every read of sKeys/sValues from the previous round happened before
        // the barriers inside workgroupExclusiveAdd.
        for (uint i = 0; i < kItems; ++i) {
            bool one = ((keys[i] >> shift) & 1u) != 0;
            uint position = one ? oneRank++ : zeroRank++;
            sKeys[position] = keys[i];
            if (kWithValues != 0) sValues[position] = values[i];
        }
        // SYNC: the whole permuted tile is in shared memory before it is read back.
        barrier();
        for (uint i = 0; i < kItems; ++i) {
            keys[i] = sKeys[first + i];
            if (kWithValues != 0) values[i] = sValues[first + i];
        }
    }

    // The tile is now ordered by digit: the first position of each digit run is where its rank 0 is.
    for (uint i = 0; i < kItems; ++i) {
        uint position = first + i;
        uint digit = digitOf(keys[i]);
        if (position == 0 || digitOf(sKeys[position - 1]) != digit) sDigitStart[digit] = position;
    }
    // SYNC: run starts are written before the scatter reads them.
    barrier();
    for (uint i = 0; i < kItems; ++i) {
        uint position = first + i;
        if (position >= validCount) break;
        uint digit = digitOf(keys[i]);
        uint destination = gUints[p.histograms].data[p.histogramsOffset + digit * p.blockCount + gl_WorkGroupID.x] +
                           position - sDigitStart[digit];
        gUints[p.keysOut].data[p.keysOutOffset + destination] = keys[i];
        if (kWithValues != 0) gUints[p.valuesOut].data[p.valuesOutOffset + destination] = values[i];
    }
}
