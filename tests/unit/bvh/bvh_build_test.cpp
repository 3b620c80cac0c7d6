// bvh_build_test.cpp: the BLAS builder: structural invariants on random and real meshes, determinism across
// thread counts, SAH against a median-split baseline, pre-splitting on the rotated atrium, the stack-size
// optimisation, the building blocks (radix sort, float keys, split planes, triangle split, clipped area, EPO), the
// raw loader, and the bunny's numbers (printed, not asserted).
#include "bvh_test_util.hpp"

#include "bvh/presplit.hpp"
#include "bvh/procedural.hpp"
#include "bvh/radix_sort.hpp"

#include <cstring>
#include <iostream>
#include <stdexcept>

namespace idk::bvh {
namespace {

using test::bunny;
using test::checkBlas;

std::vector<Triangle> rotatedAtrium() {
    IndexedMesh mesh = makeAtrium();
    rotateAboutCenter(mesh, 45.0f);
    return mesh.triangles();
}

bool sameTree(const Blas& a, const Blas& b) {
    return a.nodes.size() == b.nodes.size() && a.triIds == b.triIds &&
           std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(Node)) == 0;
}

TEST(BvhBuild, RandomSoupsKeepEveryInvariant) {
    for (uint32_t count : {1u, 2u, 3u, 17u, 1000u, 20000u}) {
        const std::vector<Triangle> tris = makeRandomTriangles(count, 7 + count);
        for (uint32_t leaf : {1u, 2u, 8u}) {
            BuildOptions options;
            options.maxLeafSize = leaf;
            const Blas blas = buildBlas(tris, options);
            EXPECT_TRUE(checkBlas(blas, tris, leaf, false)) << count << " triangles, leaf " << leaf;
            EXPECT_LE(blas.nodes.size(), 2 * size_t(count) - 1);
        }
    }
}

TEST(BvhBuild, BunnyAndAtriumKeepEveryInvariant) {
    const std::vector<Triangle> rotated = rotatedAtrium();
    const std::vector<Triangle> atrium = makeAtrium().triangles();
    for (const std::vector<Triangle>* tris : {&bunny(), &atrium, &rotated}) {
        for (float split : {0.0f, 0.3f, 1.0f}) {
            BuildOptions options;
            options.splitFactor = split;
            const Blas blas = buildBlas(*tris, options);
            EXPECT_TRUE(checkBlas(blas, *tris, options.maxLeafSize, split > 0.0f)) << "split factor " << split;
            if (split == 0.0f) {
                EXPECT_EQ(blas.stats.fragmentCount, tris->size());
            }
        }
    }
}

TEST(BvhBuild, LeafCountBoundHoldsWithPresplitFragments) {
    // With pre-splitting a leaf holds at most maxLeafSize fragments, hence at most that many distinct triangles.
    BuildOptions options;
    options.splitFactor = 1.0f;
    options.maxLeafSize = 2;
    const std::vector<Triangle> tris = rotatedAtrium();
    const Blas blas = buildBlas(tris, options);
    for (const Node& n : blas.nodes) {
        if (n.isLeaf()) {
            EXPECT_LE(n.count, 2u);
        }
    }
    EXPECT_GT(blas.stats.fragmentCount, tris.size());
    EXPECT_LT(blas.stats.referenceCount, blas.stats.fragmentCount);  // de-duplication removed some references
}

TEST(BvhBuild, SameNodesForOneTwoAndFourThreads) {
    const std::vector<Triangle> rotated = rotatedAtrium();
    for (const std::vector<Triangle>* tris : {&bunny(), &rotated}) {
        for (float split : {0.0f, 0.3f}) {
            BuildOptions options;
            options.splitFactor = split;
            options.parallelThreshold = 64;  // hand subtrees to other threads early and often
            options.threadCount = 1;
            const Blas one = buildBlas(*tris, options);
            for (uint32_t threads : {2u, 4u}) {
                options.threadCount = threads;
                for (int repeat = 0; repeat < 2; ++repeat) {
                    EXPECT_TRUE(sameTree(one, buildBlas(*tris, options))) << threads << " threads, split " << split;
                }
            }
        }
    }
}

TEST(BvhBuild, SweepSahBeatsMedianSplit) {
    const std::vector<Triangle> random = makeRandomTriangles(30000, 3);
    const std::vector<Triangle> atrium = makeAtrium().triangles();
    for (const std::vector<Triangle>* tris : {&bunny(), &random, &atrium}) {
        const Blas sweep = buildBlas(*tris);
        const Blas median = test::buildMedianSplit(*tris, 8);
        ASSERT_TRUE(checkBlas(median, *tris, 8, false));
        EXPECT_LE(sweep.stats.sah, computeSah(median.nodes));
        EXPECT_FLOAT_EQ(sweep.stats.sah, computeSah(sweep.nodes));
    }
}

TEST(BvhBuild, PresplittingLowersSahAndEpoOnTheRotatedAtrium) {
    const std::vector<Triangle> tris = rotatedAtrium();
    BuildOptions options;
    const Blas plain = buildBlas(tris, options);
    const double plainEpo = computeEpo(plain, tris);
    for (float split : {0.3f, 1.0f}) {
        options.splitFactor = split;
        const Blas split_ = buildBlas(tris, options);
        const double epo = computeEpo(split_, tris);
        std::cout << "[ rotated atrium ] split " << split << ": SAH " << plain.stats.sah << " -> " << split_.stats.sah
                  << ", EPO " << plainEpo << " -> " << epo << ", fragments " << split_.stats.fragmentCount
                  << " -> references " << split_.stats.referenceCount << " (" << tris.size() << " triangles)\n";
        EXPECT_LT(split_.stats.sah, plain.stats.sah) << "split factor " << split;
        EXPECT_LT(epo, plainEpo) << "split factor " << split;
    }
}

TEST(BvhBuild, SahTerminationMakesSmallerLeavesThanTheBound) {
    // A leaf is kept only when no split beats it: with maxLeafSize 8 most bunny leaves are far below 8.
    const Blas blas = buildBlas(bunny());
    double mean = double(blas.stats.referenceCount) / blas.stats.leafCount;
    EXPECT_LT(mean, 8.0);
    EXPECT_GT(mean, 1.0);
}

TEST(BvhBuild, StackSizeOptimisationLowersTheRequiredStack) {
    const std::vector<Triangle>& tris = bunny();
    BuildOptions options;
    const Blas plain = buildBlas(tris, options);
    options.optimizeStackSize = true;
    options.stackSizeThreshold = plain.stats.requiredStackSize;  // force at least one round
    options.stackSahBudget = 0.02f;
    const Blas optimised = buildBlas(tris, options);
    EXPECT_GT(optimised.stats.collapsedPairs, 0u);
    EXPECT_LT(optimised.stats.requiredStackSize, plain.stats.requiredStackSize);
    EXPECT_LE(optimised.stats.sah, plain.stats.sah * 1.02f);
    EXPECT_TRUE(checkBlas(optimised, tris, ~0u, false));
    EXPECT_EQ(optimised.stats.requiredStackSize, requiredStackSize(optimised.nodes));
    // Default threshold 16 and budget 0.097%: never raises the SAH beyond the budget.
    BuildOptions defaults;
    defaults.optimizeStackSize = true;
    const Blas small = buildBlas(tris, defaults);
    EXPECT_LE(small.stats.sah, plain.stats.sah * (1.0f + defaults.stackSahBudget) + 1e-4f);
}

TEST(BvhBuild, StackSizeAndDepthOnHandBuiltTrees) {
    // root -> (inner A, inner B), A -> (leaf, leaf), B -> (inner C, leaf), C -> (leaf, leaf)
    std::vector<Node> nodes(9);
    auto inner = [&](uint32_t i, uint32_t child) { nodes[i].count = 0, nodes[i].first = child; };
    auto leaf = [&](uint32_t i) { nodes[i].count = 1, nodes[i].first = 0; };
    inner(0, 1);
    inner(1, 3);
    inner(2, 5);
    leaf(3);
    leaf(4);
    inner(5, 7);
    leaf(6);
    leaf(7);
    leaf(8);
    EXPECT_EQ(requiredStackSize(nodes), 1u);  // only the root has two inner children
    EXPECT_EQ(maxDepth(nodes), 3u);
    std::vector<Node> lone(1);
    lone[0].count = 3;
    EXPECT_EQ(requiredStackSize(lone), 0u);
    EXPECT_EQ(maxDepth(lone), 0u);
}

TEST(BvhBuild, SahFollowsTheReadmeFormula) {
    // Root box 1x1x1 (half area 3), children half area 1.5 each holding 2 and 3 triangles:
    // 1.0 * 3/3 + 1.1 * 2 * 1.5/3 + 1.1 * 3 * 1.5/3 = 1 + 1.1 + 1.65.
    std::vector<Node> nodes(3);
    nodes[0].setBox({{0, 0, 0}, {1, 1, 1}});
    nodes[0].first = 1;
    nodes[1].setBox({{0, 0, 0}, {1, 1, 0.25f}});  // 1 + 0.25 + 0.25 = 1.5
    nodes[1].count = 2;
    nodes[2].setBox({{0, 0, 0.75f}, {1, 1, 1}});
    nodes[2].count = 3;
    EXPECT_NEAR(computeSah(nodes), 1.0 + 1.1 + 1.65, 1e-6);
    EXPECT_NEAR(computeSah(nodes, 2.0f), 1.0 + 2.0 + 3.0, 1e-6);
}

TEST(BvhBuild, RadixSortMatchesStableSort) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> f(-1e6f, 1e6f);
    std::vector<float> values(50000);
    for (float& v : values) v = (rng() % 4 == 0) ? float(int(f(rng)) % 7) : f(rng);  // many ties
    values[0] = -0.0f;
    values[1] = 0.0f;
    values[2] = -kInfinity;
    values[3] = kInfinity;
    std::vector<uint32_t> keys(values.size());
    for (size_t i = 0; i < values.size(); ++i) keys[i] = sortableFloatKey(values[i]);
    std::vector<uint32_t> order(values.size());
    radixSortIndices(keys, order);
    std::vector<uint32_t> expected(values.size());
    std::iota(expected.begin(), expected.end(), 0u);
    std::stable_sort(expected.begin(), expected.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
    EXPECT_EQ(order, expected);
    for (size_t i = 1; i < order.size(); ++i) ASSERT_LE(values[order[i - 1]], values[order[i]]);
}

TEST(BvhBuild, SplitPlanesArePowerOfTwoCellsOfTheScene) {
    EXPECT_FLOAT_EQ(splitNodeSize(0.6f, 1.0f), 0.5f);
    EXPECT_FLOAT_EQ(splitNodeSize(0.3f, 1.0f), 0.25f);
    EXPECT_FLOAT_EQ(splitNodeSize(0.5f, 1.0f), 0.25f);  // not smaller than the extent: next level
    EXPECT_FLOAT_EQ(splitNodeSize(1.0f, 1.0f), 0.5f);
    EXPECT_FLOAT_EQ(splitNodeSize(30.0f, 80.0f), 20.0f);
    EXPECT_EQ(splitCount(1.0f, 100.0, 100, 0.3f), 1u);   // average priority, factor < 1: no split
    EXPECT_EQ(splitCount(50.0f, 100.0, 100, 0.3f), 16u);  // half of all priority: 1 + floor(50 * 0.3)
    EXPECT_EQ(splitCount(50.0f, 100.0, 100, 0.0f), 1u);
    // Priority: an axis-aligned right triangle in a 1 x 1 x 0 box: cbrt(1 * (2 - 0.5)).
    EXPECT_NEAR(splitPriority({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), std::cbrt(1.5f), 1e-6f);
}

TEST(BvhBuild, PresplitFragmentsCoverTheirTriangle) {
    // Every point of every triangle must lie in some fragment box of that triangle.
    const std::vector<Triangle> tris = rotatedAtrium();
    std::vector<uint32_t> ids(tris.size());
    std::iota(ids.begin(), ids.end(), 0u);
    const Fragments f = preSplit(tris, ids, 1.0f);
    EXPECT_GT(f.boxes.size(), tris.size());
    std::vector<std::vector<Box>> boxesOf(tris.size());
    for (size_t i = 0; i < f.boxes.size(); ++i) {
        ASSERT_FALSE(f.boxes[i].isEmpty());
        ASSERT_TRUE(tris[f.triangleIds[i]].box().contains(f.boxes[i]));
        boxesOf[f.triangleIds[i]].push_back(f.boxes[i]);
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    uint32_t uncovered = 0;
    for (uint32_t t = 0; t < tris.size(); ++t) {
        if (boxesOf[t].size() < 2) continue;
        for (int s = 0; s < 64; ++s) {
            float a = u(rng), b = u(rng);
            if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
            if (s == 0) a = 0.0f, b = 0.0f;  // the vertices too
            if (s == 1) a = 1.0f, b = 0.0f;
            if (s == 2) a = 0.0f, b = 1.0f;
            const glm::vec3 p = tris[t].v0 + a * (tris[t].v1 - tris[t].v0) + b * (tris[t].v2 - tris[t].v0);
            Box point{p, p};
            const bool covered = std::any_of(boxesOf[t].begin(), boxesOf[t].end(), [&](const Box& box) {
                Box grown = box;  // the sample point itself is rounded: allow a relative 1e-6
                const glm::vec3 slack = glm::max(glm::abs(box.min), glm::abs(box.max)) * 1e-6f;
                grown.min -= slack;
                grown.max += slack;
                return grown.contains(point);
            });
            uncovered += covered ? 0 : 1;
        }
    }
    EXPECT_EQ(uncovered, 0u);
}

TEST(BvhBuild, SplitTriangleGivesBothSidesExactly) {
    const Triangle tri{{0, 0, 0}, {4, 0, 0}, {0, 2, 0}};
    Box left, right;
    splitTriangle(tri, 0, 1.0f, tri.box(), left, right);
    EXPECT_FLOAT_EQ(left.min.x, 0.0f);
    EXPECT_FLOAT_EQ(left.max.x, 1.0f);
    EXPECT_NEAR(left.max.y, 2.0f, 1e-5f);
    EXPECT_FLOAT_EQ(right.min.x, 1.0f);
    EXPECT_FLOAT_EQ(right.max.x, 4.0f);
    EXPECT_NEAR(right.max.y, 1.5f, 1e-5f);  // the hypotenuse at x = 1 is at y = 1.5
    EXPECT_GE(right.max.y, 1.5f);           // padded outwards, never inwards
    splitTriangle(tri, 0, 1.0f, Box{{2, -1, -1}, {5, 5, 1}}, left, right);  // clipped to the parent
    EXPECT_TRUE(left.isEmpty());
    EXPECT_FLOAT_EQ(right.min.x, 2.0f);
}

TEST(BvhBuild, ClippedTriangleArea) {
    const Triangle tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};  // area 2
    EXPECT_NEAR(clippedTriangleArea(tri, {{-1, -1, -1}, {3, 3, 1}}), 2.0, 1e-12);
    EXPECT_NEAR(clippedTriangleArea(tri, {{0, 0, -1}, {1, 1, 1}}), 1.0, 1e-12);   // unit square fully inside
    EXPECT_NEAR(clippedTriangleArea(tri, {{1, 0, -1}, {3, 3, 1}}), 0.5, 1e-12);   // the corner x >= 1
    EXPECT_NEAR(clippedTriangleArea(tri, {{5, 5, 5}, {6, 6, 6}}), 0.0, 1e-12);
    EXPECT_NEAR(clippedTriangleArea(tri, {{0, 0, 0.5f}, {2, 2, 1}}), 0.0, 1e-12);  // plane z=0 outside
}

TEST(BvhBuild, EpoCountsForeignAreaInsideNodeBoxes) {
    // Disjoint boxes give EPO 0; a big plane through the (tilted, so not flat) boxes of small triangles gives > 0.
    std::vector<Triangle> apart{{{0, 0, 0}, {1, 0, 1}, {0, 1, 0.5f}}, {{5, 0, 0}, {6, 0, 1}, {5, 1, 0.5f}}};
    EXPECT_NEAR(computeEpo(buildBlas(apart), apart), 0.0, 1e-12);
    std::vector<Triangle> overlapping = apart;
    overlapping.push_back({{-1, 0.25f, -1}, {7, 0.25f, -1}, {3, 0.25f, 8}});  // the plane y = 0.25 through both
    const Blas blas = buildBlas(overlapping, BuildOptions{.maxLeafSize = 1});
    EXPECT_GT(computeEpo(blas, overlapping), 0.0);
    // Deterministic across thread counts (ordered chunk sums).
    EXPECT_EQ(computeEpo(buildBlas(bunny()), bunny(), kTriangleCost, 1),
              computeEpo(buildBlas(bunny()), bunny(), kTriangleCost, 2));
}

TEST(BvhBuild, RawLoaderChecksItsInput) {
    EXPECT_EQ(bunny().size(), 69630u);
    auto parse = [](std::vector<uint8_t> bytes) {
        return parseRawTriangles(std::as_bytes(std::span<const uint8_t>(bytes)), "mesh.bin");
    };
    EXPECT_TRUE(parse({0, 0, 0, 0}).empty());
    std::vector<uint8_t> one(4 + 48, 0);
    one[0] = 1;
    one[4] = 0x00, one[5] = 0x00, one[6] = 0x80, one[7] = 0x3f;  // v0.x = 1.0f
    ASSERT_EQ(parse(one).size(), 1u);
    EXPECT_EQ(parse(one)[0].v0.x, 1.0f);
    auto message = [&](std::vector<uint8_t> bytes) -> std::string {
        try {
            parse(std::move(bytes));
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(message({1, 0}).find("mesh.bin"), std::string::npos);                      // too short
    EXPECT_NE(message({0xff, 0xff, 0xff, 0xff}).find("negative"), std::string::npos);    // -1 triangles
    std::vector<uint8_t> truncated = one;
    truncated.pop_back();
    EXPECT_NE(message(truncated).find("mesh.bin"), std::string::npos);
    std::vector<uint8_t> trailing = one;
    trailing.push_back(0);
    EXPECT_NE(message(trailing).find("mesh.bin"), std::string::npos);
    std::vector<uint8_t> huge{0xff, 0xff, 0xff, 0x7f};  // 2^31 - 1 triangles in 4 bytes
    EXPECT_NE(message(huge).find("mesh.bin"), std::string::npos);
    EXPECT_THROW(loadRawTriangles("/nonexistent/dir/mesh.bin"), std::runtime_error);
}

TEST(BvhBuild, NonFiniteTrianglesAreSkipped) {
    std::vector<Triangle> tris = makeRandomTriangles(100, 9);
    tris[10].v1.y = std::nanf("");
    tris[20].v2.z = kInfinity;
    const Blas blas = buildBlas(tris);
    EXPECT_EQ(blas.stats.skippedTriangles, 2u);
    EXPECT_TRUE(checkBlas(blas, tris, 8, false));
}

TEST(BvhBuild, BunnyNumbers) {
    // Printed for the report and BENCHMARKS.md; nothing here is asserted beyond sanity.
    const std::vector<Triangle>& tris = bunny();
    for (float split : {0.0f, 0.3f, 1.0f}) {
        BuildOptions options;
        options.splitFactor = split;
        const Blas blas = buildBlas(tris, options);
        const double epo = computeEpo(blas, tris);
        std::cout << "[ bunny ] split " << split << ": triangles " << tris.size() << ", fragments "
                  << blas.stats.fragmentCount << ", references " << blas.stats.referenceCount << ", nodes "
                  << blas.stats.nodeCount << ", SAH " << blas.stats.sah << ", EPO " << epo << ", depth "
                  << blas.stats.maxDepth << ", stack " << blas.stats.requiredStackSize << ", build "
                  << blas.stats.buildMs << " ms (pre-split " << blas.stats.presplitMs << " ms)\n";
        EXPECT_GT(blas.stats.sah, 0.0f);
        EXPECT_GE(epo, 0.0);
    }
}

}  // namespace
}  // namespace idk::bvh
