// scene_graph.hpp: transform propagation through the node hierarchy, shared by the loader and by
// evaluateAnimations(): node world matrices, then what hangs off them (instances, with EXT_mesh_gpu_instancing,
// cameras, lights, joint matrices of skinned nodes). Ports the transform update of IDKEngine's ModelLoader /
// animation code (its nodes are updated the same way each frame an animation plays).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace idk::scene {

// The node's local matrix: `matrix` when set, else T * R * S.
glm::mat4 localMatrix(const Node& node);

// Recomputes Node::world for every node, parents before children. Returns false when some node cannot be
// reached from a root (the hierarchy has a cycle); those nodes keep their previous world.
bool updateNodeWorlds(std::vector<Node>& nodes);

// Node worlds, then every placed instance's world (node world * its GPU-instancing matrix), every camera's and
// light's placement (scale removed), and every skinned mesh node's joint matrices:
//   jointMatrices[i] = inverse(world(node)) * world(joints[i]) * inverseBindMatrices[i]   (glTF skinning)
// with all-zero matrices when world(node) is singular or not finite (a zero-scale node draws nothing).
void updateTransforms(Scene& scene);

// The rigid part of a world matrix: unit axes (scale removed), translation kept; a zero axis becomes the
// identity's.
glm::mat4 rigidPart(const glm::mat4& m);

}  // namespace idk::scene
