// scene_reads.cpp: the reads every draw over the scene's meshes declares (passes.hpp readSceneMeshes), in one
// place so that a new vertex stream is declared by every such pass at once.
#include "passes/passes.hpp"

namespace idk::passes {

void readSceneMeshes(graph::PassBuilder& b, const SceneBuffers& s, VkPipelineStageFlags2 geometryStages) {
    const VkPipelineStageFlags2 kVs = geometryStages;
    constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    b.read(s.vertices, graph::Access::StorageRead, kVs);
    b.read(s.indices, graph::Access::VertexRead);
    b.read(s.instances, graph::Access::StorageRead, kVs | kFs);
    b.read(s.meshes, graph::Access::StorageRead, kFs);
    b.read(s.materials, graph::Access::StorageRead, kFs);
    if (s.colors.valid()) b.read(s.colors, graph::Access::StorageRead, kVs);
    if (s.uv1.valid()) b.read(s.uv1, graph::Access::StorageRead, kVs);
}

}  // namespace idk::passes
