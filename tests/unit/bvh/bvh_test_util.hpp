// bvh_test_util.hpp: shared helpers of the BVH tests: the bunny, random rays, the structural checker, and a
// median-split baseline builder for the SAH comparison.
#pragma once

#include "bvh/blas.hpp"
#include "bvh/geometry.hpp"
#include "bvh/metrics.hpp"
#include "bvh/raw_mesh.hpp"
#include "bvh/traverse.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace idk::bvh::test {

inline const std::vector<Triangle>& bunny() {
    static const std::vector<Triangle> triangles = loadRawTriangles(IDK_SHARED_DIR "/scenes/bunny/bunny.bin");
    return triangles;
}

inline Box boundsOf(const std::vector<Triangle>& triangles) {
    Box b;
    for (const Triangle& t : triangles) b.grow(t.box());
    return b;
}

inline glm::vec3 randomUnitVector(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        const glm::vec3 v(n(rng), n(rng), n(rng));
        const float l = glm::length(v);
        if (l > 1e-6f) return v / l;
    }
}

// Half the rays start anywhere in the scene box grown by 50% and go in random directions; the other half start
// outside the box and aim at a random point inside it (mostly hits).
inline std::vector<Ray> randomRays(const Box& scene, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 center = 0.5f * (scene.min + scene.max);
    const glm::vec3 extent = scene.extent();
    const float radius = glm::length(extent);
    std::vector<Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 inside = scene.min + extent * glm::vec3(u(rng), u(rng), u(rng));
        if (i % 2 == 0) {
            const glm::vec3 origin = center + 1.5f * (inside - center);
            rays[i] = {origin, randomUnitVector(rng)};
        } else {
            const glm::vec3 origin = center + radius * randomUnitVector(rng);
            rays[i] = {origin, glm::normalize(inside - origin)};
        }
    }
    return rays;
}

// Checks every structural promise of a Blas built by buildBlas (see blas.hpp).
inline ::testing::AssertionResult checkBlas(const Blas& blas, const std::vector<Triangle>& triangles,
                                            uint32_t maxLeafSize, bool presplit) {
    auto fail = [](const std::string& why) { return ::testing::AssertionFailure() << why; };
    std::vector<uint32_t> finite;
    for (uint32_t i = 0; i < triangles.size(); ++i) {
        if (triangles[i].isFinite()) finite.push_back(i);
    }
    if (blas.triangleCount != triangles.size()) return fail("triangleCount");
    if (finite.empty()) {
        return blas.nodes.empty() && blas.triIds.empty() ? ::testing::AssertionSuccess() : fail("empty mesh has nodes");
    }
    if (blas.nodes.empty()) return fail("no nodes");
    std::vector<uint32_t> visits(blas.nodes.size(), 0);
    std::vector<uint32_t> references(triangles.size(), 0);
    uint32_t nextRange = 0, leaves = 0;
    std::vector<uint32_t> stack{0};
    visits[0] = 1;
    while (!stack.empty()) {
        const uint32_t i = stack.back();
        stack.pop_back();
        const Node& n = blas.nodes[i];
        if (n.box().isEmpty()) return fail("empty box at node " + std::to_string(i));
        if (!n.isLeaf()) {
            if (n.first <= i || n.first + 1 >= blas.nodes.size()) return fail("bad child link at " + std::to_string(i));
            for (uint32_t c : {n.first, n.first + 1}) {
                if (visits[c]++ != 0) return fail("node reached twice: " + std::to_string(c));
                if (!n.box().contains(blas.nodes[c].box())) return fail("child box outside parent at " + std::to_string(c));
            }
            stack.push_back(n.first + 1);
            stack.push_back(n.first);
            continue;
        }
        ++leaves;
        if (n.first != nextRange) return fail("leaf ranges not depth-first contiguous at node " + std::to_string(i));
        if (!presplit && n.count > maxLeafSize) return fail("leaf too large: " + std::to_string(n.count));
        if (n.first + n.count > blas.triIds.size()) return fail("leaf range out of bounds");
        nextRange += n.count;
        std::set<uint32_t> inLeaf;
        for (uint32_t k = n.first; k < n.first + n.count; ++k) {
            const uint32_t id = blas.triIds[k];
            if (id >= triangles.size() || !triangles[id].isFinite()) return fail("bad triangle id");
            if (!inLeaf.insert(id).second) return fail("triangle repeated in a leaf");
            ++references[id];
            const Box tb = triangles[id].box();
            if (presplit ? !n.box().overlaps(tb) : !n.box().contains(tb)) {
                return fail("leaf box does not hold triangle " + std::to_string(id));
            }
        }
    }
    if (nextRange != blas.triIds.size()) return fail("triIds not covered by leaves");
    for (uint32_t v : visits) {
        if (v != 1) return fail("unreachable node");
    }
    for (uint32_t id : finite) {
        if (references[id] == 0) return fail("triangle never referenced: " + std::to_string(id));
        if (!presplit && references[id] != 1) return fail("triangle referenced twice: " + std::to_string(id));
    }
    if (blas.stats.nodeCount != blas.nodes.size() || blas.stats.leafCount != leaves ||
        blas.stats.referenceCount != blas.triIds.size()) {
        return fail("stats disagree with the tree");
    }
    return ::testing::AssertionSuccess();
}

// Object-median split on the largest centroid axis down to maxLeafSize triangles: the SAH baseline.
inline Blas buildMedianSplit(const std::vector<Triangle>& triangles, uint32_t maxLeafSize) {
    Blas blas;
    blas.triangleCount = uint32_t(triangles.size());
    blas.triIds.resize(triangles.size());
    std::iota(blas.triIds.begin(), blas.triIds.end(), 0u);
    std::vector<glm::vec3> centroid(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) centroid[i] = (triangles[i].v0 + triangles[i].v1 + triangles[i].v2) / 3.0f;
    struct Task {
        uint32_t node, start, end;
    };
    blas.nodes.emplace_back();
    std::vector<Task> stack{{0, 0, uint32_t(triangles.size())}};
    while (!stack.empty()) {
        const Task t = stack.back();
        stack.pop_back();
        Box box, cbox;
        for (uint32_t k = t.start; k < t.end; ++k) {
            box.grow(triangles[blas.triIds[k]].box());
            cbox.grow(centroid[blas.triIds[k]]);
        }
        blas.nodes[t.node].setBox(box);
        if (t.end - t.start <= maxLeafSize) {
            blas.nodes[t.node].first = t.start;
            blas.nodes[t.node].count = t.end - t.start;
            continue;
        }
        const int axis = cbox.largestAxis();
        const uint32_t mid = (t.start + t.end) / 2;
        std::nth_element(blas.triIds.begin() + t.start, blas.triIds.begin() + mid, blas.triIds.begin() + t.end,
                         [&](uint32_t a, uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
        const uint32_t child = uint32_t(blas.nodes.size());
        blas.nodes[t.node].first = child;
        blas.nodes.emplace_back();
        blas.nodes.emplace_back();
        stack.push_back({child + 1, mid, t.end});
        stack.push_back({child, t.start, mid});
    }
    blas.stats.nodeCount = uint32_t(blas.nodes.size());
    blas.stats.referenceCount = uint32_t(blas.triIds.size());
    for (const Node& n : blas.nodes) blas.stats.leafCount += n.isLeaf() ? 1 : 0;
    blas.stats.sah = computeSah(blas.nodes);
    return blas;
}

inline bool relativeClose(float a, float b, float tolerance) {
    return std::abs(a - b) <= tolerance * std::max(std::abs(a), std::abs(b));
}

}  // namespace idk::bvh::test
