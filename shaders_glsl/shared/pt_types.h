// pt_types.h: the path tracer's data shared by the CPU reference (engine/pathtrace) and the GPU wavefront tracer
// (shaders_glsl/pathtrace): lights for next-event estimation (punctual lights and emissive triangles), alias-table
// entries (light selection by power, environment texel selection), the environment description, the tracers'
// transmission, IOR and volume material fields (with texture indices into Scene::textures), and the macros that let
// pt_sampling.h be one source for C++ and GLSL. IDKEngine's path tracer (PathTracing/include/Shading.glsl) has
// no light list at all (reference 2.1); this is new.
//
// Conventions both tracers follow (see pt_sampling.h for the maths):
// * A TLAS instance is one scene::Instance (one BLAS per scene mesh over render::meshTriangles(scene, mesh), all
//   primitives in order); a triangle id is the index in that merged triangle list.
// * Emissive triangles: every triangle of an instance whose mesh has at least one emissive primitive gets a light
//   entry, lightIndex = GpuPtInstance::firstLight + triangleId (non-emissive ones get power 0, never selected).
//   Instances without emission have firstLight = kPtNoLight.
// * Every surface is hit from both sides (no back-face culling); single-sided emitters emit from their front
//   face only (the side the counter-clockwise winding's normal points to; mirrored instances flip it).
// * Alpha MASK: a hit with alpha < cutoff is passed through (the ray continues from the hit, no bounce counted);
//   BLEND: passed through with probability 1 - alpha (stochastic transparency, one random number).
// * Russian roulette from bounce rouletteDepth on: survival probability ptSurvivalProbability(throughput).
#ifndef IDK_PT_TYPES_H
#define IDK_PT_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kPtNoLight, 0xFFFFFFFFu);
IDK_CONST(uint, kPtNoTexture, 0xFFFFFFFFu);

IDK_CONST(uint, kPtLightPoint, 0);
IDK_CONST(uint, kPtLightSpot, 1);
IDK_CONST(uint, kPtLightDirectional, 2);
IDK_CONST(uint, kPtLightTriangle, 3);

IDK_CONST(uint, kPtLightDoubleSided, 1u);  // GpuPtLight::flags: a triangle that emits from both faces
IDK_CONST(uint, kPtLightTextured, 2u);     // the emission is emissiveFactor * emissive texture at the sample point
IDK_CONST(uint, kPtLightFlipped, 4u);      // front normal = -cross(edge1, edge2) (a mirrored instance)

// One light of the NEE list, world space.
struct GpuPtLight {
    vec3 position;   // point/spot: position; triangle: vertex 0
    uint type;       // kPtLight*
    vec3 direction;  // spot/directional: unit direction the light points to; triangle: edge v1 - v0
    float range;     // punctual: KHR_lights_punctual range, 0 = infinite
    vec3 intensity;  // point/spot: colour * intensity (cd); directional: lux; triangle: emissive factor (radiance)
    float spotScale; // spot: 1 / max(0.001, cos(inner) - cos(outer))
    vec3 edge2;      // triangle: edge v2 - v0 (front normal: normalize(cross(edge1, edge2)), negated if kPtLightFlipped)
    float spotOffset;  // spot: -cos(outer) * spotScale
    uint instance;   // triangle: TLAS instance (scene::Instance index)
    uint triangle;   // triangle: triangle id in the instance's mesh
    uint material;   // triangle: material index (GpuSceneData::materials numbering)
    uint flags;      // kPtLightDoubleSided | kPtLightTextured
};
IDK_GPU_SIZE(GpuPtLight, 80);

// Alias table entry (Walker/Vose): pick slot i uniformly, keep it when the second uniform is < threshold, else
// take `alias`. `probability` is the entry's own selection probability (for pdfs and MIS).
struct GpuPtAliasEntry {
    float threshold;
    uint alias;
    float probability;
};
IDK_GPU_SIZE(GpuPtAliasEntry, 12);

// Per TLAS instance: where its triangles' light entries start.
struct GpuPtInstance {
    uint firstLight;  // kPtNoLight: the instance emits nothing
};
IDK_GPU_SIZE(GpuPtInstance, 4);

// The environment: an equirectangular radiance map (raster mapping, include/environment.glsl) of width x height
// RGB texels (already multiplied by the intensity), read piecewise-constant (nearest texel) so that radiance and
// sampling pdf agree exactly, and its alias table over texels with probability ~ luminance * sin(theta) * area.
// A scene without an HDR gets a constant map of a few texels.
struct GpuPtEnvironment {
    uint width;
    uint height;
    float selectProbability;  // probability that NEE samples the environment instead of the light list
    uint lightCount;          // entries of the light list (and of its alias table)
};
IDK_GPU_SIZE(GpuPtEnvironment, 16);

