// scene_triangles.cpp: world-space triangles of a posed scene (see scene_triangles.hpp).
#include "tools/scene_triangles.hpp"

namespace idk::tools {

namespace {

// Object-space position of vertex v: morphed, then skinned (glTF: sum of weight * joint matrix; a vertex whose
// weights are all zero or reference no joint stays unskinned, as the renderer's skinning pass treats it).
glm::vec3 posedVertex(const scene::Primitive& prim, const std::vector<float>& weights,
                      const std::vector<glm::mat4>* joints, size_t v) {
    glm::vec3 p = prim.positions[v];
    for (size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
        if (!prim.targets[t].positions.empty() && weights[t] != 0.0f) p += weights[t] * prim.targets[t].positions[v];
    }
    if (joints == nullptr) return p;
    glm::mat4 skin(0.0f);
    float total = 0.0f;
    for (int j = 0; j < 4; ++j) {
        const float w = prim.weights[v][j];
        const uint32_t joint = prim.joints[v][j];
        if (w == 0.0f || joint >= joints->size()) continue;
        skin += w * (*joints)[joint];
        total += w;
    }
    return total > 0.0f ? glm::vec3(skin * glm::vec4(p, 1.0f)) : p;
}

}  // namespace

std::vector<bvh::Triangle> sceneWorldTriangles(const scene::Scene& scene, std::vector<uint32_t>* instanceOf) {
    std::vector<bvh::Triangle> out;
    std::vector<glm::vec3> world;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const scene::Instance& inst = scene.instances[i];
        if (inst.mesh >= scene.meshes.size() || inst.node >= scene.nodes.size()) continue;
        const scene::Mesh& mesh = scene.meshes[inst.mesh];
        const scene::Node& node = scene.nodes[inst.node];
        const std::vector<float>& weights = node.weights.empty() ? mesh.weights : node.weights;
        for (const scene::Primitive& prim : mesh.primitives) {
            const bool skinned = inst.skin.has_value() && !node.jointMatrices.empty() &&
                                 prim.joints.size() == prim.positions.size() &&
                                 prim.weights.size() == prim.positions.size();
            world.resize(prim.positions.size());
            for (size_t v = 0; v < prim.positions.size(); ++v) {
                const glm::vec3 local = posedVertex(prim, weights, skinned ? &node.jointMatrices : nullptr, v);
                world[v] = glm::vec3(inst.world * glm::vec4(local, 1.0f));
            }
            for (size_t k = 0; k + 2 < prim.indices.size(); k += 3) {
                const uint32_t a = prim.indices[k], b = prim.indices[k + 1], c = prim.indices[k + 2];
                if (a >= world.size() || b >= world.size() || c >= world.size()) continue;
                out.push_back({world[a], world[b], world[c]});
                if (instanceOf != nullptr) instanceOf->push_back(uint32_t(i));
            }
        }
    }
    return out;
}

}  // namespace idk::tools
