// scene_graph.cpp: node world matrices (iterative depth-first, no recursion), instance/camera/light placement
// and joint matrices (glTF skinning: inverse(mesh node world) * joint world * inverse bind matrix), as the
// transform update of IDKEngine's ModelLoader and animation code does it.
#include "scene/scene_graph.hpp"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace idk::scene {

glm::mat4 localMatrix(const Node& node) {
    if (node.matrix) return *node.matrix;
    return glm::translate(glm::mat4(1.0f), node.translation) * glm::mat4_cast(node.rotation) *
           glm::scale(glm::mat4(1.0f), node.scale);
}

bool updateNodeWorlds(std::vector<Node>& nodes) {
    size_t visited = 0;
    std::vector<uint32_t> stack;
    for (uint32_t root = 0; root < nodes.size(); ++root) {
        if (nodes[root].parent) continue;
        stack.assign(1, root);
        while (!stack.empty() && visited <= nodes.size()) {
            const uint32_t n = stack.back();
            stack.pop_back();
            const Node& node = nodes[n];
            nodes[n].world = (node.parent ? nodes[*node.parent].world : glm::mat4(1.0f)) * localMatrix(node);
            ++visited;
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
        }
    }
    return visited == nodes.size();
}

glm::mat4 rigidPart(const glm::mat4& m) {
    glm::mat4 r(1.0f);
    for (int c = 0; c < 3; ++c) {
        const glm::vec3 axis(m[c]);
        const float len = glm::length(axis);
        r[c] = glm::vec4(len > 0.0f && std::isfinite(len) ? axis / len : glm::vec3(c == 0, c == 1, c == 2), 0.0f);
    }
    r[3] = m[3];
    return r;
}

namespace {

void updateJointMatrices(Scene& scene) {
    for (Node& node : scene.nodes) {
        if (!node.mesh || !node.skin || *node.skin >= scene.skins.size()) {
            node.jointMatrices.clear();
            continue;
        }
        const Skin& skin = scene.skins[*node.skin];
        node.jointMatrices.assign(skin.joints.size(), glm::mat4(0.0f));
        const float det = glm::determinant(node.world);
        if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) continue;  // zero scale: degenerate, draws nothing
        const glm::mat4 toMesh = glm::inverse(node.world);
        for (size_t i = 0; i < skin.joints.size(); ++i)
            node.jointMatrices[i] = toMesh * scene.nodes[skin.joints[i]].world * skin.inverseBindMatrices[i];
    }
}

}  // namespace

void updateTransforms(Scene& scene) {
    updateNodeWorlds(scene.nodes);
    for (Instance& instance : scene.instances) {
        const Node& node = scene.nodes[instance.node];
        instance.world = node.instanceMatrices.empty() ? node.world
                                                       : node.world * node.instanceMatrices[instance.gpuInstance];
    }
    for (Camera& camera : scene.cameras) camera.world = rigidPart(scene.nodes[camera.node].world);
    for (Light& light : scene.lights) {
        const glm::mat4 world = rigidPart(scene.nodes[light.node].world);
        light.position = glm::vec3(world[3]);
        light.direction = -glm::vec3(world[2]);
    }
    updateJointMatrices(scene);
}

}  // namespace idk::scene
