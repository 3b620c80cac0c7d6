// bvh_tlas_refit_test.cpp: the TLAS (against the per-instance BLAS oracle, rebuilt after moves, empty cases),
// the CPU refit (exact boxes after a deformation, identity refit, traversal after refit), and the GPU arrays of
// flatten() (layout rules, plus an emulation of the planned GLSL walk that must agree with the CPU traversal).
#include "bvh_test_util.hpp"

#include "bvh/flatten.hpp"
#include "bvh/procedural.hpp"
#include "bvh/refit.hpp"
#include "bvh/tlas.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace idk::bvh {
namespace {

using test::bunny;

struct World {
    std::vector<std::vector<Triangle>> meshes;
    std::vector<Blas> blases;
    std::vector<BlasInstance> instances;
};

World makeWorld(uint32_t seed) {
    World w;
    w.meshes.push_back(makeIcosphere(3, 1.0f).triangles());
    w.meshes.push_back(makeRandomTriangles(800, seed));
    w.meshes.push_back(makeBox(glm::vec3(-1.0f), glm::vec3(1.0f), 4).triangles());
    w.meshes.push_back({});  // an empty BLAS
    w.meshes.push_back(bunny());
    for (const auto& m : w.meshes) w.blases.push_back(buildBlas(m));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (uint32_t i = 0; i < 60; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1.0f), 20.0f * glm::vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, 6.28f * u(rng), test::randomUnitVector(rng));
        m = glm::scale(m, glm::vec3(0.5f + 2.0f * u(rng), 0.5f + 2.0f * u(rng), (i % 7 == 0 ? -1.0f : 1.0f) * (0.5f + u(rng))));
        w.instances.push_back({m, i % uint32_t(w.meshes.size())});
    }
    return w;
}

// Oracle: every instance's BLAS traversed with the same object-space ray, the best (t, instance, triangle) kept.
Hit tlasOracle(const World& w, const Tlas& tlas, const Ray& ray) {
    Hit best;
    for (uint32_t i = 0; i < w.instances.size(); ++i) {
        Ray local = ray;
        local.origin = glm::vec3(tlas.worldToObject[i] * glm::vec4(ray.origin, 1.0f));
        local.direction = glm::vec3(tlas.worldToObject[i] * glm::vec4(ray.direction, 0.0f));
        const Hit h = closestHit(w.blases[w.instances[i].blasIndex], local);
        if (h.hit() && (!best.hit() || h.t < best.t || (h.t == best.t && i < best.instanceId))) {
            best = h;
            best.instanceId = i;
        }
    }
    return best;
}

uint32_t tlasMismatches(const World& w, const Tlas& tlas, uint32_t rayCount, uint32_t seed, uint32_t* hitCount) {
    Box worldBox;
    for (const Box& b : tlas.worldBoxes) worldBox.grow(b);
    uint32_t mismatches = 0;
    *hitCount = 0;
    for (const Ray& ray : test::randomRays(worldBox, rayCount, seed)) {
        const Hit a = closestHit(tlas, w.instances, w.blases, ray);
        const Hit b = tlasOracle(w, tlas, ray);
        *hitCount += a.hit() ? 1 : 0;
        mismatches += (a.instanceId != b.instanceId || a.triangleId != b.triangleId || a.t != b.t) ? 1 : 0;
        mismatches += anyHit(tlas, w.instances, w.blases, ray) != b.hit() ? 1 : 0;
    }
    return mismatches;
}

TEST(BvhTlas, MatchesEveryInstanceTraversedAlone) {
    World w = makeWorld(71);
    const Tlas tlas = buildTlas(w.instances, w.blases);
    // Instances of the empty BLAS get no leaf; every other instance exactly one.
    uint32_t leaves = 0;
    for (const Node& n : tlas.nodes) leaves += n.isLeaf() ? n.count : 0;
    EXPECT_EQ(leaves, 60u - 12u);
    uint32_t hits = 0;
    EXPECT_EQ(tlasMismatches(w, tlas, 20000, 72, &hits), 0u);
    EXPECT_GT(hits, 2000u);

    // Instances move: rebuild and check again.
    for (BlasInstance& inst : w.instances) inst.objectToWorld = glm::translate(inst.objectToWorld, glm::vec3(0.3f, -0.2f, 0.1f));
    const Tlas moved = buildTlas(w.instances, w.blases);
    EXPECT_EQ(tlasMismatches(w, moved, 5000, 73, &hits), 0u);
    EXPECT_GT(hits, 500u);
}

