// vxgi_passes.hpp: the passes of voxel global illumination (engine/frame/vxgi_feature.hpp drives them).
#pragma once
#include <glm/glm.hpp>

#include "passes/passes.hpp"
#include "vk/features.hpp"

namespace idk::passes {

// The grid's cube in world space: gridMin + [0, size * voxelSize]^3.
struct VoxelGridBox {
    glm::vec3 gridMin{0.0f};
    float voxelSize = 1.0f;
    uint32_t size = 64;
};

// vxgi_voxelize.cpp: "vxgi_clear" zeroes the write-conflict accumulators (transient 3D images of the atomic rung's
// formats), "vxgi_voxelize" rasterizes the scene three times (one orthographic projection per axis; each triangle
// keeps the fragments of its dominant axis) and adds every fragment's outgoing diffuse radiance to its voxel,
// "vxgi_merge" resolves them into `grid` (RGBA16F, size^3, mip 0). Returns the grid's new version.
struct VoxelizeInputs {
    SceneBuffers scene;
    graph::BufferHandle frame;
    PointShadowOutputs shadows;
    VoxelGridBox box;
    vk::Rung atomics = vk::Rung::Native;  // ladder "vxgi-atomics": Native float add, Fallback r32ui max
};
graph::TextureHandle addVoxelizePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const VoxelizeInputs& inputs, graph::TextureHandle grid, IndirectDrawLog* log);

}  // namespace idk::passes
