// refit.hpp: CPU refit of a BLAS after its vertices moved with the same topology (skinning): the BLAS's triangle
// copy is updated, leaf boxes are recomputed from their triangles, inner boxes from their children, bottom-up.
// The oracle of the GPU refit pass (IDKEngine BLASRefit/compute.glsl). Leaves get whole-triangle boxes, so a pre-split BLAS stays correct but loses
// its tighter fragment boxes (IDKEngine does not pre-split refittable meshes either).
#pragma once

#include "bvh/blas.hpp"

#include <span>

namespace idk::bvh {

// `triangles` must have blas.triangleCount entries. Updates blas.stats.sah. Throws std::invalid_argument on a
// size mismatch.
void refitBlas(Blas& blas, std::span<const Triangle> triangles);

}  // namespace idk::bvh
