// wide8.hpp: the 8-wide compressed BVH the GPU traverses (layout: shaders_glsl/shared/bvh_wide_types.h), made by
// collapsing the flattened binary BLAS (flatten.hpp), and a C++ walk of it that performs the GLSL traversal's
// operations (include/bvh_traverse_wide.glsl) in the same order: the CPU oracle of the wide layout. Not the CPU's
// own 4-wide SSE copy (wide.hpp), which the CPU traversal uses.
//
// Collapse: greedy largest-surface-area expansion (not Ylitie et al.'s dynamic-programming cost): a wide node starts
// from a binary inner node's two children and repeatedly replaces the inner child of largest surface area by its
// two children until it has 8 or only leaves are left. Leaves are the binary leaves with the same triangle
// references, so the wide walk finds the same closest hit as the binary one (its boxes contain the binary boxes).
// Refit keeps the binary layout: refit the binary nodes, then re-quantise the wide boxes (refitBvh8, same topology).
#pragma once

#include "bvh/geometry.hpp"
#include "bvh/traverse.hpp"
#include "shared/bvh_types.h"
#include "shared/bvh_wide_types.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace idk::bvh {

struct Bvh8 {
    std::vector<gpu::GpuWideNode> nodes;          // root at 0
    std::vector<gpu::GpuBlasTriangle> triangles;  // leaf references regrouped per wide node
    std::vector<std::array<uint32_t, gpu::kWideArity>> slotSources;  // binary node of each slot (kInvalidIndex: unused)
    uint32_t stackSize = 0;  // stack entries the ordered walk can need (GLSL BVH_WIDE_STACK_SIZE)
    uint32_t depth = 0;      // wide levels (root alone = 1)
};

// `nodes` / `triangles`: a flattened BLAS (flatten(blas), flattenTriangles(blas, ...)), e.g. after a refit.
// Throws std::invalid_argument for a malformed array (child or triangle range out of bounds, fewer than 4 nodes)
// or a leaf of more than 255 references (the 8-bit count; the builders' leaves hold at most maxLeafSize).
Bvh8 buildBvh8(std::span<const gpu::GpuBlasNode> nodes, std::span<const gpu::GpuBlasTriangle> triangles);

// Refit with fixed topology: re-derives every wide node's origin, scales and quantised boxes from the refitted
// binary nodes its slots stand for (Bvh8::slotSources), e.g. after render::recordRefit. `nodes` is the refitted
// flattened array of the BLAS `bvh` was built from.
void refitBvh8(Bvh8& bvh, std::span<const gpu::GpuBlasNode> nodes);

// Slot queries and the decoded (conservative) box of slot `slot`, exactly as the shader computes them.
bool wideSlotInner(const gpu::GpuWideNode& node, uint32_t slot);
uint32_t wideSlotCount(const gpu::GpuWideNode& node, uint32_t slot);
Box wideSlotBox(const gpu::GpuWideNode& node, uint32_t slot);

// The wide walk on the CPU (closest hit / any hit as traverse.hpp defines them) over a BLAS whose vertex i is
// positions[i]. Reports stack overflow of a `stackSize`-entry stack (0: bvh.stackSize) through `overflowed`.
Hit closestHitWide(const Bvh8& bvh, std::span<const glm::vec3> positions, const Ray& ray, uint32_t stackSize = 0,
                   bool* overflowed = nullptr);
bool anyHitWide(const Bvh8& bvh, std::span<const glm::vec3> positions, const Ray& ray);

}  // namespace idk::bvh
