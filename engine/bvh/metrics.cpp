// metrics.cpp: SAH, EPO, depth and stack size of a tree (see metrics.hpp).
#include "bvh/metrics.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace idk::bvh {

float computeSah(std::span<const Node> nodes, float triangleCost) {
    if (nodes.empty()) return 0.0f;
    const double rootArea = nodes[0].box().halfArea();
    if (!(rootArea > 0.0)) return 0.0f;
    double cost = 0.0;
    for (const Node& node : nodes) {
        const double probHitNode = double(node.box().halfArea()) / rootArea;
        cost += node.isLeaf() ? double(triangleCost) * node.count * probHitNode : double(kTraversalCost) * probHitNode;
    }
    return float(cost);
}

uint32_t maxDepth(std::span<const Node> nodes) {
    if (nodes.empty()) return 0;
    std::vector<uint32_t> depth(nodes.size(), 0);
    uint32_t deepest = 0;
    for (size_t i = 0; i < nodes.size(); ++i) {
        deepest = std::max(deepest, depth[i]);
        if (!nodes[i].isLeaf()) depth[nodes[i].first] = depth[nodes[i].first + 1] = depth[i] + 1;
    }
    return deepest;
}

uint32_t requiredStackSize(std::span<const Node> nodes) {
    if (nodes.empty()) return 0;
    std::vector<uint32_t> stack(nodes.size(), 0);
    for (size_t i = nodes.size(); i-- > 0;) {
        const Node& node = nodes[i];
        if (node.isLeaf()) continue;
        const Node& a = nodes[node.first];
        const Node& b = nodes[node.first + 1];
        const uint32_t both = (!a.isLeaf() && !b.isLeaf()) ? 1 : 0;
        stack[i] = std::max(stack[node.first], stack[node.first + 1]) + both;
    }
    return stack[0];
}

double computeEpo(const Blas& blas, std::span<const Triangle> triangles, float triangleCost, uint32_t threadCount) {
    const std::vector<Node>& nodes = blas.nodes;
    if (nodes.empty()) return 0.0;
    const uint32_t triCount = uint32_t(triangles.size());

    // Reference range [lo, hi) of every subtree in triIds (contiguous: leaves are emitted depth first).
    std::vector<uint32_t> lo(nodes.size()), hi(nodes.size());
    for (size_t i = nodes.size(); i-- > 0;) {
        const Node& n = nodes[i];
        if (n.isLeaf()) {
            lo[i] = n.first;
            hi[i] = n.first + n.count;
        } else {
            lo[i] = std::min(lo[n.first], lo[n.first + 1]);
            hi[i] = std::max(hi[n.first], hi[n.first + 1]);
        }
    }
    // Positions of each triangle in triIds (several after pre-splitting), as offsets into one array.
    std::vector<uint32_t> offsets(triCount + 1, 0), positions(blas.triIds.size());
    for (uint32_t id : blas.triIds) ++offsets[id + 1];
    for (uint32_t t = 0; t < triCount; ++t) offsets[t + 1] += offsets[t];
    {
        std::vector<uint32_t> cursor(offsets.begin(), offsets.end() - 1);
        for (uint32_t p = 0; p < blas.triIds.size(); ++p) positions[cursor[blas.triIds[p]]++] = p;
    }

    constexpr uint32_t kChunk = 512;
    const uint32_t chunkCount = (triCount + kChunk - 1) / kChunk;
    std::vector<double> overlap(chunkCount, 0.0), area(chunkCount, 0.0);
    std::atomic<uint32_t> nextChunk{0};
    auto worker = [&] {
        std::vector<uint32_t> stack;
        for (uint32_t chunk; (chunk = nextChunk.fetch_add(1)) < chunkCount;) {
            double sum = 0.0, areaSum = 0.0;
            for (uint32_t t = chunk * kChunk; t < std::min(triCount, (chunk + 1) * kChunk); ++t) {
                const Triangle& tri = triangles[t];
                if (!tri.isFinite()) continue;
                areaSum += clippedTriangleArea(tri, tri.box());
                const Box triBox = tri.box();
                stack.assign(1, 0);
                while (!stack.empty()) {
                    const uint32_t ni = stack.back();
                    stack.pop_back();
                    const Node& n = nodes[ni];
                    if (!n.box().overlaps(triBox)) continue;
                    bool below = false;
                    for (uint32_t k = offsets[t]; k < offsets[t + 1] && !below; ++k) {
                        below = positions[k] >= lo[ni] && positions[k] < hi[ni];
                    }
                    if (!below) {
                        const double a = clippedTriangleArea(tri, n.box());
                        if (!(a > 0.0)) continue;  // children lie inside this box: nothing more below
                        sum += (n.isLeaf() ? double(triangleCost) * n.count : double(kTraversalCost)) * a;
                    }
                    if (!n.isLeaf()) {
                        stack.push_back(n.first + 1);
                        stack.push_back(n.first);
                    }
                }
            }
            overlap[chunk] = sum;
            area[chunk] = areaSum;
        }
    };
    const uint32_t threads =
        std::min(chunkCount, threadCount != 0 ? threadCount : std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (uint32_t i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (std::thread& th : pool) th.join();

    double totalOverlap = 0.0, totalArea = 0.0;
    for (uint32_t c = 0; c < chunkCount; ++c) {
        totalOverlap += overlap[c];
        totalArea += area[c];
    }
    return totalArea > 0.0 ? totalOverlap / totalArea : 0.0;
}

}  // namespace idk::bvh
