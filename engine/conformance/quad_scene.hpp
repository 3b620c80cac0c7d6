// quad_scene.hpp: a scene built in code for the BRDF oracle test (and placed_quads.hpp): axis-aligned unit-normal quads in the plane
// z = 0 facing +Z (the camera), one mesh and material per quad, plus whatever lights the test adds.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "scene/scene.hpp"

namespace idk::conformance {

struct QuadSpec {
    glm::vec2 centre{0.0f};
    float halfSize = 0.25f;
    glm::vec3 baseColor{1.0f};  // linear
    float metallic = 0.0f;
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};
    glm::mat3 basis{1.0f};  // applied before the translation (e.g. a mirror or a 180-degree turn)
    bool doubleSided = false;
};

// Each quad becomes mesh i (two triangles, CCW seen from +Z) with material i, placed by node/instance i.
scene::Scene makeQuadScene(const std::vector<QuadSpec>& quads);

}  // namespace idk::conformance
