// meshlets.hpp: meshlets of every mesh of a packed scene (meshoptimizer: vertex-cache optimisation, then
// meshopt_buildMeshlets with normal-cone weighting, bounds from meshopt_computeMeshletBounds), stored once for the
// mesh-shader rung. Built only for scenes drawn with mesh shaders (frame/culling_feature.cpp). Ports IDKEngine's
// meshlet generation in ModelLoader (disabled there at HEAD).
#pragma once
#include <vector>

#include "render/gpu_scene.hpp"
#include "shared/meshlet_types.h"

namespace idk::render {

struct MeshletData {
    std::vector<gpu::GpuMeshlet> meshlets;
    std::vector<uint32_t> vertices;   // per meshlet: indices relative to the mesh's baseVertex
    std::vector<uint32_t> triangles;  // bytes, 4 per word (little-endian), 3 per triangle
    std::vector<uint32_t> firstMeshlet, meshletCount;  // per GpuSceneData::meshes entry
};

MeshletData buildMeshlets(const GpuSceneData& scene);

}  // namespace idk::render
