// box_tree.hpp: the SweepSAH builder over boxes, shared by the BLAS (triangle or fragment boxes) and the TLAS
// (instance world boxes). Port of IDKEngine BLAS.Build ("Bonsai" style): one radix sort per axis before the
// recursion, right-to-left then left-to-right sweeps with both early-outs, an alloc-free stable partition of the
// two other axes that reuses the cost buffer, SAH-terminated leaves with a maximum leaf size, and threaded
// recursion on a small task pool. Deviation: the output is the same byte for byte for any thread count (node slots
// are reserved from the subtree size, as if built with one primitive per leaf, then compacted depth first).
#pragma once

#include "bvh/geometry.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace idk::bvh {

// A node of the CPU trees (32 bytes, the same fields as the GPU node). Leaf <=> count > 0; a leaf covers
// primitives (or, in a finished Blas, triangle references) [first, first + count). An inner node's children are
// the adjacent pair (first, first + 1). Node 0 is the root.
struct Node {
    glm::vec3 min{kInfinity};
    uint32_t first = 0;
    glm::vec3 max{-kInfinity};
    uint32_t count = 0;

    bool isLeaf() const { return count > 0; }
    Box box() const { return {min, max}; }
    void setBox(const Box& b) {
        min = b.min;
        max = b.max;
    }
};
static_assert(sizeof(Node) == 32);

// SAH constants of the readme ("I used TRAVERSAL_COST=1.0 and settings.TriangleCost=1.1").
inline constexpr float kTraversalCost = 1.0f;
inline constexpr float kTriangleCost = 1.1f;

struct BoxTreeOptions {
    uint32_t maxLeafSize = 8;           // nodes with more primitives are always split
    float primitiveCost = kTriangleCost;
    uint32_t threadCount = 0;           // 0: std::thread::hardware_concurrency()
    uint32_t parallelThreshold = 8192;  // a subtree goes to another thread when both children have this many
};

struct BoxTree {
    std::vector<Node> nodes;         // depth-first: a pair is placed when its parent is visited, left subtree first
    std::vector<uint32_t> primOrder; // leaf ranges index this permutation of the input primitives
};

// Builds a tree over `boxes` (each must be finite and non-empty). Leaf ranges appear in primOrder in depth-first
// order, left before right, so every subtree covers one contiguous range and a leaf pair is adjacent.
// An empty input gives an empty tree (no nodes).
BoxTree buildBoxTree(std::span<const Box> boxes, const BoxTreeOptions& options);

// Copies the nodes reachable from `nodes[0]` depth first (a pair is appended when its parent is visited, left
// subtree first): drops unreachable slots and renumbers the child links. Leaf ranges are kept as they are.
std::vector<Node> compactDepthFirst(std::span<const Node> nodes);

}  // namespace idk::bvh
