// bvh_wide8_test.cpp: the 8-wide compressed BVH (engine/bvh/wide8.hpp): every decoded child box contains the
// binary child box it stands for (checked on every slot of every node), the leaves keep exactly the binary leaves'
// triangle references, the stack bound holds, and the wide walk returns the binary walk's hits (same triangle,
// bit-identical t; same any-hit answer) on the bunny, the rotated pre-split atrium and hard cases; re-quantising after a
// refit (fixed topology) equals a conversion from scratch where the topology cannot differ, and stays exact.
#include "bvh/flatten.hpp"
#include "bvh/procedural.hpp"
#include "bvh/refit.hpp"
#include "bvh/wide8.hpp"
#include "bvh_test_util.hpp"

#include <cstring>

namespace idk::bvh {
namespace {

IndexedMesh fromTriangles(const std::vector<Triangle>& tris) {
    IndexedMesh m;
    for (uint32_t t = 0; t < tris.size(); ++t) {
        m.positions.insert(m.positions.end(), {tris[t].v0, tris[t].v1, tris[t].v2});
        m.indices.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    return m;
}

struct Scene {
    IndexedMesh mesh;
    Blas blas;
    std::vector<gpu::GpuBlasNode> nodes;
    std::vector<gpu::GpuBlasTriangle> refs;
    Bvh8 wide;

    Scene(IndexedMesh m, const BuildOptions& options) : mesh(std::move(m)), blas(buildBlas(mesh.triangles(), options)) {
        nodes = flatten(blas);
        refs = flattenTriangles(blas, mesh.indices);
        wide = buildBvh8(nodes, refs);
    }
};

// Every used slot's decoded box contains its binary node's box; every binary leaf reference appears once.
void expectWellFormed(const Scene& s, const std::string& what) {
    uint64_t slots = 0, notContained = 0;
    std::vector<uint32_t> wideRefs, binaryRefs;
    for (size_t w = 0; w < s.wide.nodes.size(); ++w) {
        const gpu::GpuWideNode& node = s.wide.nodes[w];
        for (uint32_t i = 0; i < gpu::kWideArity; ++i) {
            const uint32_t source = s.wide.slotSources[w][i];
            const bool used = wideSlotInner(node, i) || wideSlotCount(node, i) > 0;
            ASSERT_EQ(used, source != kInvalidIndex) << what;
            if (!used) continue;
            ++slots;
            const gpu::GpuBlasNode& b = s.nodes[source];
            notContained += wideSlotBox(node, i).contains(Box{b.min, b.max}) ? 0 : 1;
            ASSERT_EQ(wideSlotCount(node, i), b.triCount) << what;
            for (uint32_t k = 0; k < b.triCount; ++k) binaryRefs.push_back(s.refs[b.triStartOrChild + k].triangleId);
        }
    }
    for (const gpu::GpuBlasTriangle& t : s.wide.triangles) wideRefs.push_back(t.triangleId);
    std::sort(wideRefs.begin(), wideRefs.end());
    std::sort(binaryRefs.begin(), binaryRefs.end());
    std::vector<uint32_t> allRefs;
    for (const gpu::GpuBlasTriangle& t : s.refs) allRefs.push_back(t.triangleId);
    std::sort(allRefs.begin(), allRefs.end());
    EXPECT_EQ(notContained, 0u) << what << ": " << slots << " slots";
    EXPECT_EQ(wideRefs, binaryRefs) << what;
    EXPECT_EQ(wideRefs, allRefs) << what;  // every reachable leaf became a slot
    std::printf("[ wide8 ] %s: %zu binary nodes -> %zu wide nodes (%.2f used slots each), depth %u, stack %u, "
                "%zu bytes vs %zu\n",
                what.c_str(), s.nodes.size(), s.wide.nodes.size(), double(slots) / double(s.wide.nodes.size()),
                s.wide.depth, s.wide.stackSize, s.wide.nodes.size() * sizeof(gpu::GpuWideNode),
                s.nodes.size() * sizeof(gpu::GpuBlasNode));
}

// Wide vs binary: same triangle, bit-identical t, u, v; same any-hit answer; no overflow with the bound.
uint32_t expectSameHits(const Scene& s, const std::vector<Ray>& rays, const std::string& what) {
    uint32_t hits = 0, mismatches = 0, anyMismatches = 0, overflows = 0;
    for (const Ray& r : rays) {
        bool overflowed = false;
        const Hit w = closestHitWide(s.wide, s.mesh.positions, r, 0, &overflowed);
        const Hit b = closestHit(s.blas, r);
        hits += b.hit() ? 1 : 0;
        overflows += overflowed ? 1 : 0;
        mismatches += (w.triangleId != b.triangleId || w.t != b.t || w.u != b.u || w.v != b.v) ? 1 : 0;
        anyMismatches += anyHitWide(s.wide, s.mesh.positions, r) != anyHit(s.blas, r) ? 1 : 0;
    }
    EXPECT_EQ(mismatches, 0u) << what;
    EXPECT_EQ(anyMismatches, 0u) << what;
    EXPECT_EQ(overflows, 0u) << what;
    return hits;
}

std::vector<Ray> vertexAimedRays(const IndexedMesh& mesh, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<size_t> pick(0, mesh.indices.size() - 1);
    const Box box = test::boundsOf(mesh.triangles());
    const glm::vec3 center = 0.5f * (box.min + box.max);
    std::vector<Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::uvec3 t = mesh.indices[pick(rng)];
        const glm::vec3 target = i % 2 == 0 ? mesh.positions[t.x] : 0.5f * (mesh.positions[t.y] + mesh.positions[t.z]);
        const glm::vec3 origin = center + glm::length(box.extent()) * test::randomUnitVector(rng);
        rays[i] = {origin, target - origin};
    }
    return rays;
}

TEST(BvhWide8, BunnyBoxesContainTheBinaryBoxesAndHitsMatch) {
    const Scene s(fromTriangles(test::bunny()), {});
    expectWellFormed(s, "bunny");
    EXPECT_LT(s.wide.nodes.size(), s.nodes.size() / 4);
    std::vector<Ray> rays = test::randomRays(s.blas.bounds(), 20000, 81);
    const std::vector<Ray> aimed = vertexAimedRays(s.mesh, 20000, 82);
    rays.insert(rays.end(), aimed.begin(), aimed.end());
    EXPECT_GT(expectSameHits(s, rays, "bunny"), 15000u);
}

TEST(BvhWide8, RotatedPresplitAtriumBoxesContainTheBinaryBoxesAndHitsMatch) {
    IndexedMesh atrium = makeAtrium();
    rotateAboutCenter(atrium, 45.0f);
    const Scene s(atrium, BuildOptions{.splitFactor = 0.3f});
    expectWellFormed(s, "rotated atrium, split 0.3");
    EXPECT_GT(expectSameHits(s, test::randomRays(s.blas.bounds(), 30000, 83), "rotated atrium"), 10000u);
    // Stack-size optimisation: collapsed leaves hold more than maxLeafSize references.
    const Scene collapsed(makeAtrium(), BuildOptions{.optimizeStackSize = true, .stackSizeThreshold = 8});
    expectWellFormed(collapsed, "atrium, stack-size optimised");
    expectSameHits(collapsed, test::randomRays(collapsed.blas.bounds(), 10000, 84), "atrium, stack-size optimised");
}

TEST(BvhWide8, HardCases) {
    // Far from the origin (fp32 spacing 0.0625 there: decoding rounds), degenerate and scene-spanning triangles,
    // a single triangle (one-leaf root) and an empty mesh.
    IndexedMesh far = fromTriangles(test::bunny());
    for (glm::vec3& p : far.positions) p = p * 100.0f + glm::vec3(1.0e6f, -1.0e6f, 1.0e6f);
    const Scene offset(far, {});
    expectWellFormed(offset, "bunny at 1e6");
    EXPECT_GT(expectSameHits(offset, vertexAimedRays(far, 20000, 85), "bunny at 1e6"), 15000u);

    IndexedMesh mixed = fromTriangles(test::bunny());
    const uint32_t base = uint32_t(mixed.positions.size());
    mixed.positions.insert(mixed.positions.end(), {{-1, -1, -1}, {1, 1, 1}, {0, 0, 0}, {5, 5, 5}, {-5, 0.1f, -5},
                                                   {5, 0.1f, -5}, {0, 0.1f, 8}});
    mixed.indices.insert(mixed.indices.end(), {{base, base + 1, base + 2}, {base + 3, base + 3, base + 3},
                                               {base + 4, base + 5, base + 6}});
    const Scene degenerate(mixed, {});
    expectWellFormed(degenerate, "bunny with degenerate and huge triangles");
    expectSameHits(degenerate, test::randomRays(degenerate.blas.bounds(), 20000, 86), "degenerate");

    const Scene single(IndexedMesh{{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}}}, {});
    EXPECT_EQ(single.wide.nodes.size(), 1u);
    EXPECT_GT(expectSameHits(single, test::randomRays(Box{glm::vec3(-2), glm::vec3(2)}, 5000, 87), "single"), 100u);
    const Scene empty(IndexedMesh{}, {});
    EXPECT_EQ(empty.wide.nodes.size(), 1u);
    EXPECT_EQ(expectSameHits(empty, test::randomRays(Box{glm::vec3(-2), glm::vec3(2)}, 1000, 88), "empty"), 0u);
}

TEST(BvhWide8, SmallStackFlagsOverflowAndUnflaggedRaysAreExact) {
    const Scene s(fromTriangles(test::bunny()), {});
    ASSERT_GT(s.wide.stackSize, 2u);
    uint32_t overflows = 0, wrong = 0;
    for (const Ray& r : test::randomRays(s.blas.bounds(), 5000, 89)) {
        bool overflowed = false;
        const Hit w = closestHitWide(s.wide, s.mesh.positions, r, 1, &overflowed);
        if (overflowed) {
            ++overflows;
            continue;
        }
        const Hit b = closestHit(s.blas, r);
        wrong += (w.triangleId != b.triangleId || w.t != b.t) ? 1 : 0;
    }
    EXPECT_GT(overflows, 0u);
    EXPECT_EQ(wrong, 0u);
}

bool sameNodes(const std::vector<gpu::GpuWideNode>& a, const std::vector<gpu::GpuWideNode>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::GpuWideNode)) == 0;
}

