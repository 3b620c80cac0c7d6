// sbvh_split.cpp: object-split sweep and binned spatial-split search of the spatial-split builder (see sbvh.hpp,
// sbvh_split.hpp). The bins chop references with one pass over the triangle's edges (vertices and plane crossings in
// float: estimates of the children's boxes); the chosen split then clips exactly (sbvh.cpp).
#include "bvh/sbvh_split.hpp"

#include <algorithm>

namespace idk::bvh::sbvh {

void sweepObjectSplit(std::span<const Ref> sorted, int axis, ObjectSplit& best, std::vector<float>& scratch) {
    const uint32_t n = uint32_t(sorted.size());
    if (n < 2) return;
    scratch.resize(n);
    // Right to left: scratch[i] = area(box of [i, n)) * (n - i); it only grows, so past the best cost no split
    // with a right child starting at or before i can win.
    Box acc;
    uint32_t firstSplit = 1;
    for (uint32_t i = n - 1; i > 0; --i) {
        acc.grow(sorted[i].box);
        const float rightCost = acc.halfArea() * float(n - i);
        if (rightCost > best.cost) {
            firstSplit = i + 1;
            break;
        }
        scratch[i] = rightCost;
    }
    acc = Box::empty();
    for (uint32_t i = 0; i + 1 < firstSplit; ++i) acc.grow(sorted[i].box);
    for (uint32_t split = firstSplit; split < n; ++split) {
        acc.grow(sorted[split - 1].box);
        const float leftCost = acc.halfArea() * float(split);
        if (leftCost > best.cost) break;
        const float cost = leftCost + scratch[split];
        const uint32_t imbalance = 2 * split > n ? 2 * split - n : n - 2 * split;
        if (cost < best.cost || (cost == best.cost && best.axis >= 0 && imbalance < best.imbalance)) {
            best.cost = cost;
            best.axis = axis;
            best.index = split;
            best.imbalance = imbalance;
        }
    }
}

void objectSplitBoxes(std::span<const Ref> sorted, ObjectSplit& split) {
    split.left = split.right = Box::empty();
    for (uint32_t i = 0; i < sorted.size(); ++i) (i < split.index ? split.left : split.right).grow(sorted[i].box);
}

namespace {

struct Bin {
    Box box;
    uint32_t enter = 0;  // references whose first bin this is
    uint32_t exit = 0;   // references whose last bin this is
};

}  // namespace

void findSpatialSplit(std::span<const Ref> refs, std::span<const Triangle> triangles,
                      std::span<const uint32_t> fragmentTriangle, const Box& nodeBox, uint32_t binCount,
                      uint64_t budget, SpatialSplit& best) {
    const uint32_t n = uint32_t(refs.size());
    std::vector<Bin> bins(binCount);
    std::vector<float> planes(binCount + 1);
    std::vector<Box> rightBoxes(binCount);
    std::vector<uint32_t> rightCounts(binCount);
    std::vector<Box> parts;  // the bins of one chopped reference
    for (int axis = 0; axis < 3; ++axis) {
        const float lo = nodeBox.min[axis], extent = nodeBox.max[axis] - lo;
        if (!(extent > 0.0f)) continue;
        for (uint32_t j = 0; j <= binCount; ++j) planes[j] = lo + extent * (float(j) / float(binCount));
        planes[binCount] = nodeBox.max[axis];
        std::fill(bins.begin(), bins.end(), Bin{});
        const float scale = float(binCount) / extent;
        const int last = int(binCount) - 1;
        // The bin b with planes[b] <= x < planes[b + 1] (clamped to the node).
        // Clamped in float first: a chopped triangle's vertices may lie far outside the node (float -> int overflow).
        auto estimate = [&](float x) { return int(std::clamp((x - lo) * scale, 0.0f, float(last))); };
        auto binOf = [&](float x) {
            int b = estimate(x);
            while (b > 0 && x < planes[b]) --b;
            while (b < last && x >= planes[b + 1]) ++b;
            return b;
        };
        for (const Ref& r : refs) {
            // First bin: planes[b0] <= min < planes[b0 + 1]; last bin: planes[b1] < max <= planes[b1 + 1]
            // (a zero-width reference on a plane stays in the bin right of it). The estimate from the scale is
            // corrected against the planes themselves, so the classification matches the partition exactly.
            const int b0 = binOf(r.box.min[axis]);
            int b1 = estimate(r.box.max[axis]);
            while (b1 > 0 && r.box.max[axis] <= planes[b1]) --b1;
            while (b1 < last && r.box.max[axis] > planes[b1 + 1]) ++b1;
            b1 = std::max(b0, b1);
            ++bins[b0].enter;
            ++bins[b1].exit;
            if (b0 == b1) {
                bins[b0].box.grow(r.box);
                continue;
            }
            // The part of the triangle in bin b is the convex polygon of its vertices inside the slab and its edges'
            // crossings of the slab's two planes: grow each bin of [b0, b1] by those, then clip to the reference.
            const Triangle& tri = triangles[fragmentTriangle[r.fragment]];
            const glm::vec3 v[3] = {tri.v0, tri.v1, tri.v2};
            const uint32_t span = uint32_t(b1 - b0 + 1);
            if (parts.size() < span) parts.resize(span);
            std::fill_n(parts.begin(), span, Box::empty());
            for (int e = 0; e < 3; ++e) {
                glm::vec3 a = v[e], b = v[(e + 1) % 3];
                if (a[axis] > b[axis]) std::swap(a, b);
                const int ba = binOf(a[axis]), bb = binOf(b[axis]);
                if (ba >= b0 && ba <= b1) parts[ba - b0].grow(a);
                if (ba > b0 && ba <= b1 && a[axis] == planes[ba]) parts[ba - 1 - b0].grow(a);  // on a plane: both bins
                // Planes strictly between the two vertices that bound one of the reference's bins (b0's left plane
                // and b1's right plane included).
                for (int j = std::max(ba + 1, b0); j <= std::min(bb, b1 + 1); ++j) {
                    if (!(planes[j] > a[axis] && planes[j] < b[axis])) continue;
                    glm::vec3 p = a + (b - a) * ((planes[j] - a[axis]) / (b[axis] - a[axis]));
                    p[axis] = planes[j];
                    if (j - 1 >= b0) parts[j - 1 - b0].grow(p);
                    if (j <= b1) parts[j - b0].grow(p);
                }
            }
            for (uint32_t k = 0; k < span; ++k) {
                if (parts[k].isEmpty()) continue;
                Box clipTo = r.box;
                clipTo.min[axis] = std::max(clipTo.min[axis], planes[b0 + int(k)]);
                clipTo.max[axis] = std::min(clipTo.max[axis], planes[b0 + int(k) + 1]);
                parts[k].clip(clipTo);
                if (!parts[k].isEmpty()) bins[b0 + int(k)].box.grow(parts[k]);
            }
        }
        // Plane j (1 .. binCount - 1) has bins [0, j) on the left and [j, binCount) on the right.
        Box acc;
        uint32_t count = 0;
        for (uint32_t j = binCount; j-- > 1;) {
            acc.grow(bins[j].box);
            count += bins[j].exit;
            rightBoxes[j] = acc;
            rightCounts[j] = count;
        }
        acc = Box::empty();
        count = 0;
        for (uint32_t j = 1; j < binCount; ++j) {
            acc.grow(bins[j - 1].box);
            count += bins[j - 1].enter;
            const uint32_t rightCount = rightCounts[j];
            if (count == 0 || rightCount == 0) continue;
            if (!(planes[j] > nodeBox.min[axis] && planes[j] < nodeBox.max[axis])) continue;
            if (uint64_t(count) + rightCount - n > budget) continue;  // straddlers add one reference each
            const float cost = acc.halfArea() * float(count) + rightBoxes[j].halfArea() * float(rightCount);
            if (cost < best.cost) {
                best = {cost, axis, planes[j]};
            }
        }
    }
}

}  // namespace idk::bvh::sbvh
