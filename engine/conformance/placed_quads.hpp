// placed_quads.hpp: scenes of flat quads placed anywhere (floors, walls, boxes made of faces, transparent
// panes) for the shadow and transparency tests, built on makeQuadScene, plus a CPU ray cast against them (the
// shadow oracle's visibility test and the tests' pixel classification) and the VXGI conformance check's scene.
// Test and conformance support, no IDKEngine counterpart.
#pragma once
#include <glm/glm.hpp>

#include <optional>
#include <vector>

#include "scene/scene.hpp"

namespace idk::conformance {

struct PlacedQuad {
    glm::vec3 centre{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  // the front face's normal (unit)
    glm::vec2 halfSize{0.5f};            // along the quad's local x and y
    glm::vec3 baseColor{0.8f};           // linear
    float alpha = 1.0f;
    scene::AlphaMode alphaMode = scene::AlphaMode::Opaque;
    bool unlit = false;
    bool doubleSided = false;
    float roughness = 1.0f;
};

// A quad facing `normal` (normalized here) with half sizes `half` and a linear base colour.
inline PlacedQuad placedQuad(glm::vec3 centre, glm::vec3 normal, glm::vec2 half, glm::vec3 color,
                             bool doubleSided = false) {
    PlacedQuad q;
    q.centre = centre;
    q.normal = glm::normalize(normal);
    q.halfSize = half;
    q.baseColor = color;
    q.doubleSided = doubleSided;
    return q;
}

// Quad i = mesh, material, node and instance i; Scene::bounds covers them all.
scene::Scene makePlacedQuadScene(const std::vector<PlacedQuad>& quads);

// The five faces (no bottom) of an axis-aligned box standing on y = minY, outward normals.
std::vector<PlacedQuad> boxFaces(glm::vec3 centreOfBase, glm::vec3 halfSize, glm::vec3 baseColor);

// Nearest hit of the ray o + t d (t in (tMin, tMax)) with the quads (both sides): the quad index and t.
struct RayHit {
    uint32_t quad = 0;
    double t = 0.0;
};
std::optional<RayHit> castRay(const std::vector<PlacedQuad>& quads, const glm::dvec3& o, const glm::dvec3& d,
                              double tMin, double tMax);

// A point light of the glTF default colour at `position`.
scene::Light pointLight(glm::vec3 position, float intensity);

}  // namespace idk::conformance
