// bvh_traverse_test.cpp: CPU traversal against the brute-force oracle (same intersector and tie rule, so results
// must be identical), any hit, ray intervals, and the hard cases: watertightness at shared edges and vertices of
// closed meshes (1M rays), zero-area triangles, a mesh 1e6 units away, axis-parallel rays with +0/-0 components,
// a triangle spanning the scene, empty and one-triangle meshes, invalid rays, and the ray origin offset.
#include "bvh_test_util.hpp"

#include "bvh/procedural.hpp"
#include "bvh/walk.hpp"

#include <cmath>
#include <cstring>
#include <iostream>

namespace idk::bvh {
namespace {

using test::bunny;

// Brute-force answers for a ray set, computed once and compared with several BLASes.
std::vector<Hit> bruteForce(const std::vector<Triangle>& tris, const std::vector<Ray>& rays) {
    std::vector<Hit> hits;
    hits.reserve(rays.size());
    for (const Ray& ray : rays) hits.push_back(closestHitBruteForce(tris, ray));
    return hits;
}

// Compares BVH closest and any hits with the oracle; returns the number of disagreements (prints the first few).
uint32_t countMismatches(const Blas& blas, const std::vector<Ray>& rays, const std::vector<Hit>& expected,
                         uint32_t* hits = nullptr) {
    uint32_t mismatches = 0, hitCount = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Hit a = closestHit(blas, rays[i]);
        const Hit& b = expected[i];
        hitCount += a.hit() ? 1 : 0;
        const bool same = a.triangleId == b.triangleId && (!a.hit() || (a.t == b.t && a.u == b.u && a.v == b.v));
        if (!same && mismatches++ < 5) {
            std::cout << "  mismatch: bvh " << a.triangleId << " t " << a.t << " vs brute " << b.triangleId << " t "
                      << b.t << "\n";
        }
        if (anyHit(blas, rays[i]) != b.hit() && mismatches++ < 5) std::cout << "  any-hit disagrees\n";
    }
    if (hits != nullptr) *hits = hitCount;
    return mismatches;
}

uint32_t countMismatches(const Blas& blas, const std::vector<Triangle>& tris, const std::vector<Ray>& rays,
                         uint32_t* hits = nullptr) {
    return countMismatches(blas, rays, bruteForce(tris, rays), hits);
}

TEST(BvhTraverse, RandomSoupMatchesBruteForceOn80kRays) {
    const std::vector<Triangle> tris = makeRandomTriangles(1000, 21);
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 80000, 1);
    const std::vector<Hit> expected = bruteForce(tris, rays);
    for (uint32_t leaf : {1u, 8u}) {
        const Blas blas = buildBlas(tris, BuildOptions{.maxLeafSize = leaf});
        uint32_t hits = 0;
        EXPECT_EQ(countMismatches(blas, rays, expected, &hits), 0u);
        EXPECT_GT(hits, 20000u);
    }
}

TEST(BvhTraverse, BunnyMatchesBruteForce) {
    const std::vector<Triangle>& tris = bunny();
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 1500, 2);
    const std::vector<Hit> expected = bruteForce(tris, rays);
    for (float split : {0.0f, 1.0f}) {  // pre-split: leaves reference whole triangles, boxes are fragment boxes
        uint32_t hits = 0;
        EXPECT_EQ(countMismatches(buildBlas(tris, BuildOptions{.splitFactor = split}), rays, expected, &hits), 0u);
        EXPECT_GT(hits, 500u);
    }
}

TEST(BvhTraverse, RotatedAtriumWithPresplittingMatchesBruteForce) {
    IndexedMesh mesh = makeAtrium();
    rotateAboutCenter(mesh, 45.0f);
    const std::vector<Triangle> tris = mesh.triangles();
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 3000, 3);
    const std::vector<Hit> expected = bruteForce(tris, rays);
    for (float split : {0.0f, 0.3f, 1.0f}) {
        uint32_t hits = 0;
        EXPECT_EQ(countMismatches(buildBlas(tris, BuildOptions{.splitFactor = split}), rays, expected, &hits), 0u)
            << "split factor " << split;
        EXPECT_GT(hits, 1000u);
    }
}

