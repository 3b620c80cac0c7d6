// pt_geometry.hpp: PT-A's path-tracing scene (engine/pathtrace/pt_scene.hpp: one BLAS per geometry, a TLAS over
// the scene's instances, per-vertex shading data) uploaded for the GPU tracer: each BLAS as render::GpuBlas (our
// BVH rung), the TLAS as render::GpuTlas, the shading vertices/triangles/materials per geometry and one
// GpuPtTraceInstance per instance. Using PT-A's trees and numbering (not a second build) means both tracers see
// the same triangles, instances and light indices. Mirrors IDKEngine's BLAS-per-node + TLAS (reference 2.3).
#pragma once
#include <memory>
#include <vector>

#include "bvh/wide8.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/bvh_gpu.hpp"
#include "render/bvh_wide_gpu.hpp"
#include "shared/pt_wavefront.h"
#include "vk/resources.hpp"

namespace idk::vk {
class Context;
}  // namespace idk::vk

namespace idk::render {

struct PtGpuGeometry {
    std::vector<gpu::GpuPtTraceInstance> instances;  // per PathTraceScene instance
    std::vector<std::unique_ptr<GpuBlas>> blases;    // per non-empty geometry
    std::unique_ptr<GpuTlas> tlas;
    std::vector<std::unique_ptr<GpuWideBlas>> wideBlases;  // wide: the 8-wide copy of each BLAS (same order)
    std::unique_ptr<GpuWideTlas> wideTlas;                 // wide: the same TLAS over wideBlases
    std::vector<vk::Buffer> buffers;                 // shading data per geometry + the tables below
    vk::Buffer geometryTable;                        // GpuPtGeometry[]
    vk::Buffer instanceTable;                        // GpuPtTraceInstance[]
    uint32_t blasStackSize = 1;
    uint32_t tlasStackSize = 1;
    uint32_t wideStackSize = 1;                            // wide: the largest Bvh8::stackSize
    // What a GPU pose needs to refit BLASes and rebuild the TLAS (render/pt_pose.hpp):
    std::vector<int32_t> geometryBlas;       // per geometry: index into blases, -1 without triangles
    std::vector<bvh::Bvh8> wideTrees;        // wide: the CPU copy of each wide BLAS (a refit re-quantises it)
    std::vector<bvh::Box> bounds;            // per geometry: its BLAS's object-space box (a refit updates it)
    std::vector<bvh::BlasInstance> placed;   // per instance: transform and geometry, the TLAS's input
};

// Throws std::runtime_error for a scene without any triangle. `wide` also uploads the 8-wide BVHs (the default BVH
// rung's); the binary ones are always uploaded (they own the vertex positions both read).
PtGpuGeometry uploadPtGeometry(vk::Context& ctx, const pathtrace::PathTraceScene& pts, bool wide);
void destroyPtGeometry(vk::Context& ctx, PtGpuGeometry& geometry);

// Builds the TLAS again over `placed` and `bounds` (after a refit or moved instances) and replaces tlas/wideTlas
// (descriptor addresses change: the caller re-points its scene descriptor). The old trees are destroyed deferred.
void rebuildPtTlas(vk::Context& ctx, PtGpuGeometry& geometry);

}  // namespace idk::render
