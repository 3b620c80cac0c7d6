// bvh_sbvh_test.cpp: the spatial-split builder (engine/bvh/sbvh.hpp): every structural invariant, leaf boxes that
// cover every point of their triangles, the reference budget, the same tree for 1, 2 and 4 threads, hits equal to
// brute force, no leaks through shared edges and vertices of closed meshes, a lower SAH than SweepSAH on the rotated
// atrium, the SweepSAH tree again when the budget allows no spatial split, and the exact clipped triangle box.
#include "bvh_test_util.hpp"

#include "bvh/procedural.hpp"

#include <cstring>
#include <iostream>

namespace idk::bvh {
namespace {

using test::bunny;
using test::checkBlas;

std::vector<Triangle> rotatedAtrium() {
    IndexedMesh mesh = makeAtrium();
    rotateAboutCenter(mesh, 45.0f);
    return mesh.triangles();
}

BuildOptions spatial(float budget = 2.0f, float splitFactor = 0.0f) {
    BuildOptions options;
    options.spatialSplits = true;
    options.splitBudget = budget;
    options.splitFactor = splitFactor;
    return options;
}

// Every sampled point of every triangle (vertices included) lies in some leaf box that references the triangle.
uint32_t uncoveredPoints(const Blas& blas, const std::vector<Triangle>& tris, uint32_t samples) {
    std::vector<std::vector<Box>> boxesOf(tris.size());
    for (const Node& n : blas.nodes) {
        if (!n.isLeaf()) continue;
        for (uint32_t k = n.first; k < n.first + n.count; ++k) boxesOf[blas.triIds[k]].push_back(n.box());
    }
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    uint32_t uncovered = 0;
    for (uint32_t t = 0; t < tris.size(); ++t) {
        for (uint32_t s = 0; s < samples; ++s) {
            float a = u(rng), b = u(rng);
            if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
            if (s < 3) a = s == 1 ? 1.0f : 0.0f, b = s == 2 ? 1.0f : 0.0f;  // the three vertices exactly
            const glm::vec3 p = tris[t].v0 + a * (tris[t].v1 - tris[t].v0) + b * (tris[t].v2 - tris[t].v0);
            const bool covered = std::any_of(boxesOf[t].begin(), boxesOf[t].end(), [&](const Box& box) {
                Box grown = box;  // the sample point itself is rounded: allow a relative 1e-6
                const glm::vec3 slack = glm::max(glm::abs(box.min), glm::abs(box.max)) * 1e-6f;
                grown.min -= slack;
                grown.max += slack;
                return grown.contains(Box{p, p});
            });
            uncovered += covered ? 0 : 1;
        }
    }
    return uncovered;
}

TEST(BvhSpatial, KeepsEveryInvariantAndCoversEveryTriangle) {
    const std::vector<Triangle> rotated = rotatedAtrium();
    const std::vector<Triangle> atrium = makeAtrium().triangles();
    const std::vector<Triangle> soup = makeRandomTriangles(3000, 11);
    for (const std::vector<Triangle>* tris : {&bunny(), &atrium, &rotated, &soup}) {
        for (float split : {0.0f, 0.3f}) {
            if (split > 0.0f && tris != &rotated) continue;  // spatial splits over pre-split fragments: one scene
            const BuildOptions options = spatial(2.0f, split);
            const Blas blas = buildBlas(*tris, options);
            // presplit = true: a triangle may be referenced by several leaves, each box holding a part of it.
            EXPECT_TRUE(checkBlas(blas, *tris, options.maxLeafSize, true)) << tris->size() << ", split " << split;
            for (const Node& n : blas.nodes) {
                if (n.isLeaf()) {
                    ASSERT_LE(n.count, options.maxLeafSize);
                }
            }
            EXPECT_LE(blas.stats.referenceCount, uint32_t(2.0 * blas.stats.fragmentCount));
            EXPECT_EQ(uncoveredPoints(blas, *tris, 16), 0u) << tris->size() << ", split " << split;
        }
    }
    const Blas blas = buildBlas(rotated, spatial());
    EXPECT_GT(blas.stats.spatialSplits, 0u);
    EXPECT_GT(blas.stats.referenceCount, rotated.size());  // chopped triangles sit in several leaves
}

TEST(BvhSpatial, TinyAndDegenerateInputs) {
    for (uint32_t count : {1u, 2u, 3u, 17u}) {
        const std::vector<Triangle> tris = makeRandomTriangles(count, 5 + count);
        for (uint32_t leaf : {1u, 8u}) {
            BuildOptions options = spatial();
            options.maxLeafSize = leaf;
            EXPECT_TRUE(checkBlas(buildBlas(tris, options), tris, leaf, true)) << count << " triangles";
        }
    }
    // Zero-area triangles (points and segments) and 20 copies of one triangle.
    std::vector<Triangle> odd;
    for (int i = 0; i < 40; ++i) {
        const glm::vec3 p(float(i), 0.5f * float(i), 0.0f);
        odd.push_back({p, p, p});
        odd.push_back({p, p + glm::vec3(3.0f, 1.0f, 2.0f), p + glm::vec3(6.0f, 2.0f, 4.0f)});
    }
    for (int i = 0; i < 20; ++i) odd.push_back({{0, 0, 0}, {50, 0, 0}, {0, 50, 50}});
    // A triangle far larger than the rest: chopped references whose vertices lie far outside their nodes.
    odd.push_back({{-1.0e30f, -1.0e30f, 1.0f}, {1.0e30f, -1.0e30f, 2.0f}, {0.0f, 1.0e30f, 3.0f}});
    const Blas blas = buildBlas(odd, spatial());
    EXPECT_TRUE(checkBlas(blas, odd, 8, true));
    EXPECT_EQ(uncoveredPoints(blas, odd, 16), 0u);
    EXPECT_TRUE(buildBlas(std::vector<Triangle>{}, spatial()).nodes.empty());
}

TEST(BvhSpatial, SameTreeForOneTwoAndFourThreads) {
    const std::vector<Triangle> rotated = rotatedAtrium();
    const std::vector<Triangle> soup = makeRandomTriangles(20000, 13);
    for (const std::vector<Triangle>* tris : {&soup, &rotated}) {
        BuildOptions options = spatial();
        options.parallelThreshold = 64;  // fork subtrees early and often
        options.threadCount = 1;
        const Blas one = buildBlas(*tris, options);
        for (uint32_t threads : {2u, 4u}) {
            options.threadCount = threads;
            const Blas other = buildBlas(*tris, options);
            EXPECT_TRUE(one.nodes.size() == other.nodes.size() && one.triIds == other.triIds &&
                        std::memcmp(one.nodes.data(), other.nodes.data(), one.nodes.size() * sizeof(Node)) == 0)
                << threads << " threads";
        }
    }
}

TEST(BvhSpatial, LowerSahThanSweepSahOnTheRotatedAtrium) {
    const std::vector<Triangle> tris = rotatedAtrium();
    const Blas sweep = buildBlas(tris);
    const Blas presplit = buildBlas(tris, BuildOptions{.splitFactor = 1.0f});
    const Blas sbvh = buildBlas(tris, spatial());
    std::cout << "[ rotated atrium ] SAH sweep " << sweep.stats.sah << ", pre-split 1.0 " << presplit.stats.sah
              << ", spatial (budget 2) " << sbvh.stats.sah << " with " << sbvh.stats.spatialSplits
              << " spatial splits, " << sbvh.stats.referenceCount << " references (" << tris.size()
              << " triangles)\n";
    EXPECT_LT(sbvh.stats.sah, sweep.stats.sah);
    EXPECT_LT(sbvh.stats.sah, presplit.stats.sah);
    EXPECT_FLOAT_EQ(sbvh.stats.sah, computeSah(sbvh.nodes));
}

TEST(BvhSpatial, NoBudgetGivesTheSweepSahTree) {
    // Budget 1: no reference may be added, so the builder is the full SAH sweep of box_tree.cpp (its areas are
    // summed in another order, hence the tolerance rather than equality).
    const Blas sweep = buildBlas(bunny());
    const Blas noSplits = buildBlas(bunny(), spatial(1.0f));
    EXPECT_EQ(noSplits.stats.spatialSplits, 0u);
    EXPECT_EQ(noSplits.stats.referenceCount, bunny().size());
    EXPECT_TRUE(test::relativeClose(noSplits.stats.sah, sweep.stats.sah, 1e-3f))
        << noSplits.stats.sah << " vs " << sweep.stats.sah;
}

TEST(BvhSpatial, HitsEqualBruteForce) {
    const std::vector<Triangle> rotated = rotatedAtrium();
    for (const std::vector<Triangle>* tris : {&bunny(), &rotated}) {
        const std::vector<Ray> rays = test::randomRays(test::boundsOf(*tris), 800, 4);
        std::vector<Hit> expected;
        for (const Ray& ray : rays) expected.push_back(closestHitBruteForce(*tris, ray));
        for (float split : {0.0f, 1.0f}) {
            const Blas blas = buildBlas(*tris, spatial(2.0f, split));
            uint32_t mismatches = 0, hits = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                const Hit a = closestHit(blas, rays[i]);
                const Hit& b = expected[i];
                hits += a.hit() ? 1 : 0;
                mismatches += (a.triangleId != b.triangleId || a.t != b.t || anyHit(blas, rays[i]) != b.hit()) ? 1 : 0;
            }
            EXPECT_EQ(mismatches, 0u) << tris->size() << " triangles, split " << split;
            EXPECT_GT(hits, 150u);
        }
    }
}

// Rays from inside closed meshes aimed exactly at vertices and at points on shared edges must all hit.
TEST(BvhSpatial, NoLeaksThroughEdgesAndVertices) {
    // Long thin boxes rotated 30 degrees on each axis: their long diagonal triangles overlap and get chopped; one of
    // them 1e6 units from the origin. The icosphere has vertices shared by five and six triangles.
    const glm::vec3 far(1.0e6f, -1.0e6f, 1.0e6f);
    const glm::vec3 half(400.0f, 10.0f, 10.0f);
    struct Case {
        IndexedMesh mesh;
        glm::vec3 center;
        bool chopped;  // spatial splits expected
    };
    Case cases[] = {
        {makeIcosphere(2, 1.0f), glm::vec3(0.0f), false},
        {makeBox(-half, half, 3), glm::vec3(0.0f), true},
        {makeBox(far - half, far + half, 3), far, true},
    };
    for (auto& [mesh, center, chopped] : cases) {
        rotateAboutCenter(mesh, 30.0f);
        const std::vector<Triangle> tris = mesh.triangles();
        BuildOptions options = spatial(3.0f);
        options.maxLeafSize = 1;  // deep trees of small meshes: their nodes overlap enough for spatial splits
        const Blas blas = buildBlas(tris, options);
        std::vector<std::pair<uint32_t, uint32_t>> edges;
        for (const glm::uvec3& f : mesh.indices) {
            for (int e = 0; e < 3; ++e) edges.emplace_back(f[e], f[(e + 1) % 3]);
        }
        std::mt19937 rng(41);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        uint32_t leaks = 0;
        for (uint32_t i = 0; i < 200000; ++i) {
            glm::vec3 target = mesh.positions[rng() % mesh.positions.size()];
            if (i % 4 != 0) {
                const auto [a, b] = edges[rng() % edges.size()];
                target = mesh.positions[a] + u(rng) * (mesh.positions[b] - mesh.positions[a]);
            }
            leaks += closestHit(blas, Ray{center, target - center}).hit() ? 0 : 1;
        }
        EXPECT_EQ(leaks, 0u) << "center " << center.x;
        if (chopped) {
            EXPECT_GT(blas.stats.spatialSplits, 0u) << "center " << center.x;  // chopped references were traversed
        }
    }
}

TEST(BvhSpatial, ClippedTriangleBoxIsTheExactPart) {
    const Triangle tri{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
    // The part with x in [1, 2] and y >= 1: vertices (1, 1), (2, 1), (2, 2), (1, 3): box [1, 2] x [1, 3].
    const Box part = clippedTriangleBox(tri, Box{{1, 1, -1}, {2, 10, 1}});
    EXPECT_NEAR(part.min.x, 1.0f, 1e-6f);
    EXPECT_NEAR(part.max.x, 2.0f, 1e-6f);
    EXPECT_NEAR(part.min.y, 1.0f, 1e-6f);
    EXPECT_NEAR(part.max.y, 3.0f, 1e-6f);
    for (const glm::vec3 corner : {glm::vec3(1, 1, 0), glm::vec3(2, 1, 0), glm::vec3(2, 2, 0), glm::vec3(1, 3, 0)}) {
        EXPECT_TRUE(part.contains(Box{corner, corner}));
    }
    // Tighter than the triangle's box clipped to the box: in x [2.5, 3.5] the triangle only reaches y = 1.5.
    const Box slab = clippedTriangleBox(tri, Box{{2.5f, 0, -1}, {3.5f, 4, 1}});
    EXPECT_NEAR(slab.max.y, 1.5f, 1e-6f);
    EXPECT_GE(slab.max.y, 1.5f);
    EXPECT_TRUE(clippedTriangleBox(tri, Box{{3, 3, -1}, {5, 5, 1}}).isEmpty());  // beyond the hypotenuse
    EXPECT_EQ(clippedTriangleBox(tri, Box{{-1, -1, -1}, {9, 9, 1}}), tri.box());  // whole triangle inside
    // A segment (zero-area triangle) still has a box.
    const Triangle segment{{0, 0, 0}, {4, 4, 4}, {2, 2, 2}};
    const Box s = clippedTriangleBox(segment, Box{{1, 1, 1}, {3, 3, 3}});
    EXPECT_FALSE(s.isEmpty());
    EXPECT_NEAR(s.min.x, 1.0f, 1e-6f);
    EXPECT_NEAR(s.max.z, 3.0f, 1e-6f);
}

}  // namespace
}  // namespace idk::bvh
