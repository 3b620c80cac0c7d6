// pt_geometry.hpp: PT-A's path-tracing scene (engine/pathtrace/pt_scene.hpp: one BLAS per geometry, a TLAS over
// the scene's instances, per-vertex shading data) uploaded for the GPU tracer: each BLAS as render::GpuBlas (our
// BVH rung), the TLAS as render::GpuTlas, the shading vertices/triangles/materials per geometry and one
// GpuPtTraceInstance per instance. Using PT-A's trees and numbering (not a second build) means both tracers see
// the same triangles, instances and light indices. Mirrors IDKEngine's BLAS-per-node + TLAS (reference 2.3).
#pragma once
#include <memory>
#include <vector>

#include "pathtrace/pt_scene.hpp"
#include "render/bvh_gpu.hpp"
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
    std::vector<vk::Buffer> buffers;                 // shading data per geometry + the tables below
    vk::Buffer geometryTable;                        // GpuPtGeometry[]
    vk::Buffer instanceTable;                        // GpuPtTraceInstance[]
    uint32_t blasStackSize = 1;
    uint32_t tlasStackSize = 1;
};

// Throws std::runtime_error for a scene without any triangle.
PtGpuGeometry uploadPtGeometry(vk::Context& ctx, const pathtrace::PathTraceScene& pts);
void destroyPtGeometry(vk::Context& ctx, PtGpuGeometry& geometry);

}  // namespace idk::render
