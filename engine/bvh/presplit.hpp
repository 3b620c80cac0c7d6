// presplit.hpp: PreSplitting (port of IDKEngine Bvh/PreSplitting.cs, readme "Better BVHs with PreSplitting"):
// before the build, large triangles with much empty box space are cut into several boxes ("fragments") along
// global power-of-two split planes of the scene box; every fragment keeps its original triangle id.
#pragma once

#include "bvh/geometry.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace idk::bvh {

struct Fragments {
    std::vector<Box> boxes;
    std::vector<uint32_t> triangleIds;  // original triangle of each box
};

// cbrt(largestExtent(box)^2 * (area(box) - area(triangle))): large triangles whose box is mostly empty first.
float splitPriority(const Triangle& triangle);

// 1 + floor(priority / totalPriority * triangleCount * splitFactor): the share of the total priority decides.
uint32_t splitCount(float priority, double totalPriority, uint32_t triangleCount, float splitFactor);

// Largest node size of the recursive spatial-median subdivision of the scene (2^k * globalSize, k <= -1) that is
// strictly smaller than `extent` (0 when extent / globalSize is below the float normal range).
float splitNodeSize(float extent, float globalSize);

// Splits the triangles listed in `ids` (all finite). splitFactor <= 0 gives exactly one box per triangle.
Fragments preSplit(std::span<const Triangle> triangles, std::span<const uint32_t> ids, float splitFactor);

}  // namespace idk::bvh
