// presplit.cpp: split counts from relative priorities, split planes snapped to the global power-of-two planes,
// recursive splitting with clipping to the parent box, split counts shared by largest extent.
#include "bvh/presplit.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace idk::bvh {

float splitPriority(const Triangle& triangle) {
    const Box box = triangle.box();
    const float extent = box.largestExtent();
    const float emptyArea = std::max(0.0f, 2.0f * box.halfArea() - triangle.area());
    return std::cbrt(extent * extent * emptyArea);
}

uint32_t splitCount(float priority, double totalPriority, uint32_t triangleCount, float splitFactor) {
    if (!(totalPriority > 0.0) || !(splitFactor > 0.0f)) return 1;
    const double share = double(priority) / totalPriority * double(triangleCount);
    const double extra = std::floor(share * double(splitFactor));
    return 1 + uint32_t(std::min(extra, 1.0e6));  // the cap only guards against absurd split factors
}

float splitNodeSize(float extent, float globalSize) {
    // 2^floor(log2(alpha)) by keeping only the exponent bits of alpha = extent / globalSize (Karras & Aila 2013,
    // slide 64: the split planes of recursive spatial median splits of the scene box).
    const float alpha = extent / globalSize;
    const uint32_t exponentBits = std::bit_cast<uint32_t>(alpha) & (255u << 23);
    float size = std::bit_cast<float>(exponentBits) * globalSize;
    if (size >= extent) size *= 0.5f;  // alpha was a power of two: take the next finer level
    return size;
}

Fragments preSplit(std::span<const Triangle> triangles, std::span<const uint32_t> ids, float splitFactor) {
    Fragments out;
    Box global;
    double totalPriority = 0.0;
    for (uint32_t id : ids) {
        global.grow(triangles[id].box());
        if (splitFactor > 0.0f) totalPriority += splitPriority(triangles[id]);
    }
    const glm::vec3 globalSize = global.extent();
    out.boxes.reserve(ids.size());
    out.triangleIds.reserve(ids.size());

    struct Pending {
        Box box;
        uint32_t splits;
    };
    std::vector<Pending> stack;
    for (uint32_t id : ids) {
        const Triangle& tri = triangles[id];
        const uint32_t count = splitFactor > 0.0f
                                   ? splitCount(splitPriority(tri), totalPriority, uint32_t(ids.size()), splitFactor)
                                   : 1;
        stack.push_back({tri.box(), count});
        while (!stack.empty()) {
            const Pending top = stack.back();
            stack.pop_back();
            auto emit = [&] {
                out.boxes.push_back(top.box);
                out.triangleIds.push_back(id);
            };
            if (top.splits <= 1) {
                emit();
                continue;
            }
            const int axis = top.box.largestAxis();
            const float extent = top.box.largestExtent();
            const float nodeSize = splitNodeSize(extent, globalSize[axis]);
            if (!(nodeSize > 0.0f)) {
                emit();
                continue;
            }
            // Snap the box middle to the nearest global split plane; it stays strictly inside the box because
            // nodeSize < extent, unless rounding says otherwise (then the box is kept whole).
            const float mid = 0.5f * (top.box.min[axis] + top.box.max[axis]);
            const float index = std::round((mid - global.min[axis]) / nodeSize);
            const float position = global.min[axis] + index * nodeSize;
            if (!(position > top.box.min[axis] && position < top.box.max[axis])) {
                emit();
                continue;
            }
            Box left, right;
            splitTriangle(tri, axis, position, top.box, left, right);
            if (left.isEmpty() || right.isEmpty()) {
                emit();
                continue;
            }
            const float le = left.largestExtent();
            const float re = right.largestExtent();
            uint32_t leftCount = top.splits / 2;
            if (le + re > 0.0f) {
                const float share = std::round(float(top.splits) * (le / (le + re)));
                leftCount = uint32_t(std::clamp(share, 1.0f, float(top.splits - 1)));
            }
            stack.push_back({right, top.splits - leftCount});
            stack.push_back({left, leftCount});
        }
    }
    return out;
}

}  // namespace idk::bvh
