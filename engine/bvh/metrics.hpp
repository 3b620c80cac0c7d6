// metrics.hpp: BVH quality numbers: global SAH (the readme's formula), EPO (end-point overlap, Aila, Karras &
// Laine 2013), maximum depth and the traversal stack size a tree needs.
#pragma once

#include "bvh/blas.hpp"
#include "bvh/box_tree.hpp"

#include <cstdint>
#include <span>

namespace idk::bvh {

// The readme's global SAH cost, verbatim in meaning:
//   float rootArea = blas.Nodes[0].HalfArea();
//   for each node: probHitNode = node.HalfArea() / rootArea;
//     leaf:  cost += settings.TriangleCost * node.TriCount * probHitNode;
//     inner: cost += TRAVERSAL_COST * probHitNode;
// with TRAVERSAL_COST = 1.0 and TriangleCost = 1.1 (the root counts as an inner node unless it is a leaf).
// Summed in double. 0 for an empty tree or a root of zero area.
float computeSah(std::span<const Node> nodes, float triangleCost = kTriangleCost);

// EPO = sum over nodes n of C(n) * sum over triangles t not referenced below n of area(t inside box(n)),
// divided by the total triangle area; C(n) = TRAVERSAL_COST for inner nodes, triangleCost * count for leaves.
// Exact: every triangle is clipped (Sutherland-Hodgman) against each node box it overlaps (found by walking the
// tree, pruning boxes it does not reach), no sampling. With pre-splitting a triangle counts as "below n" when any
// leaf under n references it. Parallel over triangles in fixed chunks with an ordered sum (deterministic).
double computeEpo(const Blas& blas, std::span<const Triangle> triangles, float triangleCost = kTriangleCost,
                  uint32_t threadCount = 0);

// Longest root-to-leaf path in edges (a lone root leaf: 0).
uint32_t maxDepth(std::span<const Node> nodes);

// Stack entries a traversal needs that keeps the current pair in registers, descends into one child and pushes
// the other only when both children are inner nodes (leaves are intersected at once, never pushed):
// S(leaf) = 0, S(inner) = max(S(left), S(right)) + (both children inner ? 1 : 0). Nodes must be in an order where
// children come after their parent (true for every tree built here).
uint32_t requiredStackSize(std::span<const Node> nodes);

}  // namespace idk::bvh
