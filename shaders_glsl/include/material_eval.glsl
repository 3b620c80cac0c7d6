// material_eval.glsl: glTF material inputs at a fragment, shared by the G-buffer and the forward transparency
// pass: a texture slot with its KHR_texture_transform, and the tangent frame for normal mapping (vertex tangent
// with handedness, else a screen-space cotangent frame). From IDKEngine's GBuffer/fragment.glsl with its
// normal-map bugs fixed (reference section 5).
#ifndef IDK_MATERIAL_EVAL_GLSL
#define IDK_MATERIAL_EVAL_GLSL
#include "scene_types.h"
#include "bindless.glsl"

vec4 sampleMaterialSlot(GpuTextureSlot slot, vec2 uv0, vec2 uv1) {
    vec3 h = vec3(slot.texCoord == 1u ? uv1 : uv0, 1.0);
    vec2 st = vec2(dot(slot.row0, h), dot(slot.row1, h));
    uint t = slot.texture, s = slot.samplerIndex;
    return texture(sampler2D(gTextures2D[nonuniformEXT(t)], gSamplers[nonuniformEXT(s)]), st);
}

// The KHR_materials_specular / _clearcoat / _sheen texture channels of a fragment, in the LayerTexels order
// of material_layers.glsl: specular A, specularColor RGB, clearcoat R, clearcoatRoughness G, sheenColor RGB,
// sheenRoughness A (colour slots are sRGB views, so RGB arrives linear). Call in uniform control flow.
void sampleLayerTexels(GpuMaterial m, vec2 uv0, vec2 uv1, out float specular, out vec3 specularColor,
                       out float clearcoat, out float clearcoatRoughness, out vec3 sheenColor,
                       out float sheenRoughness) {
    specular = sampleMaterialSlot(m.slots[kSlotSpecular], uv0, uv1).a;
    specularColor = sampleMaterialSlot(m.slots[kSlotSpecularColor], uv0, uv1).rgb;
    clearcoat = sampleMaterialSlot(m.slots[kSlotClearcoat], uv0, uv1).r;
    clearcoatRoughness = sampleMaterialSlot(m.slots[kSlotClearcoatRoughness], uv0, uv1).g;
    sheenColor = sampleMaterialSlot(m.slots[kSlotSheenColor], uv0, uv1).rgb;
    sheenRoughness = sampleMaterialSlot(m.slots[kSlotSheenRoughness], uv0, uv1).a;
}

// KHR_materials_diffuse_transmission's texture channels: diffuseTransmissionTexture A, diffuseTransmissionColorTexture
// RGB (an sRGB view: linear). Call in uniform control flow.
void sampleDiffuseTransmissionTexels(GpuMaterial m, vec2 uv0, vec2 uv1, out float factor, out vec3 color) {
    factor = sampleMaterialSlot(m.slots[kSlotDiffuseTransmission], uv0, uv1).a;
    color = sampleMaterialSlot(m.slots[kSlotDiffuseTransmissionColor], uv0, uv1).rgb;
}

// Tangent (t) and glTF bitangent (b) for the unit normal n; false when no frame exists (degenerate UVs).
bool materialTangentFrame(vec3 n, vec4 tangent, vec3 worldPosition, vec2 uv, out vec3 t, out vec3 b) {
    if (tangent.w != 0.0) {  // vertex tangents: B = cross(N, T) * w (glTF 2.0, 3.7.2.1)
        t = tangent.xyz - n * dot(n, tangent.xyz);
        float len2 = dot(t, t);
        if (len2 < 1e-20) return false;
        t *= inversesqrt(len2);
        b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
        return true;
    }
    // Cotangent frame (Schuler 2013) keeping the determinant's sign for mirrored UVs: T = grad u, B = -grad v.
    vec3 dp1 = dFdx(worldPosition), dp2 = dFdy(worldPosition);
    vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
    vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
    float det = dot(dp1, dp2perp);
    t = dp2perp * duv1.x + dp1perp * duv2.x;
    b = dp2perp * duv1.y + dp1perp * duv2.y;
    float len2 = max(dot(t, t), dot(b, b));
    if (len2 < 1e-30 || det == 0.0) return false;
    float s = inversesqrt(len2) * sign(det);
    t *= s;
    b *= -s;
    return true;
}

#endif
