// placed_quads.cpp: quads with arbitrary placement (an orthonormal frame from the normal), box faces, and the
// double-precision ray/quad intersection the GPU shadow and transparency tests use as their oracle.
// Conformance and test support (the VXGI check's scene), no IDKEngine counterpart.
#include "conformance/placed_quads.hpp"

#include <cmath>

#include "conformance/quad_scene.hpp"

namespace idk::conformance {
namespace {

// Local x and y axes of a quad: a right-handed frame (x, y, normal).
void quadAxes(glm::dvec3 n, glm::dvec3& x, glm::dvec3& y) {
    glm::dvec3 helper = std::abs(n.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, -1.0);
    x = glm::normalize(glm::cross(helper, n));
    y = glm::cross(n, x);
}

}  // namespace

scene::Scene makePlacedQuadScene(const std::vector<PlacedQuad>& quads) {
    std::vector<QuadSpec> specs(quads.size());
    for (size_t i = 0; i < quads.size(); ++i) {
        specs[i].halfSize = 1.0f;  // scaled per axis below
        specs[i].baseColor = quads[i].baseColor;
        specs[i].roughness = quads[i].roughness;
        specs[i].doubleSided = quads[i].doubleSided;
    }
    scene::Scene s = makeQuadScene(specs);
    s.bounds = {};
    for (size_t i = 0; i < quads.size(); ++i) {
        const PlacedQuad& q = quads[i];
        glm::dvec3 x, y;
        quadAxes(glm::normalize(glm::dvec3(q.normal)), x, y);
        glm::mat4 world(1.0f);
        world[0] = glm::vec4(glm::vec3(x) * q.halfSize.x, 0.0f);
        world[1] = glm::vec4(glm::vec3(y) * q.halfSize.y, 0.0f);
        world[2] = glm::vec4(glm::normalize(q.normal), 0.0f);
        world[3] = glm::vec4(q.centre, 1.0f);
        s.nodes[i].world = world;
        s.nodes[i].matrix = world;
        s.instances[i].world = world;
        scene::Material& m = s.materials[i];
        m.baseColorFactor.a = q.alpha;
        m.alphaMode = q.alphaMode;
        m.unlit = q.unlit;
        for (const glm::vec3& v : s.meshes[i].primitives[0].positions)
            s.bounds.extend(glm::vec3(world * glm::vec4(v, 1.0f)));
    }
    return s;
}

std::vector<PlacedQuad> boxFaces(glm::vec3 c, glm::vec3 h, glm::vec3 color) {
    std::vector<PlacedQuad> f(5);
    f[0].centre = c + glm::vec3(0.0f, 2.0f * h.y, 0.0f);  // top
    f[0].normal = {0.0f, 1.0f, 0.0f};
    f[0].halfSize = {h.x, h.z};
    f[1].centre = c + glm::vec3(h.x, h.y, 0.0f);
    f[1].normal = {1.0f, 0.0f, 0.0f};
    f[1].halfSize = {h.z, h.y};
    f[2].centre = c + glm::vec3(-h.x, h.y, 0.0f);
    f[2].normal = {-1.0f, 0.0f, 0.0f};
    f[2].halfSize = {h.z, h.y};
    f[3].centre = c + glm::vec3(0.0f, h.y, h.z);
    f[3].normal = {0.0f, 0.0f, 1.0f};
    f[3].halfSize = {h.x, h.y};
    f[4].centre = c + glm::vec3(0.0f, h.y, -h.z);
    f[4].normal = {0.0f, 0.0f, -1.0f};
    f[4].halfSize = {h.x, h.y};
    for (PlacedQuad& q : f) q.baseColor = color;
    return f;
}

std::optional<RayHit> castRay(const std::vector<PlacedQuad>& quads, const glm::dvec3& o, const glm::dvec3& d,
                              double tMin, double tMax) {
    std::optional<RayHit> best;
    for (uint32_t i = 0; i < quads.size(); ++i) {
        const PlacedQuad& q = quads[i];
        glm::dvec3 n = glm::normalize(glm::dvec3(q.normal)), x, y;
        quadAxes(n, x, y);
        double denom = glm::dot(n, d);
        if (std::abs(denom) < 1e-12) continue;
        double t = glm::dot(glm::dvec3(q.centre) - o, n) / denom;
        if (t <= tMin || t >= tMax || (best && t >= best->t)) continue;
        glm::dvec3 p = o + t * d - glm::dvec3(q.centre);
        if (std::abs(glm::dot(p, x)) <= q.halfSize.x && std::abs(glm::dot(p, y)) <= q.halfSize.y) best = RayHit{i, t};
    }
    return best;
}

scene::Light pointLight(glm::vec3 position, float intensity) {
    scene::Light l;
    l.name = "test point light";
    l.type = scene::LightType::Point;
    l.intensity = intensity;
    l.position = position;
    return l;
}

}  // namespace idk::conformance