TEST(BvhTraverse, RayIntervalIsOpenAtBothEnds) {
    const std::vector<Triangle>& tris = bunny();
    const Blas blas = buildBlas(tris);
    uint32_t checked = 0;
    for (Ray ray : test::randomRays(test::boundsOf(tris), 2000, 4)) {
        const Hit first = closestHit(blas, ray);
        if (!first.hit()) continue;
        ++checked;
        Ray shorter = ray;
        shorter.tMax = first.t;  // the hit itself is at tMax: excluded
        EXPECT_FALSE(anyHit(blas, shorter));
        EXPECT_FALSE(closestHit(blas, shorter).hit());
        shorter.tMax = std::nextafter(first.t, kInfinity);
        EXPECT_TRUE(anyHit(blas, shorter));
        Ray beyond = ray;
        beyond.tMin = first.t;  // the next surface along the ray
        const Hit second = closestHit(blas, beyond);
        EXPECT_EQ(second.triangleId, closestHitBruteForce(tris, beyond).triangleId);
        if (second.hit()) {
            EXPECT_GT(second.t, first.t);
        }
    }
    EXPECT_GT(checked, 500u);
}

// Rays from inside a closed mesh aimed exactly at vertices and at points on shared edges: none may escape.
uint32_t countLeaks(const IndexedMesh& mesh, glm::vec3 inside, float insideRadius, uint32_t rayCount, uint32_t seed,
                    bool alsoBruteForce) {
    const std::vector<Triangle> tris = mesh.triangles();
    const Blas blas = buildBlas(tris);
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (const glm::uvec3& f : mesh.indices) {
        for (int e = 0; e < 3; ++e) edges.emplace_back(f[e], f[(e + 1) % 3]);
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    uint32_t leaks = 0;
    for (uint32_t i = 0; i < rayCount; ++i) {
        glm::vec3 target;
        if (i % 8 == 0) {
            target = mesh.positions[rng() % mesh.positions.size()];  // exactly a vertex
        } else {
            const auto [a, b] = edges[rng() % edges.size()];
            const float s = (i % 8 == 1) ? 0.5f : u(rng);
            target = mesh.positions[a] + s * (mesh.positions[b] - mesh.positions[a]);  // on (or next to) an edge
        }
        glm::vec3 origin = inside;
        if (i % 2 == 1) origin += insideRadius * u(rng) * test::randomUnitVector(rng);
        const Ray ray{origin, target - origin};
        if (!closestHit(blas, ray).hit()) ++leaks;
        if (alsoBruteForce && !closestHitBruteForce(tris, ray).hit()) ++leaks;
    }
    return leaks;
}

TEST(BvhTraverse, NoLeaksThroughEdgesAndVerticesOfAnIcosphereOver1MRays) {
    EXPECT_EQ(countLeaks(makeIcosphere(3, 1.0f), glm::vec3(0.0f), 0.5f, 1000000, 31, false), 0u);
    EXPECT_EQ(countLeaks(makeIcosphere(2, 1.0f), glm::vec3(0.0f), 0.5f, 50000, 32, true), 0u);
}

TEST(BvhTraverse, NoLeaksThroughACubeFarFromTheOrigin) {
    // 1e6 units away (float spacing 0.0625 there) and at the origin, with segmented faces (shared diagonals).
    for (glm::vec3 center : {glm::vec3(0.0f), glm::vec3(1.0e6f, -1.0e6f, 1.0e6f)}) {
        const IndexedMesh box = makeBox(center - glm::vec3(100.0f), center + glm::vec3(100.0f), 3);
        EXPECT_EQ(countLeaks(box, center, 60.0f, 200000, 33, true), 0u) << center.x;
    }
}

TEST(BvhTraverse, MeshOffsetBy1e6MatchesBruteForce) {
    std::vector<Triangle> tris = bunny();
    for (Triangle& t : tris) {
        for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) *v = *v * 100.0f + glm::vec3(1.0e6f, 2.0e6f, -1.0e6f);
    }
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 1000, 5);
    uint32_t hits = 0;
    EXPECT_EQ(countMismatches(buildBlas(tris), tris, rays, &hits), 0u);
    EXPECT_GT(hits, 300u);
}

