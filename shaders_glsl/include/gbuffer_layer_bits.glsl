// gbuffer_layer_bits.glsl: which texels of the newer material extensions the G-buffer's optional layers target
// (RGBA32UI, gbuffer_fragment.glsl) carries in its spare bits (y.a, z.a and w), packed by the G-buffer pass and
// unpacked by the deferred lighting pass (deferred_lighting_pixel.glsl) from the same material flags.
// 48 spare bits cannot hold every texel at once (iridescence 16, diffuse transmission 32, coat normal 24,
// anisotropy direction 16 + strength 8), so a material that combines them keeps the first of each pair below in
// the deferred pass and takes the factors alone for the other (the forward pass and the path tracers read every
// texture; a real renderer with many such materials would add a second layers target):
//   y.a, z.a    iridescenceTexture R, iridescenceThicknessTexture G; else diffuseTransmissionTexture A and
//               diffuseTransmissionColorTexture R (sRGB)
//   w 0..23     the coat normal (clearcoatNormalTexture), octahedral in 2 x 12 bits; else w 0..15 the
//               KHR_materials_anisotropy direction (gbuffer_anisotropy.glsl; without it the isotropic lobe at the
//               rms roughness)
//   w 24..31    anisotropyTexture B of an anisotropic material; else w 16..31 the diffuse-transmission colour's
//               G, B (sRGB), when y.a and z.a hold its other texels
#ifndef IDK_GBUFFER_LAYER_BITS_GLSL
#define IDK_GBUFFER_LAYER_BITS_GLSL
#include "scene_types.h"

bool layerBitsHoldCoatNormal(uint flags) { return (flags & kMaterialClearcoatNormal) != 0u; }
bool layerBitsHoldAnisotropyDirection(uint flags) {
    return (flags & kMaterialAnisotropy) != 0u && !layerBitsHoldCoatNormal(flags);
}
bool layerBitsHoldDiffuseTransmission(uint flags) {
    return (flags & kMaterialDiffuseTransmission) != 0u &&
           (flags & (kMaterialIridescence | kMaterialClearcoatNormal | kMaterialAnisotropy)) == 0u;
}

// y.a and z.a. diffTransColorSrgb: the sRGB-encoded colour texel.
vec2 packLayerAlphas(uint flags, vec2 iridescenceT, float diffTransT, vec3 diffTransColorSrgb) {
    if ((flags & kMaterialIridescence) != 0u) return iridescenceT;
    return layerBitsHoldDiffuseTransmission(flags) ? vec2(diffTransT, diffTransColorSrgb.r) : vec2(1.0);
}

// w. coatOct: the coat normal's octahedral xy in [-1, 1]; anisotropyWord: encodeAnisotropyDirection's 16 bits.
uint packLayerWord(uint flags, vec2 coatOct, uint anisotropyWord, float anisotropyStrengthT, vec3 diffTransColorSrgb) {
    uint w = 0u;
    if (layerBitsHoldCoatNormal(flags)) {
        uvec2 q = uvec2(round(clamp(coatOct * 0.5 + 0.5, 0.0, 1.0) * 4095.0));
        w = q.x | (q.y << 12u);
    } else if (layerBitsHoldAnisotropyDirection(flags)) {
        w = anisotropyWord & 0xFFFFu;
    }
    if ((flags & kMaterialAnisotropy) != 0u) {
        w |= uint(round(clamp(anisotropyStrengthT, 0.0, 1.0) * 255.0)) << 24u;
    } else if (layerBitsHoldDiffuseTransmission(flags)) {
        w |= packUnorm4x8(vec4(diffTransColorSrgb.gb, 0.0, 0.0)) << 16u;
    }
    return w;
}

vec2 unpackCoatNormalOct(uint w) { return vec2(uvec2(w & 4095u, (w >> 12u) & 4095u)) / 4095.0 * 2.0 - 1.0; }
float unpackAnisotropyStrengthTexel(uint flags, uint w) {
    return (flags & kMaterialAnisotropy) != 0u ? float(w >> 24u) / 255.0 : 1.0;
}
// The diffuse-transmission texels (A; colour sRGB-encoded), white when the bits hold something else.
void unpackDiffuseTransmissionTexels(uint flags, vec2 alphas, uint w, out float factor, out vec3 colorSrgb) {
    factor = 1.0;
    colorSrgb = vec3(1.0);
    if (layerBitsHoldDiffuseTransmission(flags)) {
        factor = alphas.x;
        colorSrgb = vec3(alphas.y, unpackUnorm4x8(w >> 16u).xy);
    }
}

#endif