TEST(BvhTlas, EmptyInputsHitNothing) {
    const std::vector<Blas> noBlases;
    const Tlas empty = buildTlas({}, noBlases);
    EXPECT_TRUE(empty.nodes.empty());
    const Ray ray{{0, 0, -5}, {0, 0, 1}};
    EXPECT_FALSE(closestHit(empty, {}, noBlases, ray).hit());
    std::vector<Blas> blases{buildBlas({})};
    const std::vector<BlasInstance> instances{{glm::mat4(1.0f), 0}};
    const Tlas onlyEmpty = buildTlas(instances, blases);
    EXPECT_FALSE(closestHit(onlyEmpty, instances, blases, ray).hit());
    EXPECT_FALSE(anyHit(onlyEmpty, instances, blases, ray));
    const std::vector<Triangle> one{{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}};
    blases.push_back(buildBlas(one));
    const std::vector<BlasInstance> two{{glm::mat4(1.0f), 0}, {glm::translate(glm::mat4(1.0f), {0, 0, 2}), 1}};
    const Tlas single = buildTlas(two, blases);
    const Hit h = closestHit(single, two, blases, ray);
    EXPECT_EQ(h.instanceId, 1u);
    EXPECT_FLOAT_EQ(h.t, 7.0f);
    const float nan = std::nanf("");
    EXPECT_FALSE(closestHit(single, two, blases, {{0, 0, -5}, {nan, 0, 1}}).hit());
}

TEST(BvhTlas, TransformedBoxHoldsTheTransformedCorners) {
    std::mt19937 rng(74);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1.0f), 1000.0f * glm::vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, 3.0f * u(rng), test::randomUnitVector(rng));
        m = glm::scale(m, glm::vec3(1.0f + u(rng), 2.0f + u(rng), -1.5f));
        const Box box{glm::vec3(u(rng), u(rng), u(rng)) - 2.0f, glm::vec3(u(rng), u(rng), u(rng)) + 2.0f};
        const Box world = transformBox(m, box);
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                                   (c & 4) ? box.max.z : box.min.z);
            const glm::vec3 p(m * glm::vec4(corner, 1.0f));
            ASSERT_TRUE(world.contains(Box{p, p}));
        }
    }
}

std::vector<Triangle> deformed(const std::vector<Triangle>& tris) {
    std::vector<Triangle> out = tris;
    for (Triangle& t : out) {
        for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) {  // a function of the position: shared vertices stay shared
            *v += 0.02f * glm::vec3(std::sin(40.0f * v->y), std::cos(30.0f * v->z), std::sin(50.0f * v->x));
        }
    }
    return out;
}

TEST(BvhRefit, BoxesAreExactAfterADeformation) {
    const std::vector<Triangle>& tris = bunny();
    Blas blas = buildBlas(tris);
    const std::vector<Triangle> moved = deformed(tris);
    refitBlas(blas, moved);
    for (size_t i = 0; i < blas.nodes.size(); ++i) {
        const Node& n = blas.nodes[i];
        Box expected;
        if (n.isLeaf()) {
            for (uint32_t k = n.first; k < n.first + n.count; ++k) expected.grow(moved[blas.triIds[k]].box());
        } else {
            expected = blas.nodes[n.first].box();
            expected.grow(blas.nodes[n.first + 1].box());
            ASSERT_TRUE(n.box().contains(blas.nodes[n.first].box()));
            ASSERT_TRUE(n.box().contains(blas.nodes[n.first + 1].box()));
        }
        ASSERT_EQ(n.box(), expected) << "node " << i;  // the leaf boxes a rebuild of this topology would have
    }
    EXPECT_TRUE(test::checkBlas(blas, moved, 8, false));
    EXPECT_FLOAT_EQ(blas.stats.sah, computeSah(blas.nodes));
    // Traversal after the refit agrees with brute force on the moved mesh.
    uint32_t mismatches = 0;
    for (const Ray& ray : test::randomRays(test::boundsOf(moved), 1000, 81)) {
        const Hit a = closestHit(blas, ray);
        const Hit b = closestHitBruteForce(moved, ray);
        mismatches += (a.triangleId != b.triangleId || a.t != b.t) ? 1 : 0;
    }
    EXPECT_EQ(mismatches, 0u);
}

