// vrs_hardware_types.h: the push blocks of the hardware VRS rungs (issue 14; frame/vrs_hardware.cpp), shared by
// C++ and GLSL: the rate-image converter (vrs/rate_image.comp: palette indices -> one byte per tile in the rung's
// encoding) and the fragment lighting + sky pass (vrs/lighting_rate.frag) that runs at those rates.
#ifndef IDK_VRS_HARDWARE_TYPES_H
#define IDK_VRS_HARDWARE_TYPES_H
#include "interop.h"
#include "deferred_types.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kVrsEncodingKhr, 0);   // VK_KHR_fragment_shading_rate texel: vrsKhrRateTexel (shared/vrs_types.h)
IDK_CONST(uint, kVrsEncodingNv, 1);    // VK_NV_shading_rate_image texel: the palette index
IDK_CONST(uint, kVrsRateImageGroupSize, 64);

// rate_image.comp: one invocation per 4 tiles writes one uint (4 bytes, tile order) of the staging buffer that a
// copy then turns into the R8_UINT rate image (no 8-bit storage or R8 storage-image support needed).
struct VrsRateImagePush {
    DeviceAddress rates;   // VrsRatesHeader + uint[tiles]
    DeviceAddress texels;  // uint[(tiles + 3) / 4]
    uint tiles;
    uint encoding;         // kVrsEncodingKhr / kVrsEncodingNv
};
IDK_GPU_SIZE(VrsRateImagePush, 24);

// lighting_rate.frag: lighting + sky of the pixels the rasterizer shades at the attachment's rates.
struct VrsLightingRatePush {
    LightingPush lighting;      // lighting.vrsRates: the rates (the fragment shades its cell's anchor pixel)
    DeviceAddress invocations;  // uint: fragment invocations, counted with an atomic (shadingInvocations)
};
IDK_GPU_SIZE(VrsLightingRatePush, 88);

IDK_GPU_END
#endif
