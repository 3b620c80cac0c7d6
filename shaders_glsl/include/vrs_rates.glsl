// vrs_rates.glsl: reading the VRS rate buffer (shared/vrs_types.h) by device address: which palette index a pixel's
// tile has, and whether the pixel is the anchor of its coarse cell (the one sample the software rung shades per
// cell; the lighting and sky passes skip the others, vrs/reconstruct.comp fills them).
#ifndef IDK_VRS_RATES_GLSL
#define IDK_VRS_RATES_GLSL
#extension GL_EXT_buffer_reference : require
#include "vrs_types.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer VrsRatesRef {
    VrsRatesHeader header;
    uint rate[];
};

uint vrsTileRate(VrsRatesRef r, uvec2 pixel) {
    uvec2 tile = pixel / r.header.tileSize;
    return r.rate[tile.y * r.header.tilesX + tile.x];
}

// Cells are aligned to multiples of their size; tiles are multiples of 4, so no cell crosses a tile.
bool vrsIsAnchor(VrsRatesRef r, uvec2 pixel) {
    uvec2 cell = vrsCellSize(vrsTileRate(r, pixel));
    return pixel.x % cell.x == 0u && pixel.y % cell.y == 0u;
}

#ifndef IDK_VRS_FRAGMENT_STAGE  // compute only (workgroup built-ins); the hardware rung's fragment pass defines it
// The software rung in an 8x8-workgroup compute pass (lighting, sky): invocation i of the workgroup takes the i-th
// anchor of its 8x8 block (one rate per block: tiles are multiples of 8), so the shading work is packed into the
// first invocations and whole subgroups past the anchor count exit at once. Skipping non-anchor pixels in place
// would save nothing on SIMD hardware (lavapipe's 8 lanes or a GPU's 32/64 run masked lanes at full cost).
// Returns false for invocations without an anchor; rates == 0 (VRS off) keeps every pixel.
bool vrsAnchorOfInvocation(uint64_t rates, inout ivec2 pixel) {
    if (rates == 0ul) return true;
    VrsRatesRef r = VrsRatesRef(rates);
    uvec2 origin = gl_WorkGroupID.xy * 8u;
    uvec2 perRow = 8u / vrsCellSize(vrsTileRate(r, origin));
    uint i = gl_LocalInvocationIndex;
    if (i >= perRow.x * perRow.y) return false;
    pixel = ivec2(origin + uvec2(i % perRow.x, i / perRow.x) * (8u / perRow));
    return true;
}

#endif  // IDK_VRS_FRAGMENT_STAGE

#endif
