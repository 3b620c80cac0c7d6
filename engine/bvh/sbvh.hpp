// sbvh.hpp: the spatial-split builder (SBVH, Stich, Friedrich & Dietrich 2009, "Spatial Splits in Bounding Volume
// Hierarchies"). Each node compares the best object split (a full SAH sweep over the node's references sorted by
// centroid on each axis, as the SweepSAH builder in box_tree.hpp) with the best spatial split (binned planes on each
// axis, references chopped at the bin planes); the spatial search only runs where the object split's children
// overlap by more than overlapThreshold of the root area, and a split may only add as many references as the
// node's budget. Chopped references get the exact box of the triangle part inside them (clippedTriangleBox).
// Not in IDKEngine (it has pre-splitting only); added for issue 19. Deterministic for any thread count: the budget
// is split between the children in proportion to their reference counts (never a shared counter), and subtrees
// built on other threads are stitched in depth-first order.
#pragma once

#include "bvh/box_tree.hpp"
#include "bvh/geometry.hpp"
#include "bvh/presplit.hpp"

#include <cstdint>
#include <span>

namespace idk::bvh {

struct SpatialTreeOptions {
    BoxTreeOptions tree;
    float referenceBudget = 2.0f;      // at most this many references per input fragment over the whole tree
    float overlapThreshold = 1.0e-5f;  // alpha: spatial splits are searched where overlap / root area exceeds it
    uint32_t bins = 16;                // spatial bins per axis (16 and 32 measured: 16 is faster, SAH about even)
};

struct SpatialTree {
    BoxTree tree;                 // primOrder[k] = the fragment of leaf reference k (fragments may repeat)
    uint32_t spatialSplits = 0;   // nodes split by a spatial split
};

// Builds over the fragments (from preSplit; one per triangle when pre-splitting is off). Leaf ranges follow
// depth-first order as in buildBoxTree; every reference box holds the part of its triangle inside the node.
SpatialTree buildSpatialTree(std::span<const Triangle> triangles, const Fragments& fragments,
                             const SpatialTreeOptions& options);

}  // namespace idk::bvh
