// sbvh.cpp: the spatial-split builder's recursion (see sbvh.hpp): per node the object split, the spatial split where
// the object split's children overlap, the partition that keeps the three centroid-sorted arrays sorted (references
// that keep their box keep their order; chopped ones are sorted and merged in), and fork-join threading whose
// subtrees are stitched back in depth-first order.
#include "bvh/sbvh.hpp"

#include "bvh/sbvh_split.hpp"

#include <algorithm>
#include <atomic>
#include <thread>

namespace idk::bvh {
namespace {

using sbvh::Ref;
using RefArrays = std::array<std::vector<Ref>, 3>;  // the same references, sorted by refLess on axis 0, 1, 2

struct Subtree {
    std::vector<Node> nodes;       // node 0 is the subtree root
    std::vector<uint32_t> prims;   // fragment of each leaf reference, depth-first
};

// What happens to one reference straddling the spatial split plane.
struct Straddler {
    uint32_t fragment;
    enum Side : uint8_t { Both, Left, Right } side;
    Box left, right;  // the exact boxes of the two parts
};

struct Builder {
    std::span<const Triangle> triangles;
    std::span<const uint32_t> fragmentTriangle;
    SpatialTreeOptions options;
    float rootArea = 0.0f;
    std::atomic<int> freeThreads{0};
    std::atomic<uint32_t> spatialSplits{0};

