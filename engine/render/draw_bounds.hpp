// draw_bounds.hpp: bounding boxes of the GPU scene's draws on the CPU, for what the renderer decides per frame
// without the GPU: the far plane of point-shadow cubes and the back-to-front order of BLEND draws. Object-space
// boxes per mesh are computed once; world boxes follow the instances' current transforms.
// Plays the role of IDKEngine's per-mesh bounding boxes (BBoxes in ModelManager).
#pragma once
#include <vector>

#include "render/gpu_scene.hpp"
#include "scene/scene.hpp"

namespace idk::render {

// Per GpuSceneData::meshes entry: the box of the vertices its indices reference (empty for an empty mesh).
std::vector<scene::Aabb> meshBounds(const GpuSceneData& scene);

// World box of a mesh box placed by an instance (the eight transformed corners).
scene::Aabb worldBounds(const scene::Aabb& objectBox, const glm::mat4& model);

// Union of every draw's world box.
scene::Aabb sceneBounds(const GpuSceneData& scene, const std::vector<scene::Aabb>& meshBoxes);

}  // namespace idk::render