TEST(BvhWide8, RefitEqualsConversionFromScratchOfTheRefittedBinary) {
    // Scaling every vertex by 2 is exact and scales every area by 4: the greedy collapse picks the same slots, so
    // re-quantising with fixed topology must give the from-scratch conversion bit for bit.
    Scene s(fromTriangles(test::bunny()), {});
    for (glm::vec3& p : s.mesh.positions) p *= 2.0f;
    refitBlas(s.blas, s.mesh.triangles());
    s.nodes = flatten(s.blas);
    Bvh8 refitted = s.wide;
    refitBvh8(refitted, s.nodes);
    const Bvh8 scratch = buildBvh8(s.nodes, s.refs);
    EXPECT_FALSE(sameNodes(refitted.nodes, Scene(fromTriangles(test::bunny()), {}).wide.nodes));  // boxes changed
    EXPECT_TRUE(sameNodes(refitted.nodes, scratch.nodes));
    EXPECT_EQ(refitted.slotSources, scratch.slotSources);
}

TEST(BvhWide8, RefitAfterDeformationTracesTheRefittedBinary) {
    Scene s(fromTriangles(test::bunny()), {});
    for (glm::vec3& p : s.mesh.positions) p += 0.01f * glm::vec3(std::sin(40.0f * p.y), std::cos(30.0f * p.x), 0.0f);
    refitBlas(s.blas, s.mesh.triangles());
    s.nodes = flatten(s.blas);
    refitBvh8(s.wide, s.nodes);
    expectWellFormed(s, "bunny after refit");
    EXPECT_GT(expectSameHits(s, test::randomRays(s.blas.bounds(), 10000, 90), "bunny after refit"), 3000u);
    EXPECT_THROW(refitBvh8(s.wide, std::span(s.nodes).first(100)), std::invalid_argument);
}

TEST(BvhWide8, MalformedInputIsRejected) {
    const Scene s(fromTriangles(test::bunny()), {});
    std::vector<gpu::GpuBlasNode> nodes = s.nodes;
    EXPECT_THROW(buildBvh8(std::span(nodes).first(2), s.refs), std::invalid_argument);
    EXPECT_THROW(buildBvh8(nodes, std::span(s.refs).first(10)), std::invalid_argument);  // leaf ranges out of bounds
    nodes[2].triStartOrChild = uint32_t(nodes.size());
    nodes[2].triCount = 0;
    EXPECT_THROW(buildBvh8(nodes, s.refs), std::invalid_argument);  // child index out of bounds
    std::vector<gpu::GpuBlasNode> big = s.nodes;
    for (gpu::GpuBlasNode& n : big) {
        if (n.triCount > 0) n.triCount = 300;  // a 9-bit count
    }
    EXPECT_THROW(buildBvh8(big, s.refs), std::invalid_argument);
}

}  // namespace
}  // namespace idk::bvh
