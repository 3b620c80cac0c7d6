// bvh_fp32_kernel_test.cpp: the single-precision watertight test (intersect.hpp, edge_function.hpp) against exact
// oracles. Edge functions: the sign of a*b - c*d must equal double's (products of floats are exact in double, so
// its sign is exact) on near-ties, exact ties, zeros, tiny, huge and overflowing products; the value must be within
// the stated error bound. Whole test: hit/miss decisions must equal the former double-precision kernel
// (bvh_double_oracle.hpp) on every ray/triangle pair of rays aimed at vertices and edges of closed meshes, at the
// origin and 1e6 units away, with t, u, v close.
#include "bvh_double_oracle.hpp"
#include "bvh_test_util.hpp"

#include "bvh/procedural.hpp"

#include <cmath>
#include <iostream>

namespace idk::bvh {
namespace {

int signOf(double x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

// Steps x by k ulps (k may be negative); stays finite for the magnitudes used here.
float stepUlps(float x, int k) {
    for (; k > 0; --k) x = std::nextafter(x, kInfinity);
    for (; k < 0; ++k) x = std::nextafter(x, -kInfinity);
    return x;
}

struct EdgeStats {
    uint32_t cases = 0, signMismatches = 0, valueMismatches = 0, exactZeros = 0, nearTies = 0;
};

// One a*b - c*d case, checked by edgeFunction() and by the integer path alone.
void checkEdge(float a, float b, float c, float d, EdgeStats& s) {
    a = flushSubnormal(a), b = flushSubnormal(b), c = flushSubnormal(c), d = flushSubnormal(d);
    const double ab = double(a) * double(b), cd = double(c) * double(d), exact = ab - cd;
    const int want = signOf(exact);
    const bool representable = std::abs(ab) < 0x1p100 && std::abs(cd) < 0x1p100;  // no saturation of the value
    for (const EdgeValue& got : {edgeFunction(a, b, c, d), detail::exactDifference(a, b, c, d)}) {
        ++s.cases;
        if (got.sign != want && s.signMismatches++ < 5)
            std::cout << "  sign " << got.sign << " vs " << want << " for " << a << "*" << b << " - " << c << "*" << d
                      << "\n";
        // The fast path's bound (edge_function.hpp) is 3u|e| + 3u(|p| + |q|) + 3 * 2^-126; 4u covers both paths.
        const double bound = 4.0 * 0x1p-24 * (std::abs(ab) + std::abs(cd) + std::abs(exact)) + 0x1p-124;
        if (representable && !(std::abs(double(got.value) - exact) <= bound) && s.valueMismatches++ < 5)
            std::cout << "  value " << got.value << " vs " << exact << "\n";
    }
    s.exactZeros += exact == 0.0 ? 1 : 0;
    s.nearTies += (exact != 0.0 && std::abs(exact) <= 0x1p-20 * (std::abs(ab) + std::abs(cd))) ? 1 : 0;
}

TEST(BvhFp32Kernel, EdgeFunctionSignsAreExact) {
    std::mt19937 rng(91);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-60, 60), ulps(-3, 3), wide(-140, 62);
    EdgeStats s;
    for (int i = 0; i < 200000; ++i) {
        const float scale = std::ldexp(1.0f, exponent(rng));
        const float a = unit(rng) * scale, b = unit(rng) * std::ldexp(1.0f, exponent(rng));
        switch (i % 6) {
            case 0: checkEdge(a, b, unit(rng) * scale, unit(rng) * std::ldexp(1.0f, exponent(rng)), s); break;
            case 1: checkEdge(a, b, stepUlps(a, ulps(rng)), stepUlps(b, ulps(rng)), s); break;  // near-ties
            case 2: checkEdge(a, b, stepUlps(b, ulps(rng)), stepUlps(a, ulps(rng)), s); break;
            case 3: checkEdge(a, b, b, a, s); break;                                             // exact ties
            case 4: {  // a*b = (2a)*(b/2) exactly, then perturbed: equal products with different factors
                const float c = stepUlps(2.0f * a, ulps(rng) / 2), d = 0.5f * b;
                checkEdge(a, b, c, d, s);
                break;
            }
            default: {  // any exponent: zeros, subnormals (flushed), tiny, huge and overflowing (in float) products
                const auto any = [&] { return rng() % 8 == 0 ? 0.0f : unit(rng) * std::ldexp(1.0f, wide(rng)); };
                checkEdge(any(), any(), any(), any(), s);
            }
        }
    }
    EXPECT_EQ(s.signMismatches, 0u);
    EXPECT_EQ(s.valueMismatches, 0u);
    EXPECT_GT(s.exactZeros, 30000u);  // the cases really probe ties ...
    EXPECT_GT(s.nearTies, 30000u);    // ... and products equal to within rounding
    std::cout << "  " << s.cases << " cases, " << s.exactZeros << " exact zeros, " << s.nearTies << " near ties\n";
}

struct DecisionStats {
    uint64_t pairs = 0, hits = 0, decisionMismatches = 0, onEdge = 0;
    double maxTError = 0.0, maxUvError = 0.0;
};

// Every triangle of `mesh` against rays from inside aimed at its vertices and at points on its edges.
void compareDecisions(const IndexedMesh& mesh, glm::vec3 inside, float insideRadius, uint32_t rayCount,
                      uint32_t seed, DecisionStats& s) {
    const std::vector<Triangle> tris = mesh.triangles();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (uint32_t i = 0; i < rayCount; ++i) {
        const glm::uvec3 f = mesh.indices[rng() % mesh.indices.size()];
        const glm::vec3 p = mesh.positions[f[0]], q = mesh.positions[f[1]];
        const glm::vec3 target = i % 4 == 0 ? p : p + (i % 4 == 1 ? 0.5f : u(rng)) * (q - p);
        glm::vec3 origin = inside;
        if (i % 2 == 1) origin += insideRadius * u(rng) * test::randomUnitVector(rng);
        const PreparedRay r = prepareRay({origin, target - origin, -1.0e30f, kInfinity});
        for (const Triangle& tri : tris) {
            ++s.pairs;
            TriangleHit single, twice;
            const bool a = intersectTriangle(r, tri, single), b = test::intersectTriangleDouble(r, tri, twice);
            const test::DoubleEdges e = test::doubleEdges(r, tri);
            s.onEdge += (b && (e.u == 0.0 || e.v == 0.0 || e.w == 0.0)) ? 1 : 0;
            if (a != b) {
                if (s.decisionMismatches++ < 5) std::cout << "  fp32 " << a << " vs double " << b << "\n";
                continue;
            }
            if (!a) continue;
            ++s.hits;
            s.maxTError = std::max(s.maxTError, std::abs(double(single.t) - twice.t) / std::abs(double(twice.t)));
            s.maxUvError = std::max({s.maxUvError, std::abs(double(single.u) - twice.u),
                                     std::abs(double(single.v) - twice.v)});
        }
    }
}

TEST(BvhFp32Kernel, DecisionsEqualTheDoubleKernelAtEdgesAndVertices) {
    DecisionStats s;
    compareDecisions(makeIcosphere(2, 1.0f), glm::vec3(0.0f), 0.5f, 20000, 93, s);
    for (glm::vec3 center : {glm::vec3(0.0f), glm::vec3(1.0e6f, -1.0e6f, 1.0e6f)})
        compareDecisions(makeBox(center - glm::vec3(100.0f), center + glm::vec3(100.0f), 3), center, 60.0f, 20000, 94,
                         s);
    std::cout << "  " << s.pairs << " ray/triangle pairs, " << s.hits << " hits, " << s.onEdge
              << " exactly on an edge or vertex; max relative t error " << s.maxTError << ", max u/v error "
              << s.maxUvError << "\n";
    EXPECT_EQ(s.decisionMismatches, 0u);
    EXPECT_GT(s.onEdge, 10000u);  // the rays really hit edges and vertices exactly
    EXPECT_LT(s.maxTError, 1e-5);
    EXPECT_LT(s.maxUvError, 1e-5);
}

}  // namespace
}  // namespace idk::bvh
