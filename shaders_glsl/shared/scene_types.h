// scene_types.h: the GPU scene as the deferred renderer reads it (engine/render/gpu_scene.cpp packs it): merged
// vertices and indices, one GpuMesh per glTF primitive, one GpuInstance per drawn (node instance, primitive)
// pair (= one indirect draw, selected by gl_DrawID), materials with bindless texture slots, punctual lights.
// Ports IDKEngine's GpuTypes (GpuMesh, GpuMeshInstance, GpuMaterial, GpuLight); see DESIGN "one definition".
#ifndef IDK_SCENE_TYPES_H
#define IDK_SCENE_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

// One vertex of the merged vertex buffer (pulled by gl_VertexIndex, no vertex input state).
struct GpuVertex {
    vec3 position;  // object space
    vec3 normal;    // object space, unit
    vec2 uv0;       // TEXCOORD_0 (0 when absent)
    vec4 tangent;   // object space xyz + handedness w (+-1); w == 0: none, the fragment shader derives one
};
IDK_GPU_SIZE(GpuVertex, 48);

// One glTF primitive: a range of the merged index buffer (indices relative to baseVertex) and its material.
struct GpuMesh {
    uint firstIndex;
    uint indexCount;
    int baseVertex;
    uint material;  // index into the material buffer (the last entry is glTF's default material)
};
IDK_GPU_SIZE(GpuMesh, 16);

IDK_CONST(uint, kInstanceMirrored, 1u);  // GpuInstance::flags: det(model) < 0, front faces wind clockwise

// One indirect draw: a primitive placed by a node. Draw i of the MDI buffer draws instance i.
struct GpuInstance {
    mat4 model;         // object -> world
    mat3 normalMatrix;  // inverse-transpose of mat3(model)
    uint mesh;          // index into the mesh buffer
    uint flags;         // kInstanceMirrored
};
IDK_GPU_SIZE(GpuInstance, 108);

// A material texture slot: a bindless texture (always valid: a placeholder until the real texture is
// streamed in), its sampler, and its KHR_texture_transform as an affine 2x3 matrix: uv' = (dot(row0, (uv, 1)),
// dot(row1, (uv, 1))).
struct GpuTextureSlot {
    uint texture;   // bindless sampled-image index
    uint samplerIndex;  // bindless sampler index
    uint texCoord;  // 0: GpuVertex::uv0, 1: the optional TEXCOORD_1 stream
    vec3 row0;
    vec3 row1;
};
IDK_GPU_SIZE(GpuTextureSlot, 36);

IDK_CONST(uint, kSlotBaseColor, 0);          // sRGB
IDK_CONST(uint, kSlotMetallicRoughness, 1);  // linear: G = roughness, B = metallic
IDK_CONST(uint, kSlotNormal, 2);             // linear: tangent-space normal, xy remapped to [-1, 1]
IDK_CONST(uint, kSlotOcclusion, 3);          // linear: R
IDK_CONST(uint, kSlotEmissive, 4);           // sRGB
// KHR_materials_specular / _clearcoat / _sheen textures; white placeholders leave the factors unchanged.
IDK_CONST(uint, kSlotSpecular, 5);            // linear: A scales specular
IDK_CONST(uint, kSlotSpecularColor, 6);       // sRGB: RGB scales specularColor
IDK_CONST(uint, kSlotClearcoat, 7);           // linear: R scales clearcoat
IDK_CONST(uint, kSlotClearcoatRoughness, 8);  // linear: G scales clearcoatRoughness
IDK_CONST(uint, kSlotSheenColor, 9);          // sRGB: RGB scales sheenColor
IDK_CONST(uint, kSlotSheenRoughness, 10);     // linear: A scales sheenRoughness
// KHR_materials_diffuse_transmission textures (white placeholders leave the factors unchanged).
IDK_CONST(uint, kSlotDiffuseTransmission, 11);       // linear: A scales diffuseTransmission
IDK_CONST(uint, kSlotDiffuseTransmissionColor, 12);  // sRGB: RGB scales diffuseTransmissionColor
// KHR_materials_iridescence, clearcoat normal and anisotropy textures (read only when the flag below says so).
IDK_CONST(uint, kSlotIridescence, 13);           // linear: R scales iridescence
IDK_CONST(uint, kSlotIridescenceThickness, 14);  // linear: G, thickness = mix(min, max, G)
IDK_CONST(uint, kSlotClearcoatNormal, 15);       // linear: the coat's tangent-space normal, xy remapped to [-1, 1]
IDK_CONST(uint, kSlotAnisotropy, 16);            // linear: RG direction remapped to [-1, 1], B scales strength
// KHR_materials_transmission / _volume textures (read only with kMaterialTransmission).
IDK_CONST(uint, kSlotTransmission, 17);  // linear: R scales transmission
IDK_CONST(uint, kSlotThickness, 18);     // linear: G scales thickness
IDK_CONST(uint, kSlotCount, 19);

IDK_CONST(uint, kAlphaOpaque, 0);
IDK_CONST(uint, kAlphaMask, 1);
IDK_CONST(uint, kAlphaBlend, 2);

