#version 460
// rate_image.comp.glsl: the classifier's palette indices (shared/vrs_types.h) as hardware shading-rate texels, one
// byte per tile: VK_KHR_fragment_shading_rate's (log2 w << 2) | log2 h, or VK_NV_shading_rate_image's palette index.
// Four tiles per invocation packed little-endian into one uint, so the staging buffer holds the R8_UINT texels in
// tile order for vkCmdCopyBufferToImage (frame/vrs_hardware.cpp).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "vrs_types.h"
#include "vrs_hardware_types.h"
#include "vrs_rates.glsl"

layout(local_size_x = kVrsRateImageGroupSize) in;
layout(push_constant, scalar) uniform Push { VrsRateImagePush p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer TexelWords { uint word[]; };

void main() {
    uint first = gl_GlobalInvocationID.x * 4u;
    if (first >= p.tiles) return;
    VrsRatesRef rates = VrsRatesRef(p.rates);
    uint packed = 0u;
    for (uint i = 0u; i < 4u && first + i < p.tiles; ++i) {
        uint rate = rates.rate[first + i];
        uint texel = p.encoding == kVrsEncodingKhr ? vrsKhrRateTexel(rate) : min(rate, kVrsRateCount - 1u);
        packed |= texel << (8u * i);
    }
    TexelWords(p.texels).word[gl_GlobalInvocationID.x] = packed;
}
