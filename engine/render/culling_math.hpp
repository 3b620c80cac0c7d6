// culling_math.hpp: the CPU side of GPU culling: frustum planes of a view-projection matrix, the per-draw culling
// records of a packed scene (object boxes, index ranges, which draws are skipped or never culled), and the CPU
// oracle of the culling kernel (the same box test, shared/culling_types.h) that tests compare the GPU against.
#pragma once
#include <vector>

#include "render/gpu_scene.hpp"
#include "shared/culling_types.h"
#include "shared/meshlet_types.h"

namespace idk::render {

// World-space planes (inside: dot(n, p) + w >= 0) of the clip volume -w <= x, y <= w, 0 <= z <= w, and the
// matrix and viewport (pixels) the Hi-Z test projects with.
gpu::GpuCullView frustumView(const glm::mat4& viewProjection, glm::uvec2 viewport = glm::uvec2(1));

// One GpuCullDraw per scene draw: BLEND draws (instanceCount 0) are skipped; draws of deformed vertex copies
// (skinned or morphed: their vertexOffset is not the mesh's baseVertex) are never culled, since their rest-pose
// box does not bound the animated vertices.
// `meshlets` (optional, render/meshlets.hpp) fills the meshlet ranges of the mesh rung and each draw's first
// meshlet visibility word (ceil(meshletCount / 32) words per draw, one per task workgroup).
struct MeshletData;
// `blendCasts` (the point-shadow faces): BLEND draws are culled and drawn like the others (they cast by coverage).
std::vector<gpu::GpuCullDraw> packCullDraws(const GpuSceneData& scene, const MeshletData* meshlets = nullptr,
                                            bool blendCasts = false);
// The words of the mesh rung's meshlet visibility bits that `draws` (packed with meshlets) address.
uint32_t meshletVisibilityWords(const std::vector<gpu::GpuCullDraw>& draws);

// The oracle: per draw, whether the culling kernel draws it in `view` (false for skipped draws) in `phase`
// (gpu::kCull*). Early and late phases read `visibility` (one uint per draw), the late phase rewrites it and tests
// against `pyramid` (render/depth_pyramid.hpp).
// `meshTasks` (the mesh rung): the late phase also relaunches the visible draws the early phase drew (their
// meshlets not drawn early are tested again); a relaunched draw is one drawn whose visibility was 1 before.
std::vector<bool> cullOracle(const std::vector<gpu::GpuCullDraw>& draws, const std::vector<gpu::GpuInstance>& instances,
                             const gpu::GpuCullView& view, uint32_t phase = gpu::kCullFrustum,
                             std::vector<uint32_t>* visibility = nullptr, const std::vector<float>* pyramid = nullptr,
                             bool meshTasks = false);

// The oracle of the mesh rung's task shader (gbuffer/gbuffer_mesh.task.glsl) for the draws one phase launched
// (`launched`: per draw, launched by the culling pass; `drawnEarly`: the late phase's relaunch flag, per draw):
// each launched draw's meshlets through meshletInView (shared/meshlet_culling.h) from `eye` and, in the late
// phase, the Hi-Z test of its vertex box (meshletBox) against `pyramid`. The early phase tests only the meshlets
// whose bit in `meshletBits` is set; the late phase rewrites the words of the launched draws and does not draw
// again what the early phase drew. The counters it adds up are the task shader's (GpuCullCounters).
struct MeshletCounts {
    uint32_t tested = 0, drawn = 0, triangles = 0;
};
MeshletCounts meshletOracle(const std::vector<gpu::GpuCullDraw>& draws, const std::vector<gpu::GpuInstance>& instances,
                            const std::vector<gpu::GpuMeshlet>& meshlets, const gpu::GpuCullView& view, glm::vec3 eye,
                            uint32_t phase, const std::vector<bool>& launched, const std::vector<bool>& drawnEarly,
                            std::vector<uint32_t>& meshletBits, const std::vector<float>* pyramid = nullptr);

}  // namespace idk::render
