// pt_pose.hpp: the path tracer's animated geometry on the GPU. The instances that PT-A's scene left GPU-posed
// (pathtrace::PtPosing::Gpu: an object-space rest copy each, with its own BLAS) are posed by the rasterizer's
// skinning/morph compute (GpuAnimation, shaders_glsl/skinning) into the GpuScene's deformed vertex copies; the
// pt_pose pass (shaders_glsl/pathtrace/pose.comp.glsl) copies those into the path tracer's shading vertices and
// BLAS positions; each such BLAS is refit on the GPU (recordRefit; the 8-wide copy re-quantised from the refit
// nodes as refitWide does) and the caller rebuilds the TLAS over the refit boxes (rebuildPtTlas). Replaces
// IDKEngine's per-frame BLAS refit of skinned meshes for its path tracer (ModelManager.Update -> BVH.GpuBlasRefit).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk
namespace idk::scene {
struct Scene;
}  // namespace idk::scene
namespace idk::pathtrace {
struct PathTraceScene;
}  // namespace idk::pathtrace

namespace idk::render {

class GpuScene;
struct GpuSceneData;
struct PtGpuGeometry;

// One deformed primitive of a GPU-posed instance: `count` vertices of the rasterizer's deformed copy, the
// primitive's vertices in the instance's path-tracing geometry (primitives are appended in order, as
// pathtrace::buildPathTraceScene does). Primitives the rasterizer does not deform keep their uploaded rest pose.
struct PtPoseRange {
    uint32_t geometry = 0;     // PathTraceScene::geometries index (the instance's own)
    uint32_t sourceFirst = 0;  // first GpuVertex of the deformed copy in GpuScene::vertices()
    uint32_t destFirst = 0;    // first vertex of the primitive in the geometry
    uint32_t count = 0;
};

// The ranges of every pts.gpuPosedInstances entry. Throws std::invalid_argument when `data` was not packed from
// `scene` (primitive counts differ).
std::vector<PtPoseRange> ptPoseRanges(const scene::Scene& scene, const pathtrace::PathTraceScene& pts,
                                      const GpuSceneData& data);

// Runs the GpuAnimation's pending pose (skinning) and pt_pose in one render graph, then the refit of every posed
// BLAS, in one submission, and waits; updates geometry.bounds of the posed geometries (and their wide nodes).
// Call rebuildPtTlas afterwards. Nothing happens without ranges.
void posePtGeometry(vk::Context& ctx, vk::ShaderLibrary& shaders, GpuScene& gpuScene,
                    std::span<const PtPoseRange> ranges, PtGpuGeometry& geometry);

}  // namespace idk::render
