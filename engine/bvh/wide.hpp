// wide.hpp (internal to the CPU traversal): a 4-wide copy of a binary BVH, made by collapsing every other level
// (a node's four grandchildren, or its leaf children, become the slots of one wide node), stored as SoA boxes so one
// SSE robust slab test covers four children. Same role as Embree's BVH4 for single rays. The tree it describes is
// the binary one (same leaves, same triangle ranges); each box test is the scalar intersectBox operation for
// operation, so the hits are those of the binary walk. The GPU keeps the binary layout (flatten.hpp).
#pragma once

#include "bvh/box_tree.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace idk::bvh {

struct alignas(64) WideNode {
    // bounds[0..2][slot] = min x, y, z; bounds[3..5][slot] = max x, y, z. An unused slot has an empty box
    // (min +inf, max -inf), which the slab test always rejects.
    float bounds[6][4];
    uint32_t first[4];  // inner slot: index of its WideNode; leaf slot: first triangle reference
    uint32_t count[4];  // 0: inner slot (or unused), > 0: leaf with this many triangle references
};
static_assert(sizeof(WideNode) == 128);

// The wide nodes of a binary tree whose root (nodes[0]) is an inner node; element 0 is the root's. Empty for an
// empty tree or a root leaf (the binary walk handles those).
std::vector<WideNode> buildWideNodes(std::span<const Node> nodes);

}  // namespace idk::bvh
