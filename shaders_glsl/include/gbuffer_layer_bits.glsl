// gbuffer_layer_bits.glsl: which texels of the newer material extensions the G-buffer's optional layers targets
// carry, packed by the G-buffer pass (gbuffer_fragment.glsl) and unpacked by the deferred lighting pass
// (deferred_lighting_pixel.glsl) from the same material flags.
// The first layers target (RGBA32UI) has 48 spare bits (y.a, z.a and w); they cannot hold every texel at once
// (iridescence 16, diffuse transmission 32, coat normal 24, anisotropy direction 16 + strength 8), so a material
// that combines them keeps the first of each pair below there:
//   y.a, z.a    iridescenceTexture R, iridescenceThicknessTexture G; else diffuseTransmissionTexture A and
//               diffuseTransmissionColorTexture R (sRGB)
//   w 0..23     the coat normal (clearcoatNormalTexture), octahedral in 2 x 12 bits; else w 0..15 the
//               KHR_materials_anisotropy direction (gbuffer_anisotropy.glsl; without it the isotropic lobe at the
//               rms roughness)
//   w 24..31    anisotropyTexture B of an anisotropic material; else w 16..31 the diffuse-transmission colour's
//               G, B (sRGB), when y.a and z.a hold its other texels
// and the second ("spill") target (RG32UI), allocated only for scenes with a material whose textures need it
// (scene::SceneFeatures::hasSpilledLayerTexels), takes the other of each pair:
//   x           the diffuse-transmission texels (packUnorm4x8: colour R, G, B sRGB-encoded, factor A) of a material
//               whose first-target bits hold iridescence, the coat normal or anisotropy
//   y 0..15     the anisotropy direction of a material whose w holds the coat normal
// Without the spill target those texels are dropped and the factors alone shade (right when the material has no
// such texture, which is when the frame recipe leaves the target out). Its cost on a GPU: 8 more bytes per
// pixel written by the G-buffer and read by the lighting pass, ~33 MB of traffic per 1080p frame (2 GB/s at
// 60 fps), which is why scenes that fit keep the single target.
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

// The spill target's word pair (x: diffuse transmission, y: anisotropy direction), zero where unused.
bool layerBitsSpillDiffuseTransmission(uint flags) {
    return (flags & kMaterialDiffuseTransmission) != 0u && !layerBitsHoldDiffuseTransmission(flags);
}
bool layerBitsSpillAnisotropyDirection(uint flags) {
    return (flags & kMaterialAnisotropy) != 0u && layerBitsHoldCoatNormal(flags);
}
uvec2 packLayerSpill(uint flags, float diffTransT, vec3 diffTransColorSrgb, uint anisotropyWord) {
    uvec2 spill = uvec2(0u);
    if (layerBitsSpillDiffuseTransmission(flags)) spill.x = packUnorm4x8(vec4(diffTransColorSrgb, diffTransT));
    if (layerBitsSpillAnisotropyDirection(flags)) spill.y = anisotropyWord & 0xFFFFu;
    return spill;
}

vec2 unpackCoatNormalOct(uint w) { return vec2(uvec2(w & 4095u, (w >> 12u) & 4095u)) / 4095.0 * 2.0 - 1.0; }
float unpackAnisotropyStrengthTexel(uint flags, uint w) {
    return (flags & kMaterialAnisotropy) != 0u ? float(w >> 24u) / 255.0 : 1.0;
}
// The diffuse-transmission texels (A; colour sRGB-encoded), from the first target, else from the spill target's x
// (haveSpill: it was allocated), else white.
void unpackDiffuseTransmissionTexels(uint flags, vec2 alphas, uint w, bool haveSpill, uint spillX, out float factor,
                                     out vec3 colorSrgb) {
    factor = 1.0;
    colorSrgb = vec3(1.0);
    if (layerBitsHoldDiffuseTransmission(flags)) {
        factor = alphas.x;
        colorSrgb = vec3(alphas.y, unpackUnorm4x8(w >> 16u).xy);
    } else if (haveSpill && layerBitsSpillDiffuseTransmission(flags)) {
        vec4 t = unpackUnorm4x8(spillX);
        factor = t.a;
        colorSrgb = t.rgb;
    }
}

#endif
