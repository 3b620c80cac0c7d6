// pbr_oracle.hpp: C++ twins (double precision) of what the deferred renderer's shaders compute, for GPU tests:
// the glTF metallic-roughness BRDF and KHR_lights_punctual attenuation of include/pbr.glsl, the AgX tonemap of
// tonemap/tonemap.comp.glsl, and the G-buffer's storage quantization (sRGB8 albedo, UNORM8 metallic/roughness).
#pragma once
#include <glm/glm.hpp>

#include "shared/scene_types.h"

namespace idk::test {

// f(l, v) * max(N.l, 0) for unit n, v, l (material_layers.glsl layeredBrdfCosine without extensions: pbr.glsl
// brdfCosine with the albedo-scaled diffuse weight of dielectricDiffuseWeight).
glm::dvec3 brdfCosine(const glm::dvec3& baseColor, double metallic, double perceptualRoughness, const glm::dvec3& n,
                      const glm::dvec3& v, const glm::dvec3& l);

// Direction to the light (out) and intensity * attenuation at p (pbr.glsl lightIncidence).
glm::dvec3 lightIncidence(const gpu::GpuLight& light, const glm::dvec3& p, glm::dvec3& l);

// AgX of linear radiance to display-linear values in [0, 1] (tonemap.comp.glsl agx), and the sRGB OETF.
glm::dvec3 agx(const glm::dvec3& linear);
double srgbEncode(double linear);

// Values as the G-buffer stores them: sRGB 8-bit for colour, UNORM 8-bit for metallic/roughness/occlusion.
double quantizeSrgb8(double linear);
double quantizeUnorm8(double value);

}  // namespace idk::test