TEST(BvhRefit, RefitWithTheBuildPositionsChangesNothing) {
    const std::vector<Triangle> tris = makeAtrium().triangles();
    const Blas built = buildBlas(tris);
    Blas refit = built;
    refitBlas(refit, tris);
    ASSERT_EQ(refit.nodes.size(), built.nodes.size());
    EXPECT_EQ(std::memcmp(refit.nodes.data(), built.nodes.data(), built.nodes.size() * sizeof(Node)), 0);
    EXPECT_THROW(refitBlas(refit, std::vector<Triangle>(tris.begin(), tris.end() - 1)), std::invalid_argument);
}

TEST(BvhRefit, PresplitBlasStaysCorrectAfterRefit) {
    IndexedMesh mesh = makeAtrium();
    rotateAboutCenter(mesh, 45.0f);
    const std::vector<Triangle> tris = mesh.triangles();
    Blas blas = buildBlas(tris, BuildOptions{.splitFactor = 0.3f});
    const std::vector<Triangle> moved = deformed(tris);
    refitBlas(blas, moved);
    uint32_t mismatches = 0;
    for (const Ray& ray : test::randomRays(test::boundsOf(moved), 1000, 82)) {
        mismatches += closestHit(blas, ray).triangleId != closestHitBruteForce(moved, ray).triangleId ? 1 : 0;
    }
    EXPECT_EQ(mismatches, 0u);
}

// The planned GLSL walk over the flattened arrays: start at the root pair, test both children, intersect a hit
// leaf's GpuBlasTriangle range at once, push the farther inner child.
Hit gpuWalk(const std::vector<gpu::GpuBlasNode>& nodes, const std::vector<gpu::GpuBlasTriangle>& tris,
            const std::vector<glm::vec3>& positions, const Ray& ray) {
    Hit best;
    const PreparedRay r = prepareRay(ray);
    float tRoot = 0.0f;
    if (!r.valid || !intersectBox(r, nodes[0].min, nodes[0].max, kInfinity, tRoot)) return best;
    std::vector<uint32_t> stack;
    uint32_t pair = nodes[0].triStartOrChild;
    for (;;) {
        uint32_t inner[2];
        float innerT[2];
        uint32_t innerCount = 0;
        for (uint32_t c = pair; c < pair + 2; ++c) {
            float t = 0.0f;
            // The CPU walk's slack beyond the current hit (ties with a smaller id stay reachable).
            if (!intersectBox(r, nodes[c].min, nodes[c].max, best.t + std::abs(best.t) * 0x1p-20f, t)) continue;
            if (nodes[c].triCount == 0) {
                inner[innerCount] = c;
                innerT[innerCount++] = t;
                continue;
            }
            for (uint32_t k = nodes[c].triStartOrChild; k < nodes[c].triStartOrChild + nodes[c].triCount; ++k) {
                const Triangle tri{positions[tris[k].vertexIndices.x], positions[tris[k].vertexIndices.y],
                                   positions[tris[k].vertexIndices.z]};
                TriangleHit h;
                if (!intersectTriangle(r, tri, h) || !(h.t < ray.tMax)) continue;
                if (h.t < best.t || (h.t == best.t && tris[k].triangleId < best.triangleId)) {
                    best = {tris[k].triangleId, kInvalidIndex, h.t, h.u, h.v};
                }
            }
        }
        if (innerCount == 2 && innerT[1] < innerT[0]) std::swap(inner[0], inner[1]);
        if (innerCount == 2) stack.push_back(nodes[inner[1]].triStartOrChild);
        if (innerCount >= 1) {
            pair = nodes[inner[0]].triStartOrChild;
            continue;
        }
        if (stack.empty()) return best;
        pair = stack.back();
        stack.pop_back();
    }
}

