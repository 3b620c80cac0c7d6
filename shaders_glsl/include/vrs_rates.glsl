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

// rates == 0: VRS off, every pixel is shaded.
bool vrsShades(uint64_t rates, uvec2 pixel) {
    return rates == 0ul || vrsIsAnchor(VrsRatesRef(rates), pixel);
}

#endif