TEST(BvhTraverse, ZeroAreaTrianglesAreBuiltAndNeverHit) {
    std::vector<Triangle> tris = makeRandomTriangles(500, 41);
    const size_t firstDegenerate = tris.size();
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 p(u(rng), u(rng), u(rng)), d(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
        if (i % 3 == 0) tris.push_back({p, p, p});                      // a point
        if (i % 3 == 1) tris.push_back({p, p + d, p + 0.25f * d});      // collinear (up to rounding)
        if (i % 3 == 2) tris.push_back({p, p + d, p + d});              // two equal vertices
    }
    for (float split : {0.0f, 1.0f}) {
        const Blas blas = buildBlas(tris, BuildOptions{.splitFactor = split});
        EXPECT_TRUE(test::checkBlas(blas, tris, 8, split > 0.0f));
        // Rays aimed exactly at the degenerate triangles' vertices.
        std::vector<Ray> rays;
        for (size_t i = firstDegenerate; i < tris.size(); ++i) {
            const glm::vec3 origin(u(rng) * 3.0f - 1.0f, 2.0f, u(rng) * 3.0f - 1.0f);
            rays.push_back({origin, tris[i].v0 - origin});
            rays.push_back({origin, tris[i].v1 - origin});
        }
        EXPECT_EQ(countMismatches(blas, tris, rays), 0u);
        // Triangles with two identical vertices have exactly zero area in any space: never hit. (Collinear ones
        // may become a sliver after the shear's rounding; for them only the agreement above is required.)
        uint32_t degenerateHits = 0;
        for (const Ray& ray : rays) {
            const Hit h = closestHit(blas, ray);
            if (!h.hit() || h.triangleId < firstDegenerate) continue;
            const Triangle& t = tris[h.triangleId];
            degenerateHits += (t.v0 == t.v1 || t.v1 == t.v2 || t.v0 == t.v2) ? 1 : 0;
        }
        EXPECT_EQ(degenerateHits, 0u);
    }
}

TEST(BvhTraverse, AxisParallelRaysWithSignedZeros) {
    // Unit floor tiles and walls on integer coordinates: rays run exactly along box faces and tile edges.
    std::vector<Triangle> tris;
    for (int i = 0; i < 8; ++i) {
        for (int j = 0; j < 8; ++j) {
            const float x = float(i), y = float(j);
            tris.push_back({{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}});
            tris.push_back({{x, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}});
        }
        tris.push_back({{float(i), 0, 0}, {float(i), 8, 0}, {float(i), 8, float(i % 3 + 1)}});  // walls x = i
    }
    const Blas blas = buildBlas(tris, BuildOptions{.maxLeafSize = 2});
    std::vector<Ray> rays;
    uint32_t downward = 0;
    for (int xi = -1; xi <= 18; ++xi) {
        for (int yi = -1; yi <= 18; ++yi) {
            const float x = 0.5f * float(xi), y = 0.5f * float(yi);
            for (int signs = 0; signs < 4; ++signs) {
                const float zx = (signs & 1) ? -0.0f : 0.0f, zy = (signs & 2) ? -0.0f : 0.0f;
                rays.push_back({{x, y, 5.0f}, {zx, zy, -1.0f}});
                if (x >= 0.0f && x <= 8.0f && y >= 0.0f && y <= 8.0f) ++downward;
                rays.push_back({{x, y, -5.0f}, {zx, zy, 1.0f}});
                rays.push_back({{-3.0f, y, 0.5f * x}, {1.0f, zx, zy}});   // along +x through the walls
                rays.push_back({{x, -3.0f, 0.0f}, {zx, 1.0f, zy}});       // in the floor plane
                rays.push_back({{x, 11.0f, 0.5f}, {zx, -1.0f, zy}});
            }
        }
    }
    EXPECT_EQ(countMismatches(blas, tris, rays), 0u);
    uint32_t downHits = 0;
    for (size_t i = 0; i < rays.size(); i += 5) {
        const Hit h = closestHit(blas, rays[i]);
        downHits += h.hit() ? 1 : 0;
        if (h.hit()) {
            EXPECT_LE(h.t, 5.0f);
        }
    }
    EXPECT_EQ(downHits, downward);  // every downward ray over [0, 8]^2 lands (tile edges and corners included)
}

TEST(BvhTraverse, TriangleSpanningTheWholeScene) {
    std::vector<Triangle> tris = makeRandomTriangles(3000, 51);
    tris.push_back({{-50.0f, 0.5f, -50.0f}, {50.0f, 0.5f, -50.0f}, {0.0f, 0.5f, 100.0f}});
    tris.push_back({{-50.0f, -50.0f, 0.3f}, {50.0f, -50.0f, 0.7f}, {0.0f, 100.0f, 0.5f}});
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(makeRandomTriangles(3000, 51)), 20000, 6);
    const std::vector<Hit> expected = bruteForce(tris, rays);
    for (float split : {0.0f, 0.3f}) {
        const Blas blas = buildBlas(tris, BuildOptions{.splitFactor = split});
        EXPECT_TRUE(test::checkBlas(blas, tris, 8, split > 0.0f));
        uint32_t hits = 0;
        EXPECT_EQ(countMismatches(blas, rays, expected, &hits), 0u);
        EXPECT_GT(hits, 15000u);
    }
}

