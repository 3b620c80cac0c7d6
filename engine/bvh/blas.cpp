// blas.cpp: buildBlas (pre-split -> SweepSAH box tree or spatial-split tree -> optional stack-size optimisation ->
// de-duplicated leaf references in depth-first order) and the stack-size optimisation itself.
#include "bvh/blas.hpp"

#include "bvh/metrics.hpp"
#include "bvh/presplit.hpp"
#include "bvh/sbvh.hpp"

#include <algorithm>
#include <chrono>
#include <tuple>

namespace idk::bvh {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

uint32_t optimizeStackSize(BoxTree& tree, const BuildOptions& options) {
    std::vector<Node>& nodes = tree.nodes;
    if (nodes.empty()) return 0;
    const float ci = options.triangleCost;
    const double rootArea = nodes[0].box().halfArea();
    if (!(rootArea > 0.0)) return 0;
    const double budget = double(options.stackSahBudget) * computeSah(nodes, ci);
    double used = 0.0;
    uint32_t collapsed = 0;
    std::vector<uint32_t> level;
    struct Candidate {
        double delta;
        uint32_t node;
    };
    std::vector<Candidate> candidates;
    while (requiredStackSize(nodes) >= options.stackSizeThreshold) {
        // level[n]: stack entries held when n is reached (inner ancestors whose two children are both inner).
        level.assign(nodes.size(), 0);
        uint32_t deepest = 0;
        candidates.clear();
        for (uint32_t i = 0; i < nodes.size(); ++i) {
            const Node& n = nodes[i];
            if (n.isLeaf()) continue;
            const Node& a = nodes[n.first];
            const Node& b = nodes[n.first + 1];
            const uint32_t both = (!a.isLeaf() && !b.isLeaf()) ? 1 : 0;
            level[n.first] = level[n.first + 1] = level[i] + both;
            if (a.isLeaf() && b.isLeaf()) deepest = std::max(deepest, level[i]);
        }
        for (uint32_t i = 0; i < nodes.size(); ++i) {
            const Node& n = nodes[i];
            if (n.isLeaf() || level[i] != deepest) continue;
            const Node& a = nodes[n.first];
            const Node& b = nodes[n.first + 1];
            if (!a.isLeaf() || !b.isLeaf()) continue;
            // SAH change of turning the pair's parent into one leaf over both ranges.
            const double areaP = n.box().halfArea(), areaA = a.box().halfArea(), areaB = b.box().halfArea();
            const double delta =
                (ci * double(a.count + b.count) * areaP - kTraversalCost * areaP - ci * a.count * areaA -
                 ci * b.count * areaB) / rootArea;
            candidates.push_back({delta, i});
        }
        std::sort(candidates.begin(), candidates.end(),
                  [](const Candidate& x, const Candidate& y) { return std::tie(x.delta, x.node) < std::tie(y.delta, y.node); });
        uint32_t progress = 0;
        for (const Candidate& c : candidates) {
            if (used + c.delta > budget) break;
            used += c.delta;
            Node& n = nodes[c.node];
            const Node& a = nodes[n.first];
            const Node& b = nodes[n.first + 1];
            // The two leaves cover adjacent ranges (left first), so the parent covers their union.
            const uint32_t first = a.first;
            n.count = a.count + b.count;
            n.first = first;
            ++progress;
        }
        if (progress == 0) break;
        collapsed += progress;
        nodes = compactDepthFirst(nodes);
    }
    return collapsed;
}

void updateWideNodes(Blas& blas) { blas.wideNodes = buildWideNodes(blas.nodes); }

Blas buildBlas(std::span<const Triangle> triangles, const BuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Blas blas;
    blas.triangleCount = uint32_t(triangles.size());
    BuildStats& stats = blas.stats;
    stats.triangleCount = blas.triangleCount;

    std::vector<uint32_t> finite;
    finite.reserve(triangles.size());
    for (uint32_t i = 0; i < triangles.size(); ++i) {
        if (triangles[i].isFinite()) finite.push_back(i);
    }
    stats.skippedTriangles = blas.triangleCount - uint32_t(finite.size());

    const auto splitStart = std::chrono::steady_clock::now();
    const Fragments fragments = preSplit(triangles, finite, options.splitFactor);
    stats.presplitMs = msSince(splitStart);
    stats.fragmentCount = uint32_t(fragments.boxes.size());

    BoxTreeOptions treeOptions;
    treeOptions.maxLeafSize = options.maxLeafSize;
    treeOptions.primitiveCost = options.triangleCost;
    treeOptions.threadCount = options.threadCount;
    treeOptions.parallelThreshold = options.parallelThreshold;
    BoxTree tree;
    if (options.spatialSplits) {
        SpatialTreeOptions spatialOptions;
        spatialOptions.tree = treeOptions;
        spatialOptions.referenceBudget = options.splitBudget;
        SpatialTree spatial = buildSpatialTree(triangles, fragments, spatialOptions);
        tree = std::move(spatial.tree);
        stats.spatialSplits = spatial.spatialSplits;
    } else {
        tree = buildBoxTree(fragments.boxes, treeOptions);
    }
    if (options.optimizeStackSize) stats.collapsedPairs = optimizeStackSize(tree, options);

    // Leaf references in depth-first order (left first), fragments of one triangle merged within each leaf.
    blas.nodes = std::move(tree.nodes);
    blas.triIds.reserve(fragments.boxes.size());
    std::vector<uint32_t> stack;
    if (!blas.nodes.empty()) stack.push_back(0);
    while (!stack.empty()) {
        Node& node = blas.nodes[stack.back()];
        stack.pop_back();
        if (!node.isLeaf()) {
            stack.push_back(node.first + 1);
            stack.push_back(node.first);
            continue;
        }
        const size_t begin = blas.triIds.size();
        for (uint32_t k = node.first; k < node.first + node.count; ++k) {
            blas.triIds.push_back(fragments.triangleIds[tree.primOrder[k]]);
        }
        std::sort(blas.triIds.begin() + long(begin), blas.triIds.end());
        blas.triIds.erase(std::unique(blas.triIds.begin() + long(begin), blas.triIds.end()), blas.triIds.end());
        node.first = uint32_t(begin);
        node.count = uint32_t(blas.triIds.size() - begin);
        ++stats.leafCount;
    }
    blas.triIds.shrink_to_fit();
    blas.leafTriangles.reserve(blas.triIds.size());
    for (uint32_t id : blas.triIds) blas.leafTriangles.push_back(triangles[id]);

    updateWideNodes(blas);

    stats.referenceCount = uint32_t(blas.triIds.size());
    stats.nodeCount = uint32_t(blas.nodes.size());
    stats.maxDepth = maxDepth(blas.nodes);
    stats.requiredStackSize = requiredStackSize(blas.nodes);
    stats.sah = computeSah(blas.nodes, options.triangleCost);
    stats.buildMs = msSince(start);
    return blas;
}

}  // namespace idk::bvh