// The path-tracing fields of a material that the raster's GpuMaterial (scene_types.h) does not carry; one entry
// per GpuSceneData::materials entry (Scene::materials, then glTF's default material).
struct GpuPtMaterial {
    float transmission;         // KHR_materials_transmission factor
    float ior;                  // KHR_materials_ior
    float thickness;            // KHR_materials_volume thickness factor; 0 = thin-walled (no refraction)
    float attenuationDistance;  // 0 = no absorption (glTF's infinity)
    vec3 attenuationColor;
    uint transmissionTexture;   // Scene::textures index (R channel), kPtNoTexture when none
    uint transmissionTexCoord;  // 0 or 1
    vec3 transmissionRow0;      // KHR_texture_transform as in GpuTextureSlot
    vec3 transmissionRow1;
    float specular;             // the material-extension factors of PtSurface (same meaning and defaults)
    vec3 specularColor;
    float clearcoat;
    float clearcoatRoughness;
    vec3 sheenColor;
    float sheenRoughness;
    // KHR_materials_anisotropy
    float anisotropyStrength;   // anisotropyStrength, [0, 1]
    float anisotropyRotation;   // anisotropyRotation, radians counter-clockwise from the tangent
};
IDK_GPU_SIZE(GpuPtMaterial, 108);

// A surface at a hit, material already evaluated from its textures (both tracers fill it the same way).
struct PtSurface {
    vec3 baseColor;        // linear, vertex colour and texture applied
    float alpha;
    float metallic;
    float roughness;       // perceptual; alpha = roughness^2
    float transmission;
    float ior;
    vec3 emission;         // radiance emitted toward the viewer (0 on the back of a single-sided emitter)
    float thickness;       // > 0: a closed volume that refracts; 0: thin-walled
    vec3 attenuationColor;
    float attenuationDistance;  // 0: no absorption
    vec3 shadingNormal;    // unit, normal-mapped, on the geometric normal's side
    vec3 geometricNormal;  // unit, front-face side (the outside of a closed volume)
    // Material extensions (pt_bsdf_frame.h); the defaults (1, 1, 0, 0, 0, 0) leave the core glTF BSDF.
    float specular;            // KHR_materials_specular specularFactor
    vec3 specularColor;        // KHR_materials_specular specularColorFactor (linear)
    float clearcoat;           // KHR_materials_clearcoat clearcoatFactor
    float clearcoatRoughness;  // perceptual
    vec3 sheenColor;           // KHR_materials_sheen sheenColorFactor (linear; 0: no sheen)
    float sheenRoughness;      // perceptual
    // KHR_materials_anisotropy
    vec3 anisotropyDirection;  // world, unit tangent-plane direction of alpha_t (pt_anisotropy.h); 0: the BSDF's basis
    float anisotropyStrength;  // [0, 1], texture applied; 0: isotropic GGX
    // KHR_materials_diffuse_transmission, KHR_materials_dispersion (defaults 0, 1, 0: the core BSDF)
    float diffuseTransmission;      // [0, 1], texture applied: the share of the diffuse lobe that transmits
    vec3 diffuseTransmissionColor;  // linear, texture applied: the tint of the transmitted diffuse light
    float dispersion;               // 20 / V_d (pt_dispersion.h); 0: the IOR is the same for every wavelength
    // KHR_materials_iridescence, clearcoat normal and anisotropy textures
    float iridescence;           // iridescenceFactor, texture applied; 0: no thin film (pt_iridescence.h)
    float iridescenceIor;        // the film's IOR
    float iridescenceThickness;  // nanometres, texture applied; 0: no thin film
    vec3 clearcoatNormal;        // world, unit, the coat's own normal map applied; 0: the shading normal
};
IDK_GPU_SIZE(PtSurface, 188);  // also a buffer element (conformance probe)

// Outcome of sampling the BSDF.
IDK_CONST(uint, kPtLobeNone, 0);          // no valid direction (absorbed)
IDK_CONST(uint, kPtLobeDiffuse, 1);
IDK_CONST(uint, kPtLobeSpecular, 2);      // GGX reflection (metal or dielectric coat)
IDK_CONST(uint, kPtLobeTransmission, 3);  // refraction (thick) or straight-through (thin-walled)
IDK_CONST(uint, kPtLobeMultiScatter, 4);  // GGX energy compensation (pt_energy.h), a reflection
IDK_CONST(uint, kPtLobeSheen, 5);         // KHR_materials_sheen, a reflection
IDK_CONST(uint, kPtLobeClearcoat, 6);     // KHR_materials_clearcoat, a reflection
IDK_CONST(uint, kPtLobeDiffuseTransmission, 7);  // KHR_materials_diffuse_transmission, Lambert through the surface
IDK_CONST(uint, kPtLobeDeltaFlag, 16u);   // OR-ed into the lobe when the sampled lobe is a delta (smooth) lobe

IDK_GPU_END

#endif
