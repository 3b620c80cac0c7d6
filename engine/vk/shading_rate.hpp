// shading_rate.hpp: the pure arithmetic of the hardware VRS rungs (issue 14): the tile (= shading-rate texel)
// size picked from the device's limits, and the classifier's palette index written in each rung's encoding:
// VK_KHR_fragment_shading_rate attachment texels ((log2 width << 2) | log2 height, spec "Attachment Fragment
// Shading Rate") and VK_NV_shading_rate_image texels (an index into the viewport's palette, whose entries this
// file lists). No device: unit-tested with fake limits (tests/unit/app/shading_rate_test.cpp).
#pragma once
#include <volk.h>

#include <cstdint>
#include <string>

namespace idk::vk {

// The limits that decide the tile. KHR: VkPhysicalDeviceFragmentShadingRatePropertiesKHR's
// min/maxFragmentShadingRateAttachmentTexelSize (powers of two) and ...AspectRatio; NV: the fixed
// VkPhysicalDeviceShadingRateImagePropertiesNV::shadingRateTexelSize.
struct ShadingRateTexelLimits {
    VkExtent2D min{0, 0};
    VkExtent2D max{0, 0};
    uint32_t maxAspectRatio = 0;
};

struct ShadingRateTile {
    uint32_t size = 0;   // square tile side in pixels (0: none fits)
    std::string error;   // why none fits (empty when size != 0)
};

// The classifier works on square tiles of 8, 16 or 32 pixels (vrs/classify.comp: 256 invocations per tile); the
// attachment texel is one tile, so one texel holds one tile's rate. Prefers the original's 16x16 and otherwise
// the square nearest to it inside [min, max].
ShadingRateTile khrShadingRateTile(const ShadingRateTexelLimits& limits);
// NV's texel size is fixed by the device: usable only when it is a square the classifier handles.
ShadingRateTile nvShadingRateTile(VkExtent2D texelSize);

// Palette index (shared/vrs_types.h: 0..4 = 1x1, 2x1, 2x2, 4x2, 4x4; larger is clamped to 4x4) to the KHR
// attachment texel value, and to the NV palette entry that index selects (the palette is bound in this order,
// so an NV texel is the palette index itself, as in IDKEngine).
uint8_t khrShadingRateTexel(uint32_t paletteRate);
VkShadingRatePaletteEntryNV nvPaletteEntry(uint32_t paletteRate);
// Fragment size in pixels of a KHR texel value (width, height): the decoding the spec gives, for tests and logs.
VkExtent2D khrFragmentSize(uint8_t texel);

}  // namespace idk::vk