TEST(BvhFlatten, GpuLayoutRules) {
    static_assert(sizeof(gpu::GpuBlasNode) == 32 && sizeof(gpu::GpuBlasTriangle) == 16 && sizeof(gpu::GpuTlasNode) == 32);
    EXPECT_EQ(offsetof(gpu::GpuBlasNode, triStartOrChild), 12u);
    EXPECT_EQ(offsetof(gpu::GpuBlasNode, max), 16u);
    EXPECT_EQ(offsetof(gpu::GpuBlasNode, triCount), 28u);
    const Blas blas = buildBlas(bunny());
    const std::vector<gpu::GpuBlasNode> nodes = flatten(blas);
    ASSERT_EQ(nodes.size(), blas.nodes.size() + 1);
    EXPECT_EQ(nodes[0].triCount, 0u);
    EXPECT_EQ(nodes[0].triStartOrChild, gpu::kBvhRootPair);
    for (size_t i = 0; i < nodes.size(); ++i) {
        if (i == 1) continue;  // padding
        const size_t cpu = i == 0 ? 0 : i - 1;
        EXPECT_EQ(nodes[i].min, blas.nodes[cpu].min);
        EXPECT_EQ(nodes[i].triCount, blas.nodes[cpu].count);
        if (nodes[i].triCount == 0) {
            ASSERT_EQ(nodes[i].triStartOrChild % 2, 0u) << "pair not at an even index";
            ASSERT_LT(nodes[i].triStartOrChild + 1, nodes.size());
        } else {
            EXPECT_EQ(nodes[i].triStartOrChild, blas.nodes[cpu].first);
        }
    }
    // One-leaf and empty meshes still give a root whose pair is at 2.
    const std::vector<Triangle> one{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
    const std::vector<gpu::GpuBlasNode> small = flatten(buildBlas(one));
    ASSERT_EQ(small.size(), 4u);
    EXPECT_EQ(small[0].triCount, 0u);
    EXPECT_EQ(small[2].triCount, 1u);
    EXPECT_GT(small[3].min.x, small[3].max.x);  // empty-box partner
    const std::vector<gpu::GpuBlasNode> none = flatten(buildBlas({}));
    ASSERT_EQ(none.size(), 4u);
    EXPECT_GT(none[0].min.x, none[0].max.x);
    const Blas tiny = buildBlas(one);
    std::vector<glm::vec3> positions{one[0].v0, one[0].v1, one[0].v2};
    const std::vector<glm::uvec3> indices{{0, 1, 2}};
    EXPECT_TRUE(gpuWalk(small, flattenTriangles(tiny, indices), positions, {{0.2f, 0.2f, 1}, {0, 0, -1}}).hit());
    EXPECT_FALSE(gpuWalk(none, {}, positions, {{0.2f, 0.2f, 1}, {0, 0, -1}}).hit());
}

TEST(BvhFlatten, EmulatedGpuWalkMatchesTheCpuTraversal) {
    const std::vector<Triangle>& tris = bunny();
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;
    for (uint32_t t = 0; t < tris.size(); ++t) {
        positions.insert(positions.end(), {tris[t].v0, tris[t].v1, tris[t].v2});
        indices.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    for (float split : {0.0f, 0.3f}) {
        const Blas blas = buildBlas(tris, BuildOptions{.splitFactor = split});
        const std::vector<gpu::GpuBlasNode> nodes = flatten(blas);
        const std::vector<gpu::GpuBlasTriangle> gpuTris = flattenTriangles(blas, indices);
        ASSERT_EQ(gpuTris.size(), blas.triIds.size());
        uint32_t mismatches = 0, hits = 0;
        for (const Ray& ray : test::randomRays(test::boundsOf(tris), 20000, 91)) {
            const Hit a = gpuWalk(nodes, gpuTris, positions, ray);
            const Hit b = closestHit(blas, ray);
            hits += b.hit() ? 1 : 0;
            mismatches += (a.triangleId != b.triangleId || a.t != b.t) ? 1 : 0;
        }
        EXPECT_EQ(mismatches, 0u) << "split " << split;
        EXPECT_GT(hits, 5000u);
    }
    // The TLAS flattens the same way.
    World w = makeWorld(92);
    const Tlas tlas = buildTlas(w.instances, w.blases);
    const std::vector<gpu::GpuTlasNode> tnodes = flatten(tlas);
    EXPECT_EQ(tnodes.size(), tlas.nodes.size() + 1);
    EXPECT_EQ(tnodes[0].instanceStartOrChild, gpu::kBvhRootPair);
}

}  // namespace
}  // namespace idk::bvh
