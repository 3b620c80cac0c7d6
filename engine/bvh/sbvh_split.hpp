// sbvh_split.hpp: the two split searches of the spatial-split builder (sbvh.hpp), internal to engine/bvh:
// the object split (full SAH sweep over references sorted by centroid) and the binned spatial split.
#pragma once

#include "bvh/geometry.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace idk::bvh::sbvh {

// A reference: (part of) the triangle of one fragment, inside `box`.
struct Ref {
    Box box;
    uint32_t fragment = 0;
};

// Strict order of the references of one node along an axis: box centre (min + max), then fragment. A node never
// holds two references of one fragment (a chopped fragment sends one part to each child), so it is total.
inline bool refLess(const Ref& a, const Ref& b, int axis) {
    const float ka = a.box.min[axis] + a.box.max[axis];
    const float kb = b.box.min[axis] + b.box.max[axis];
    return ka < kb || (ka == kb && a.fragment < b.fragment);
}

// Costs are area * count sums (the SAH without the constants); `cost` starts at the bound a split must beat.
struct ObjectSplit {
    float cost = kInfinity;
    int axis = -1;
    uint32_t index = 0;         // first reference of the right child in the axis' sorted array
    uint32_t imbalance = 0xFFFFFFFFu;
    Box left, right;
};

struct SpatialSplit {
    float cost = kInfinity;  // estimated from the bins
    int axis = -1;
    float position = 0.0f;
};

// Sweeps one axis' sorted array; updates `best` when a cheaper (or as cheap and more balanced) split is found.
void sweepObjectSplit(std::span<const Ref> sorted, int axis, ObjectSplit& best, std::vector<float>& scratch);

// The boxes of the best object split (after every axis was swept).
void objectSplitBoxes(std::span<const Ref> sorted, ObjectSplit& split);

// Bins the references on every axis of `nodeBox` and keeps the cheapest plane that adds at most `budget` references
// and costs less than `best.cost`. A reference straddles plane p when box.min < p < box.max; one with
// box.min >= p goes right, every other one left.
void findSpatialSplit(std::span<const Ref> refs, std::span<const Triangle> triangles,
                      std::span<const uint32_t> fragmentTriangle, const Box& nodeBox, uint32_t bins, uint64_t budget,
                      SpatialSplit& best);

}  // namespace idk::bvh::sbvh