TEST(BvhTraverse, EmptyMesh) {
    const std::vector<Triangle> none;
    const Blas blas = buildBlas(none);
    EXPECT_TRUE(blas.nodes.empty());
    EXPECT_TRUE(blas.triIds.empty());
    EXPECT_EQ(blas.stats.sah, 0.0f);
    EXPECT_EQ(computeEpo(blas, none), 0.0);
    const Ray ray{{0, 0, -1}, {0, 0, 1}};
    EXPECT_FALSE(closestHit(blas, ray).hit());
    EXPECT_FALSE(anyHit(blas, ray));
    EXPECT_FALSE(closestHitBruteForce(none, ray).hit());
}

TEST(BvhTraverse, SingleTriangle) {
    const std::vector<Triangle> tris{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
    const Blas blas = buildBlas(tris);
    ASSERT_EQ(blas.nodes.size(), 1u);
    EXPECT_TRUE(blas.nodes[0].isLeaf());
    const Hit h = closestHit(blas, {{1.0f / 3, 1.0f / 3, 2}, {0, 0, -1}});
    ASSERT_TRUE(h.hit());
    EXPECT_EQ(h.triangleId, 0u);
    EXPECT_FLOAT_EQ(h.t, 2.0f);
    EXPECT_NEAR(h.u, 1.0f / 3, 1e-6f);
    EXPECT_NEAR(h.v, 1.0f / 3, 1e-6f);
    // Back side, vertices and edges count; just outside does not.
    EXPECT_TRUE(closestHit(blas, {{0.25f, 0.25f, -2}, {0, 0, 1}}).hit());
    EXPECT_TRUE(closestHit(blas, {{0, 0, 1}, {0, 0, -1}}).hit());
    EXPECT_TRUE(closestHit(blas, {{1, 0, 1}, {-0.0f, 0, -1}}).hit());
    EXPECT_TRUE(closestHit(blas, {{0.5f, 0.5f, 1}, {0, -0.0f, -1}}).hit());
    EXPECT_TRUE(closestHit(blas, {{0.5f, 0, 1}, {0, 0, -1}}).hit());
    EXPECT_FALSE(closestHit(blas, {{0.5f, -1e-6f, 1}, {0, 0, -1}}).hit());
    EXPECT_FALSE(closestHit(blas, {{0.6f, 0.6f, 1}, {0, 0, -1}}).hit());
    EXPECT_FALSE(closestHit(blas, {{0.2f, 0.2f, 1}, {0, 0, 1}}).hit());  // pointing away
    EXPECT_FALSE(closestHit(blas, {{0.2f, 0.2f, 1}, {1, 0, 0}}).hit());  // parallel
}

TEST(BvhTraverse, InvalidRaysHitNothingAndDoNotCrash) {
    const std::vector<Triangle>& tris = bunny();
    const Blas blas = buildBlas(tris);
    const glm::vec3 c = 0.5f * (blas.bounds().min + blas.bounds().max);
    const float nan = std::nanf("");
    const std::vector<Ray> rays{
        {c, {nan, 0, 0}},      {c, {nan, nan, nan}}, {c, {0, nan, 1}},        {{nan, 0, 0}, {0, 0, 1}},
        {c, {kInfinity, 0, 0}}, {c, {0, 0, 0}},      {c, {-0.0f, 0.0f, -0.0f}}, {{c.x, kInfinity, c.z}, {0, -1, 0}},
        {c, {0, 0, 1}, nan, kInfinity}, {c, {0, 0, 1}, 0.0f, nan}, {c, {0, 0, 1}, 5.0f, 1.0f}};
    for (const Ray& ray : rays) {
        EXPECT_FALSE(closestHit(blas, ray).hit());
        EXPECT_FALSE(anyHit(blas, ray));
        EXPECT_FALSE(closestHitBruteForce(tris, ray).hit());
    }
    EXPECT_FALSE(prepareRay({c, {nan, 1, 1}}).valid);
}

TEST(BvhTraverse, BoxTestIsRobust) {
    const glm::vec3 lo(0.0f), hi(1.0f);
    float tNear = 0.0f;
    auto hits = [&](glm::vec3 o, glm::vec3 d) { return intersectBox(prepareRay({o, d}), lo, hi, kInfinity, tNear); };
    EXPECT_TRUE(hits({0.0f, 0.5f, -1.0f}, {0.0f, 0.0f, 1.0f}));    // on the x = 0 face, 0 * inf = NaN ignored
    EXPECT_TRUE(hits({0.0f, 0.5f, -1.0f}, {-0.0f, 0.0f, 1.0f}));
    EXPECT_TRUE(hits({1.0f, 1.0f, 2.0f}, {-0.0f, -0.0f, -1.0f}));  // along the box's edge x = y = 1
    EXPECT_FALSE(hits({1.0f + 1e-6f, 0.5f, -1.0f}, {0.0f, 0.0f, 1.0f}));
    EXPECT_FALSE(hits({-1e-6f, 0.5f, -1.0f}, {-0.0f, 0.0f, 1.0f}));
    EXPECT_TRUE(hits({0.5f, 0.5f, 0.5f}, {0.0f, 0.0f, -1.0f}));    // inside
    EXPECT_FALSE(hits({0.5f, 0.5f, 2.0f}, {0.0f, 0.0f, 1.0f}));    // behind
    EXPECT_FALSE(intersectBox(prepareRay({{0.5f, 0.5f, -1}, {0, 0, 1}}), Box{}.min, Box{}.max, kInfinity, tNear));
    EXPECT_FALSE(intersectBox(prepareRay({{0.5f, 0.5f, -1}, {0, -0.0f, 1}}), Box{}.min, Box{}.max, kInfinity, tNear));
}

TEST(BvhTraverse, SseBoxTestEqualsTheScalarOne) {
    // The traversal's SSE slab test must give exactly intersectBox's answer, zeros, -0 and faces included.
    std::mt19937 rng(71);
    std::uniform_int_distribution<int> grid(-4, 4);
    const float zeros[3] = {0.0f, -0.0f, 1.0f};
    uint32_t hits = 0;
    for (int i = 0; i < 200000; ++i) {
        Node node;
        const glm::vec3 p(grid(rng), grid(rng), grid(rng)), q(grid(rng), grid(rng), grid(rng));
        node.setBox(i % 4 == 3 ? Box{p, q} : Box{glm::min(p, q), glm::max(p, q)});  // some empty or inverted
        node.first = uint32_t(rng());  // lane 3 garbage must not matter
        node.count = uint32_t(rng());
        glm::vec3 d = glm::vec3(grid(rng), grid(rng), grid(rng)) * 0.25f;
        for (int k = 0; k < 3; ++k) {
            if (rng() % 3 == 0) d[k] = zeros[rng() % 2];
        }
        if (d == glm::vec3(0.0f)) d.z = 1.0f;
        const PreparedRay r = prepareRay({glm::vec3(grid(rng), grid(rng), grid(rng)) * 0.5f, d});
        const float limit = (i % 4 == 0) ? kInfinity : float(grid(rng) + 5);
        float scalarT = 0.0f, sseT = 0.0f;
        const bool scalar = intersectBox(r, node.min, node.max, limit, scalarT);
        const bool sse = detail::SseBoxTest(r)(node, limit, sseT);
        ASSERT_EQ(scalar, sse) << i;
        if (scalar) {
            ASSERT_EQ(scalarT, sseT) << i;
            ++hits;
        }
    }
    EXPECT_GT(hits, 20000u);
}

TEST(BvhTraverse, OffsetOriginPreventsSelfIntersection) {
    std::mt19937 rng(61);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), logScale(-3.0f, 6.0f);
    uint32_t selfHitsNaive = 0, selfHitsOffset = 0;
    for (int i = 0; i < 200000; ++i) {
        const float scale = std::pow(10.0f, logScale(rng));
        const glm::vec3 base = scale * (2.0f * glm::vec3(u(rng), u(rng), u(rng)) - 1.0f);
        const float size = scale * (0.01f + u(rng));
        const Triangle tri{base, base + size * test::randomUnitVector(rng), base + size * test::randomUnitVector(rng)};
        glm::vec3 n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        if (!(glm::length(n) > 0.0f)) continue;
        n = glm::normalize(n);
        float a = u(rng), b = u(rng);
        if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
        const glm::vec3 p = tri.v0 + a * (tri.v1 - tri.v0) + b * (tri.v2 - tri.v0);
        glm::vec3 d = test::randomUnitVector(rng);
        if (glm::dot(d, n) < 0.0f) d = -d;  // leave on the normal's side
        TriangleHit h;
        selfHitsNaive += intersectTriangle(prepareRay({p, d}), tri, h) ? 1 : 0;
        selfHitsOffset += intersectTriangle(prepareRay({offsetRayOrigin(p, n), d}), tri, h) ? 1 : 0;
    }
    std::cout << "[ offset ] self hits without offset " << selfHitsNaive << ", with offset " << selfHitsOffset << "\n";
    EXPECT_GT(selfHitsNaive, 0u);  // the problem is real...
    EXPECT_EQ(selfHitsOffset, 0u); // ...and the offset removes it
}

}  // namespace
}  // namespace idk::bvh
