// bvh_refit_test.cpp: the GPU refit on the bunny (an asset, so not a registered check): a smooth deformation and
// back, every node bit for bit against the CPU refit (conformance::expectExactRefit, the comparison the registered
// check "bvh/refit" runs on asset-free meshes), traversal over the refit tree against the CPU, and the build's
// boxes restored exactly; and the refit plan's level order (CPU only). The soup, atrium, single-triangle, empty-mesh
// and ray-offset cases are registered checks (engine/conformance/bvh_refit_checks.cpp).
#include <cstring>

#include "bvh_gpu_test_util.hpp"
#include "conformance/bvh_refit_support.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

class BvhRefitTest : public GpuTest {
protected:
    void expectExactRefit(TestBlas& t, const render::TriangleMesh& moved, const std::string& what) {
        conformance::Verdict v;
        const uint32_t different = conformance::expectExactRefit(ctx(), shaders(), v, t, moved, what);
        std::printf("[ bvh refit ] %s: %zu nodes, %zu levels, %u differ\n", what.c_str(), t.gpu->downloadNodes().size(),
                    t.gpu->refitLevels().size(), different);
        EXPECT_TRUE(v.passed()) << v.messages();
    }
};

TEST_F(BvhRefitTest, BunnyMatchesCpuRefitBitForBit) {
    const render::TriangleMesh original = bunnyMesh();
    TestBlas bunny(ctx(), original, {}, "bunny");
    const std::vector<gpu::GpuBlasNode> built = bunny.gpu->downloadNodes();
    expectExactRefit(bunny, conformance::deformed(original, 0.02f), "bunny deformed");
    // The traversal over the refit tree agrees with the CPU traversal over the CPU refit.
    RayBatch batch(ctx(), shaders(), 1u << 16);
    const std::vector<bvh::Ray> rays = randomRays(bunny.blas.bounds(), 40000, 81);
    const std::vector<gpu::GpuBvhHit> hits = batch.trace(*bunny.gpu, render::TraceMode::Closest, rays);
    const Agreement a = compareClosest(rays, hits, [&](const bvh::Ray& r) { return bvh::closestHit(bunny.blas, r); });
    report("bunny after refit", a);
    EXPECT_EQ(a.mismatches, 0u) << a.firstProblems;
    EXPECT_GT(a.hits, 10000u);
    // Back to the build positions: the build's boxes come back exactly.
    expectExactRefit(bunny, original, "bunny restored");
    const std::vector<gpu::GpuBlasNode> restored = bunny.gpu->downloadNodes();
    ASSERT_EQ(restored.size(), built.size());
    EXPECT_EQ(std::memcmp(restored.data(), built.data(), built.size() * sizeof(gpu::GpuBlasNode)), 0);
}

TEST_F(BvhRefitTest, LevelOrderVisitsChildrenFirst) {
    const bvh::Blas blas = bvh::buildBlas(trianglesOf(bunnyMesh()));
    const std::vector<gpu::GpuBlasNode> nodes = bvh::flatten(blas);
    std::vector<std::pair<uint32_t, uint32_t>> levels;
    const std::vector<uint32_t> order = render::refitOrder(nodes, levels);
    EXPECT_EQ(order.size(), nodes.size() - 1);  // every node but the padding
    EXPECT_EQ(levels.size(), bvh::maxDepth(blas.nodes) + 1);
    std::vector<int> levelOf(nodes.size(), -1);
    for (size_t l = 0; l < levels.size(); ++l) {
        for (uint32_t k = levels[l].first; k < levels[l].first + levels[l].second; ++k) levelOf[order[k]] = int(l);
    }
    for (uint32_t i : order) {
        if (nodes[i].triCount == 0) {
            ASSERT_LT(levelOf[nodes[i].triStartOrChild], levelOf[i]);
            ASSERT_LT(levelOf[nodes[i].triStartOrChild + 1], levelOf[i]);
        }
    }
    EXPECT_EQ(order.back(), 0u);  // the root comes last
}

}  // namespace
}  // namespace idk::test
