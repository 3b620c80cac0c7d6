// pt_test_scenes.cpp: procedural test scenes and image metrics for tests/unit/pathtrace.
#include "pt_test_scenes.hpp"

#include <cmath>

namespace idk::test {

scene::Primitive uvSphere(const glm::vec3& centre, float radius, uint32_t rings, uint32_t segments) {
    scene::Primitive p;
    const float pi = 3.14159265358979f;
    for (uint32_t r = 0; r <= rings; ++r) {
        const float theta = pi * float(r) / float(rings);
        for (uint32_t s = 0; s <= segments; ++s) {
            const float phi = 2.0f * pi * float(s) / float(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            p.positions.push_back(centre + radius * n);
            p.normals.push_back(n);
        }
    }
    const uint32_t row = segments + 1;
    for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * row + s, b = a + row, c = b + 1, d = a + 1;
            // Outward (counter-clockwise seen from outside).
            p.indices.insert(p.indices.end(), {a, d, b, d, c, b});
        }
    return p;
}

scene::Primitive quad(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3) {
    scene::Primitive p;
    p.positions = {p0, p1, p2, p3};
    const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    p.normals.assign(4, n);
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

scene::Primitive box(const glm::vec3& lo, const glm::vec3& hi) {
    scene::Primitive out;
    auto face = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        const scene::Primitive q = quad(a, b, c, d);
        const auto base = uint32_t(out.positions.size());
        out.positions.insert(out.positions.end(), q.positions.begin(), q.positions.end());
        out.normals.insert(out.normals.end(), q.normals.begin(), q.normals.end());
        for (uint32_t i : q.indices) out.indices.push_back(base + i);
    };
    const glm::vec3 l = lo, h = hi;
    face({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z});  // +z
    face({h.x, l.y, l.z}, {l.x, l.y, l.z}, {l.x, h.y, l.z}, {h.x, h.y, l.z});  // -z
    face({h.x, l.y, h.z}, {h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z});  // +x
    face({l.x, l.y, l.z}, {l.x, l.y, h.z}, {l.x, h.y, h.z}, {l.x, h.y, l.z});  // -x
    face({l.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, l.z}, {l.x, h.y, l.z});  // +y
    face({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z});  // -y
    return out;
}

uint32_t addObject(scene::Scene& s, scene::Primitive prim, const scene::Material& material, const glm::mat4& world) {
    s.materials.push_back(material);
    prim.material = uint32_t(s.materials.size() - 1);
    scene::Mesh mesh;
    mesh.primitives.push_back(std::move(prim));
    s.meshes.push_back(std::move(mesh));
    scene::Node node;
    node.mesh = uint32_t(s.meshes.size() - 1);
    node.world = world;
    s.nodes.push_back(node);
    s.rootNodes.push_back(uint32_t(s.nodes.size() - 1));
    scene::Instance inst;
    inst.mesh = uint32_t(s.meshes.size() - 1);
    inst.node = uint32_t(s.nodes.size() - 1);
    inst.world = world;
    s.instances.push_back(inst);
    return uint32_t(s.instances.size() - 1);
}

scene::Material diffuse(const glm::vec3& color) {
    scene::Material m;
    m.baseColorFactor = glm::vec4(color, 1.0f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    return m;
}

scene::CameraView lookAt(const glm::vec3& eye, const glm::vec3& target, float yfov) {
    scene::CameraView c;
    c.position = eye;
    c.forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(c.forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    c.up = glm::cross(right, c.forward);
    c.yfov = yfov;
    c.znear = 0.01f;
    c.zfar = 0.0f;
    return c;
}

glm::dvec3 imageMean(const core::ImageRgba32f& image) {
    glm::dvec3 sum(0.0);
    const size_t n = size_t(image.width) * image.height;
    for (size_t i = 0; i < n; ++i)
        sum += glm::dvec3(image.pixels[4 * i], image.pixels[4 * i + 1], image.pixels[4 * i + 2]);
    return n ? sum / double(n) : sum;
}

double imageRmse(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    double sum = 0.0;
    const size_t n = size_t(a.width) * a.height;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.pixels[4 * i + c]) - double(b.pixels[4 * i + c]);
            sum += d * d;
        }
    return n ? std::sqrt(sum / double(3 * n)) : 0.0;
}

bool imageFinite(const core::ImageRgba32f& image) {
    for (float v : image.pixels)
        if (!std::isfinite(v)) return false;
    return true;
}

}  // namespace idk::test
