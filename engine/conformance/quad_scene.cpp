// quad_scene.cpp: builds the flat-quad scenes of the BRDF oracle test directly as scene::Scene arrays (one mesh,
// material, node and instance per quad). Test and conformance support, no IDKEngine counterpart.
#include "conformance/quad_scene.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace idk::conformance {

scene::Scene makeQuadScene(const std::vector<QuadSpec>& quads) {
    scene::Scene s;
    s.sourcePath = "generated:quads";
    for (size_t i = 0; i < quads.size(); ++i) {
        const QuadSpec& q = quads[i];
        scene::Material m;
        m.name = "quad " + std::to_string(i);
        m.baseColorFactor = glm::vec4(q.baseColor, 1.0f);
        m.metallic = q.metallic;
        m.roughness = q.roughness;
        m.emissive = q.emissive;
        m.doubleSided = q.doubleSided;
        s.materials.push_back(m);

        scene::Primitive p;
        float h = q.halfSize;
        p.positions = {{-h, -h, 0.0f}, {h, -h, 0.0f}, {h, h, 0.0f}, {-h, h, 0.0f}};
        p.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
        p.uv0 = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
        p.indices = {0, 1, 2, 0, 2, 3};
        p.material = uint32_t(i);
        scene::Mesh mesh;
        mesh.name = m.name;
        mesh.primitives.push_back(std::move(p));
        s.meshes.push_back(std::move(mesh));

        scene::Node node;
        node.name = m.name;
        node.translation = glm::vec3(q.centre, 0.0f);
        node.mesh = uint32_t(i);
        node.world = glm::translate(glm::mat4(1.0f), node.translation) * glm::mat4(q.basis);
        node.matrix = node.world;
        s.rootNodes.push_back(uint32_t(s.nodes.size()));
        s.nodes.push_back(node);
        s.instances.push_back({uint32_t(i), uint32_t(i), node.world});
        for (const glm::vec3& v : s.meshes.back().primitives[0].positions)
            s.bounds.extend(glm::vec3(node.world * glm::vec4(v, 1.0f)));
    }
    return s;
}

}  // namespace idk::conformance
