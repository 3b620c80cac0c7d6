// culling_math.hpp: the CPU side of GPU culling: frustum planes of a view-projection matrix, the per-draw culling
// records of a packed scene (object boxes, index ranges, which draws are skipped or never culled), and the CPU
// oracle of the culling kernel (the same box test, shared/culling_types.h) that tests compare the GPU against.
#pragma once
#include <vector>

#include "render/gpu_scene.hpp"
#include "shared/culling_types.h"

namespace idk::render {

// World-space planes (inside: dot(n, p) + w >= 0) of the clip volume -w <= x, y <= w, 0 <= z <= w, and the
// matrix and viewport (pixels) the Hi-Z test projects with.
gpu::GpuCullView frustumView(const glm::mat4& viewProjection, glm::uvec2 viewport = glm::uvec2(1));

// One GpuCullDraw per scene draw: BLEND draws (instanceCount 0) are skipped; draws of deformed vertex copies
// (skinned or morphed: their vertexOffset is not the mesh's baseVertex) are never culled, since their rest-pose
// box does not bound the animated vertices.
// `meshlets` (optional, render/meshlets.hpp) fills the meshlet ranges of the mesh rung.
struct MeshletData;
std::vector<gpu::GpuCullDraw> packCullDraws(const GpuSceneData& scene, const MeshletData* meshlets = nullptr);

// The oracle: per draw, whether the culling kernel draws it in `view` (false for skipped draws) in `phase`
// (gpu::kCull*). Early and late phases read `visibility` (one uint per draw), the late phase rewrites it and tests
// against `pyramid` (render/depth_pyramid.hpp).
std::vector<bool> cullOracle(const std::vector<gpu::GpuCullDraw>& draws, const std::vector<gpu::GpuInstance>& instances,
                             const gpu::GpuCullView& view, uint32_t phase = gpu::kCullFrustum,
                             std::vector<uint32_t>* visibility = nullptr, const std::vector<float>* pyramid = nullptr);

}  // namespace idk::render
