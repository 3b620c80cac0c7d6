// flatten.hpp: CPU trees -> the GPU arrays of shaders_glsl/shared/bvh_types.h (root at 0, padding at 1, pairs at
// even indices, the root never a leaf). Every CPU index i > 0 becomes i + 1.
#pragma once

#include "bvh/blas.hpp"
#include "bvh/tlas.hpp"
#include "shared/bvh_types.h"

#include <span>
#include <vector>

namespace idk::bvh {

std::vector<gpu::GpuBlasNode> flatten(const Blas& blas);

// The leaf-ordered triangle references of `blas`; `indices[t]` are the vertex indices of triangle t.
std::vector<gpu::GpuBlasTriangle> flattenTriangles(const Blas& blas, std::span<const glm::uvec3> indices);

std::vector<gpu::GpuTlasNode> flatten(const Tlas& tlas);

}  // namespace idk::bvh
