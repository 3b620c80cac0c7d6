// shading_rate.cpp: tile size from the device's shading-rate texel limits, and palette index -> KHR / NV
// encodings (see shading_rate.hpp). The GLSL converter (vrs/rate_image.comp) encodes with the same
// vrsKhrRateTexel of shared/vrs_types.h; this file holds the C++ side the tests compare against the spec.
#include "vk/shading_rate.hpp"

#include <algorithm>

#include "shared/vrs_types.h"

namespace idk::vk {
namespace {

constexpr uint32_t kMinClassifierTile = 8, kMaxClassifierTile = 32, kPreferredTile = gpu::kVrsDefaultTileSize;

std::string extent(VkExtent2D e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

bool powerOfTwo(uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }

}  // namespace

ShadingRateTile khrShadingRateTile(const ShadingRateTexelLimits& l) {
    const std::string range = extent(l.min) + ".." + extent(l.max);
    if (!powerOfTwo(l.min.width) || !powerOfTwo(l.min.height) || !powerOfTwo(l.max.width) ||
        !powerOfTwo(l.max.height) || l.maxAspectRatio == 0)
        return {0, "attachment texel limits " + range + " are not powers of two (the device reports no attachment rate)"};
    // A square texel needs a side inside both [min.width, max.width] and [min.height, max.height]; a square has
    // aspect ratio 1, which every maxAspectRatio (>= 1) allows.
    const uint32_t lo = std::max({l.min.width, l.min.height, kMinClassifierTile});
    const uint32_t hi = std::min({l.max.width, l.max.height, kMaxClassifierTile});
    if (lo > hi)
        return {0, "attachment texel sizes " + range + " allow no square tile of 8, 16 or 32 pixels (the classifier's)"};
    return {std::clamp(kPreferredTile, lo, hi), ""};  // powers of two clamped by powers of two stay powers of two
}

ShadingRateTile nvShadingRateTile(VkExtent2D t) {
    if (t.width != t.height || !powerOfTwo(t.width) || t.width < kMinClassifierTile || t.width > kMaxClassifierTile)
        return {0, "shading-rate texel " + extent(t) + " is not a square of 8, 16 or 32 pixels (the classifier's)"};
    return {t.width, ""};
}

uint8_t khrShadingRateTexel(uint32_t paletteRate) { return uint8_t(gpu::vrsKhrRateTexel(paletteRate)); }

VkShadingRatePaletteEntryNV nvPaletteEntry(uint32_t paletteRate) {
    switch (std::min(paletteRate, gpu::kVrsRateCount - 1)) {
        case 0: return VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_PIXEL_NV;
        case 1: return VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_2X1_PIXELS_NV;
        case 2: return VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_2X2_PIXELS_NV;
        case 3: return VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_4X2_PIXELS_NV;
        default: return VK_SHADING_RATE_PALETTE_ENTRY_1_INVOCATION_PER_4X4_PIXELS_NV;
    }
}

VkExtent2D khrFragmentSize(uint8_t texel) { return {1u << ((texel >> 2) & 3u), 1u << (texel & 3u)}; }

}  // namespace idk::vk
