// scene_triangles.hpp: every placed instance of a scene as world-space triangles for CPU queries (collision,
// picking) in idk_tools, which may not depend on idk_render (render::worldTriangles does the same for the BVH
// command and GPU tests). Morph targets at the node's current weights, skinned instances by their current joint
// matrices, EXT_mesh_gpu_instancing copies by Instance::world.
#pragma once

#include <cstdint>
#include <vector>

#include "bvh/geometry.hpp"
#include "scene/scene.hpp"

namespace idk::tools {

// One triangle per index triple of every primitive of every instance; `instanceOf` (when given) receives the
// Scene::instances index of each triangle.
std::vector<bvh::Triangle> sceneWorldTriangles(const scene::Scene& scene, std::vector<uint32_t>* instanceOf = nullptr);

}  // namespace idk::tools