IDK_CONST(uint, kMaterialDoubleSided, 1u);  // GpuMaterial::flags
IDK_CONST(uint, kMaterialUnlit, 2u);        // KHR_materials_unlit: output = base colour
// The BSDF extensions a material uses: shaders skip the lobes (and the G-buffer the material lookup) of the rest.
IDK_CONST(uint, kMaterialSpecular, 4u);     // KHR_materials_specular (factor or colour not the default)
IDK_CONST(uint, kMaterialClearcoat, 8u);    // KHR_materials_clearcoat with clearcoatFactor > 0
IDK_CONST(uint, kMaterialSheen, 16u);       // KHR_materials_sheen with a sheen colour above 0
IDK_CONST(uint, kMaterialLayers, 28u);      // any of the three
// KHR_materials_diffuse_transmission, KHR_materials_dispersion
IDK_CONST(uint, kMaterialDiffuseTransmission, 32u);  // diffuseTransmissionFactor > 0
IDK_CONST(uint, kMaterialDispersion, 64u);           // dispersion > 0
// KHR_materials_anisotropy
IDK_CONST(uint, kMaterialAnisotropy, 128u);  // KHR_materials_anisotropy with anisotropyStrength > 0
// KHR_materials_iridescence, clearcoat normal and anisotropy textures
IDK_CONST(uint, kMaterialIridescence, 256u);         // KHR_materials_iridescence with iridescenceFactor > 0
IDK_CONST(uint, kMaterialClearcoatNormal, 512u);     // clearcoat with a clearcoatNormalTexture (kSlotClearcoatNormal)
IDK_CONST(uint, kMaterialAnisotropyTexture, 1024u);  // anisotropy with an anisotropyTexture (kSlotAnisotropy)
// KHR_materials_transmission with transmissionFactor > 0 on a lit material: drawn by the screen-space transmission
// pass (frame/transmission_feature.hpp) instead of the G-buffer; _volume: thicknessFactor > 0 (refracts).
IDK_CONST(uint, kMaterialTransmission, 2048u);
IDK_CONST(uint, kMaterialVolume, 4096u);

// glTF metallic-roughness material (core + KHR_materials_emissive_strength, KHR_texture_transform, and the
// factors and textures of KHR_materials_specular, _clearcoat, _sheen).
struct GpuMaterial {
    vec4 baseColorFactor;  // linear RGBA
    vec3 emissiveFactor;   // linear, emissive strength applied
    float metallicFactor;
    float roughnessFactor;
    float normalScale;
    float occlusionStrength;
    float alphaCutoff;
    uint alphaMode;  // kAlpha*
    uint flags;      // kMaterial*
    GpuTextureSlot slots[kSlotCount];  // indexed by kSlot*
    // BSDF extension factors (read when flags has the extension's bit; defaults 1, 1, 0, 0, 0, 0).
    float specular;            // KHR_materials_specular specularFactor
    vec3 specularColor;        // specularColorFactor
    float clearcoat;           // KHR_materials_clearcoat clearcoatFactor
    float clearcoatRoughness;
    vec3 sheenColor;           // KHR_materials_sheen sheenColorFactor
    float sheenRoughness;
    // KHR_materials_anisotropy
    float anisotropyStrength;  // KHR_materials_anisotropy anisotropyStrength (read when kMaterialAnisotropy)
    float anisotropyRotation;  // radians, counter-clockwise from the tangent
    // KHR_materials_diffuse_transmission, KHR_materials_dispersion (defaults 0, 1, 0)
    float diffuseTransmission;      // diffuseTransmissionFactor (read when kMaterialDiffuseTransmission)
    vec3 diffuseTransmissionColor;  // diffuseTransmissionColorFactor, linear
    float dispersion;               // 20 / V_d (read when kMaterialDispersion)
    // KHR_materials_iridescence, clearcoat normal and anisotropy textures
    float iridescence;              // iridescenceFactor (read when kMaterialIridescence)
    float iridescenceIor;
    float iridescenceThicknessMin;  // nanometres
    float iridescenceThicknessMax;  // nanometres (the thickness without a thickness texture)
    float clearcoatNormalScale;     // read when kMaterialClearcoatNormal
    // KHR_materials_transmission, _ior, _volume (read when kMaterialTransmission; defaults 0, 1.5, 0, 0, 1)
    float transmission;             // transmissionFactor
    float ior;                      // KHR_materials_ior
    float thickness;                // thicknessFactor, object space (0: thin-walled)
    float attenuationDistance;      // 0: no absorption (glTF's infinity)
    vec3 attenuationColor;          // linear
};
IDK_GPU_SIZE(GpuMaterial, 856);

IDK_CONST(uint, kLightDirectional, 0);
IDK_CONST(uint, kLightPoint, 1);
IDK_CONST(uint, kLightSpot, 2);

// A KHR_lights_punctual light in world space.
struct GpuLight {
    vec3 position;
    uint type;        // kLight*
    vec3 direction;   // unit, where the light points
    float range;      // 0: infinite
    vec3 intensity;   // colour * intensity: candela (point, spot) or lux (directional)
    float spotScale;  // KHR_lights_punctual: 1 / max(0.001, cos(inner) - cos(outer))
    float spotOffset; // -cos(outer) * spotScale
    uint pad;
};
IDK_GPU_SIZE(GpuLight, 56);

IDK_GPU_END
#endif