    void build(RefArrays refs, uint64_t budget, Subtree& out, uint32_t slot);
    bool partitionSpatial(RefArrays& refs, const sbvh::SpatialSplit& split, RefArrays& left, RefArrays& right);
    Straddler chop(const Ref& r, const sbvh::SpatialSplit& split) const;
};

Box boundsOf(std::span<const Ref> refs) {
    Box b;
    for (const Ref& r : refs) b.grow(r.box);
    return b;
}

// The two parts of a straddler, each the exact box of the triangle inside the reference on that side of the plane.
// Stich et al.'s reference unsplitting (keeping a straddler whole on the cheaper side) is left out: on the benchmark
// scenes it raised the final SAH (rotated atrium 28.39 -> 28.53, atrium 29.83 -> 30.04 at budget 1.5), as the
// whole box makes the two children overlap again.
Straddler Builder::chop(const Ref& r, const sbvh::SpatialSplit& split) const {
    const int axis = split.axis;
    Straddler s{r.fragment, Straddler::Both, {}, {}};
    Box lh = r.box, rh = r.box;
    lh.max[axis] = split.position;
    rh.min[axis] = split.position;
    const Triangle& tri = triangles[fragmentTriangle[r.fragment]];
    s.left = clippedTriangleBox(tri, lh);
    s.right = clippedTriangleBox(tri, rh);
    if (s.left.isEmpty() && s.right.isEmpty()) {  // cannot happen for a reference that holds its part; kept whole
        s.side = Straddler::Left;
        s.left = r.box;
    } else if (s.left.isEmpty() || s.right.isEmpty()) {  // the triangle only reaches one side of the plane
        s.side = s.left.isEmpty() ? Straddler::Right : Straddler::Left;
    }
    return s;
}

bool Builder::partitionSpatial(RefArrays& refs, const sbvh::SpatialSplit& split, RefArrays& left, RefArrays& right) {
    const int axis = split.axis;
    const float p = split.position;
    std::vector<Straddler> straddlers;
    for (const Ref& r : refs[0]) {
        if (r.box.min[axis] < p && r.box.max[axis] > p) straddlers.push_back(chop(r, split));
    }
    std::sort(straddlers.begin(), straddlers.end(),
              [](const Straddler& a, const Straddler& b) { return a.fragment < b.fragment; });
    auto find = [&](uint32_t fragment) -> const Straddler& {
        return *std::lower_bound(straddlers.begin(), straddlers.end(), fragment,
                                 [](const Straddler& s, uint32_t f) { return s.fragment < f; });
    };
    std::vector<Ref> newLeft, newRight, merged;
    for (int k = 0; k < 3; ++k) {
        std::vector<Ref>& l = left[k];
        std::vector<Ref>& r = right[k];
        newLeft.clear();
        newRight.clear();
        for (const Ref& ref : refs[k]) {
            if (ref.box.min[axis] >= p) {
                r.push_back(ref);
            } else if (ref.box.max[axis] <= p) {
                l.push_back(ref);
            } else {
                // A part keeps its place in the sorted order only when its box is unchanged.
                const Straddler& s = find(ref.fragment);
                if (s.side != Straddler::Right) (s.left == ref.box ? l : newLeft).push_back({s.left, ref.fragment});
                if (s.side != Straddler::Left) (s.right == ref.box ? r : newRight).push_back({s.right, ref.fragment});
            }
        }
        auto less = [k](const Ref& a, const Ref& b) { return sbvh::refLess(a, b, k); };
        for (auto [side, extra] : {std::pair{&l, &newLeft}, std::pair{&r, &newRight}}) {
            if (extra->empty()) continue;
            std::sort(extra->begin(), extra->end(), less);
            merged.resize(side->size() + extra->size());
            std::merge(side->begin(), side->end(), extra->begin(), extra->end(), merged.begin(), less);
            side->swap(merged);
        }
    }
    return !left[0].empty() && !right[0].empty();
}

// Copies subtree `s` into `out`: its root into `slot`, the rest appended (pairs stay adjacent), ranges shifted.
void append(Subtree& out, uint32_t slot, const Subtree& s) {
    const uint32_t base = uint32_t(out.nodes.size()) - 1;  // s node k >= 1 goes to base + k
    const uint32_t primBase = uint32_t(out.prims.size());
    for (uint32_t k = 0; k < s.nodes.size(); ++k) {
        Node node = s.nodes[k];
        node.first = node.isLeaf() ? node.first + primBase : base + node.first;
        if (k == 0) {
            out.nodes[slot] = node;
        } else {
            out.nodes.push_back(node);
        }
    }
    out.prims.insert(out.prims.end(), s.prims.begin(), s.prims.end());
}

void Builder::build(RefArrays refs, uint64_t budget, Subtree& out, uint32_t slot) {
    const BoxTreeOptions& opt = options.tree;
    const uint32_t n = uint32_t(refs[0].size());
    const Box box = boundsOf(refs[0]);
    out.nodes[slot].setBox(box);
    auto makeLeaf = [&] {
        out.nodes[slot].first = uint32_t(out.prims.size());
        out.nodes[slot].count = n;
        for (const Ref& r : refs[0]) out.prims.push_back(r.fragment);
    };
    if (n <= 1) return makeLeaf();

    // As in box_tree.cpp: a split must beat the leaf, Ci * n * A > Ct * A + Ci * (sum of area * count).
    const float ci = opt.primitiveCost;
    sbvh::ObjectSplit object;
    object.cost = n > opt.maxLeafSize ? kInfinity : (ci * float(n) - kTraversalCost) * box.halfArea() / ci;
    thread_local std::vector<float> scratch;
    for (int axis = 0; axis < 3; ++axis) sbvh::sweepObjectSplit(refs[axis], axis, object, scratch);
    if (object.axis < 0 && n > opt.maxLeafSize) {  // every cost infinite (coordinates near FLT_MAX): median
        object.axis = 0;
        object.index = n / 2;
    }
    if (object.axis < 0) return makeLeaf();
    objectSplitBoxes(refs[object.axis], object);

    RefArrays left, right;
    bool spatial = false;
    if (budget > 0) {
        Box overlap = object.left;
        overlap.clip(object.right);
        if (overlap.halfArea() > options.overlapThreshold * rootArea) {
            sbvh::SpatialSplit split;
            split.cost = object.cost;
            sbvh::findSpatialSplit(refs[0], triangles, fragmentTriangle, box, options.bins, budget, split);
            if (split.axis >= 0) {
                // The bins only estimate the children's boxes: keep the spatial split if its real cost still wins.
                spatial = partitionSpatial(refs, split, left, right) &&
                          boundsOf(left[0]).halfArea() * float(left[0].size()) +
                                  boundsOf(right[0]).halfArea() * float(right[0].size()) < object.cost;
                if (!spatial) left = right = RefArrays{};
            }
        }
    }
    if (spatial) {
        spatialSplits.fetch_add(1, std::memory_order_relaxed);
    } else {
        const int axis = object.axis;
        const Ref pivot = refs[axis][object.index];
        for (int k = 0; k < 3; ++k) {
            for (const Ref& r : refs[k]) (sbvh::refLess(r, pivot, axis) ? left[k] : right[k]).push_back(r);
        }
    }
    refs = RefArrays{};  // free the parent's arrays before recursing

    // The budget left after this split goes to the children in proportion to their reference counts.
    const uint64_t nl = left[0].size(), nr = right[0].size();
    const uint64_t remaining = budget - std::min(budget, nl + nr - n);
    const uint64_t leftBudget = remaining * nl / (nl + nr);
    const uint64_t rightBudget = remaining - leftBudget;

    const uint32_t child = uint32_t(out.nodes.size());
    out.nodes[slot].first = child;
    out.nodes[slot].count = 0;
    out.nodes.resize(out.nodes.size() + 2);
    const bool fork = nl >= opt.parallelThreshold && nr >= opt.parallelThreshold &&
                      freeThreads.fetch_sub(1, std::memory_order_acq_rel) > 0;
    if (!fork) {
        if (nl >= opt.parallelThreshold && nr >= opt.parallelThreshold) freeThreads.fetch_add(1, std::memory_order_acq_rel);
        build(std::move(left), leftBudget, out, child);
        build(std::move(right), rightBudget, out, child + 1);
        return;
    }
    Subtree a, b;
    a.nodes.resize(1);
    b.nodes.resize(1);
    std::thread worker([&] { build(std::move(left), leftBudget, a, 0); });
    build(std::move(right), rightBudget, b, 0);
    worker.join();
    freeThreads.fetch_add(1, std::memory_order_acq_rel);
    append(out, child, a);
    append(out, child + 1, b);
}

}  // namespace

SpatialTree buildSpatialTree(std::span<const Triangle> triangles, const Fragments& fragments,
                             const SpatialTreeOptions& options) {
    SpatialTree result;
    const uint32_t n = uint32_t(fragments.boxes.size());
    if (n == 0) return result;
    Builder builder;
    builder.triangles = triangles;
    builder.fragmentTriangle = fragments.triangleIds;
    builder.options = options;
    builder.options.tree.maxLeafSize = std::max(1u, options.tree.maxLeafSize);
    builder.options.tree.parallelThreshold = std::max(2u, options.tree.parallelThreshold);
    builder.options.bins = std::max(2u, options.bins);
    const uint32_t threads =
        options.tree.threadCount != 0 ? options.tree.threadCount : std::max(1u, std::thread::hardware_concurrency());
    builder.freeThreads = int(threads) - 1;

    RefArrays refs;
    refs[0].resize(n);
    for (uint32_t i = 0; i < n; ++i) refs[0][i] = {fragments.boxes[i], i};
    builder.rootArea = boundsOf(refs[0]).halfArea();
    for (int axis = 0; axis < 3; ++axis) {
        if (axis > 0) refs[axis] = refs[0];
        std::sort(refs[axis].begin(), refs[axis].end(),
                  [axis](const Ref& a, const Ref& b) { return sbvh::refLess(a, b, axis); });
    }
    const double extra = std::max(0.0, double(options.referenceBudget) - 1.0) * double(n);
    const uint64_t budget = uint64_t(std::min(extra, 1.0e12));

    Subtree tree;
    tree.nodes.resize(1);
    builder.build(std::move(refs), budget, tree, 0);
    result.tree.nodes = compactDepthFirst(tree.nodes);
    result.tree.primOrder = std::move(tree.prims);
    result.spatialSplits = builder.spatialSplits.load();
    return result;
}

}  // namespace idk::bvh
