// oit_layers.glsl (GLSL include): the fixed-layer OIT rung's per-pixel arrays (OitLayerBuffers in oit_types.h):
// insertion of a depth into the sorted key array and the shading pass's slot claim.
// Departure from IDKEngine (reference 2.14), which keeps the first kOitLayerCount arrivals through a counter: this
// keeps the kOitLayerCount NEAREST, so beyond the layer count only the farthest, most hidden layers are lost.
#ifndef IDK_OIT_LAYERS_INCLUDE_GLSL
#define IDK_OIT_LAYERS_INCLUDE_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#include "oit_types.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) coherent buffer OitWords { uint data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer OitColors { uvec2 data[]; };

uint oitPixel(OitLayerBuffers l, ivec2 pixel) { return uint(pixel.y) * l.width + uint(pixel.x); }

// Atomic insertion: each slot keeps the minimum of what reaches it and the larger value moves on to the next slot.
// Concurrent inserts commute (every slot ends as the min of the values that reach it), so after the pass the slots
// hold the kOitLayerCount smallest keys in ascending order, equal depths in separate slots. A key pushed past
// the last slot is dropped. Lock free: no spin loops (they can hang GPUs that do not schedule diverged lanes).
void oitInsertDepth(OitLayerBuffers l, ivec2 pixel, float depth) {
    uint key = floatBitsToUint(depth);  // depth in [0, 1]: the bit patterns order as the floats
    uint i = oitPixel(l, pixel);
    for (uint s = 0u; s < kOitLayerCount; ++s) {
        uint old = atomicMin(OitWords(l.keys).data[s * l.pixelCount + i], key);
        if (old == kOitEmptyKey) return;
        key = max(old, key);
    }
}

// The slot this fragment's depth landed in, or -1 if it was not among the nearest. Fragments of equal depth claim
// distinct slots through the claim bits (atomicOr returns who was first).
int oitClaimSlot(OitLayerBuffers l, ivec2 pixel, float depth) {
    uint key = floatBitsToUint(depth);
    uint i = oitPixel(l, pixel);
    for (uint s = 0u; s < kOitLayerCount; ++s) {
        uint k = OitWords(l.keys).data[s * l.pixelCount + i];
        if (k > key) return -1;  // ascending: no later slot can match
        if (k != key) continue;
        uint bit = 1u << s;
        if ((atomicOr(OitWords(l.claims).data[i], bit) & bit) == 0u) return int(s);
    }
    return -1;
}

void oitStoreColor(OitLayerBuffers l, ivec2 pixel, int slot, vec4 c) {
    uint i = oitPixel(l, pixel);
    OitColors(l.colors).data[uint(slot) * l.pixelCount + i] = uvec2(packHalf2x16(c.rg), packHalf2x16(vec2(c.b, c.a)));
}

#endif
