// pt_surface.hpp: a plain PtSurface for the path tracer's BSDF tests: the core glTF material facing +z (shading and
// geometric normal), opaque, without volume, with every extension at its neutral default (specular 1 and white,
// no coat, sheen, anisotropy, transmission, film or dispersion; a white diffuse-transmission colour), so a test
// sets only the fields it studies.
#pragma once
#include "shared/pt_types.h"

namespace idk::test {

inline gpu::PtSurface plainPtSurface(glm::vec3 baseColor, float metallic, float roughness, float ior = 1.5f) {
    gpu::PtSurface s{};
    s.baseColor = baseColor;
    s.alpha = 1.0f;
    s.metallic = metallic;
    s.roughness = roughness;
    s.ior = ior;
    s.attenuationColor = glm::vec3(1.0f);
    s.shadingNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    s.geometricNormal = glm::vec3(0.0f, 0.0f, 1.0f);
    s.specular = 1.0f;
    s.specularColor = glm::vec3(1.0f);
    s.diffuseTransmissionColor = glm::vec3(1.0f);
    return s;
}

}  // namespace idk::test
