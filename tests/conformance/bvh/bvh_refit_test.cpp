// bvh_refit_test.cpp: the GPU refit (shaders_glsl/bvh/refit.comp.glsl recorded by render::recordRefit) against the
// CPU refit (bvh::refitBlas, flattened): every node bit for bit after the vertices moved, on the bunny (smooth
// deformation and back), a random triangle soup with per-vertex jitter, a pre-split atrium, a single triangle and an
// empty mesh; the refit plan's level order; traversal after the refit; and the ray-origin offset kernel bit for bit.
#include <cstring>

#include "bvh/refit.hpp"
#include "bvh_gpu_test_util.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

class BvhRefitTest : public GpuTest {
protected:
    // Uploads `moved` positions, refits on the GPU and compares every node with the CPU refit of the same BLAS.
    void expectExactRefit(TestBlas& t, const render::TriangleMesh& moved, const std::string& what) {
        bvh::Blas cpu = t.blas;
        bvh::refitBlas(cpu, trianglesOf(moved));
        const std::vector<gpu::GpuBlasNode> expected = bvh::flatten(cpu);
        t.gpu->uploadPositions(moved.positions);
        ctx().runImmediate([&](VkCommandBuffer cmd) { render::recordRefit(cmd, {ctx(), shaders()}, *t.gpu); });
        const std::vector<gpu::GpuBlasNode> got = t.gpu->downloadNodes();
        ASSERT_EQ(got.size(), expected.size()) << what;
        uint32_t different = 0;
        for (size_t i = 0; i < got.size(); ++i) {
            if (std::memcmp(&got[i], &expected[i], sizeof(gpu::GpuBlasNode)) != 0 && different++ < 3) {
                ADD_FAILURE() << what << ": node " << i << " gpu min " << got[i].min.x << "," << got[i].min.y << ","
                              << got[i].min.z << " cpu min " << expected[i].min.x << "," << expected[i].min.y << ","
                              << expected[i].min.z;
            }
        }
        std::printf("[ bvh refit ] %s: %zu nodes, %zu levels, %u differ\n", what.c_str(), got.size(),
                    t.gpu->refitLevels().size(), different);
        EXPECT_EQ(different, 0u) << what;
        t.blas = std::move(cpu);
        t.mesh = moved;
        t.triangles = trianglesOf(moved);
    }
};

// A smooth function of the position: shared vertices stay shared (the mesh stays closed).
render::TriangleMesh deformed(render::TriangleMesh mesh, float amplitude) {
    for (glm::vec3& v : mesh.positions) {
        v += amplitude * glm::vec3(std::sin(40.0f * v.y), std::cos(30.0f * v.z), std::sin(50.0f * v.x));
    }
    return mesh;
}

TEST_F(BvhRefitTest, BunnyMatchesCpuRefitBitForBit) {
    const render::TriangleMesh original = bunnyMesh();
    TestBlas bunny(ctx(), original, {}, "bunny");
    const std::vector<gpu::GpuBlasNode> built = bunny.gpu->downloadNodes();
    expectExactRefit(bunny, deformed(original, 0.02f), "bunny deformed");
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

TEST_F(BvhRefitTest, RandomSoupWithJitteredVerticesMatchesCpu) {
    std::vector<bvh::Triangle> soup = bvh::makeRandomTriangles(3000, 82);
    render::TriangleMesh mesh;
    for (uint32_t t = 0; t < soup.size(); ++t) {
        mesh.positions.insert(mesh.positions.end(), {soup[t].v0, soup[t].v1, soup[t].v2});
        mesh.indices.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    TestBlas t(ctx(), mesh, {}, "random soup");
    std::mt19937 rng(83);
    std::normal_distribution<float> n(0.0f, 0.05f);
    for (int round = 0; round < 3; ++round) {
        render::TriangleMesh moved = t.mesh;
        for (glm::vec3& p : moved.positions) p += glm::vec3(n(rng), n(rng), n(rng));
        if (round == 2) moved.positions[7] = glm::vec3(-0.0f, 0.0f, -0.0f);  // signed zeros in the min/max order
        expectExactRefit(t, moved, "random soup, round " + std::to_string(round));
    }
}

TEST_F(BvhRefitTest, PresplitSingleAndEmptyMeshes) {
    bvh::IndexedMesh atrium = bvh::makeAtrium();
    bvh::rotateAboutCenter(atrium, 45.0f);
    TestBlas presplit(ctx(), fromIndexed(atrium), bvh::BuildOptions{.splitFactor = 0.3f}, "rotated atrium");
    expectExactRefit(presplit, deformed(presplit.mesh, 0.3f), "rotated atrium, split 0.3");

    TestBlas single(ctx(), render::TriangleMesh{{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}}}, {}, "one triangle");
    expectExactRefit(single, render::TriangleMesh{{{-2, -1, 0}, {1, -1, 3}, {0, 5, 0}}, {{0, 1, 2}}}, "one triangle");

    TestBlas empty(ctx(), render::TriangleMesh{}, {}, "empty");
    EXPECT_TRUE(empty.gpu->refitLevels().empty());
    expectExactRefit(empty, render::TriangleMesh{}, "empty mesh");
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

TEST_F(BvhRefitTest, OffsetRayOriginMatchesCpuBitForBit) {
    const uint32_t count = 100000;
    std::mt19937 rng(91);
    std::uniform_real_distribution<float> exponent(-12.0f, 8.0f), sign(-1.0f, 1.0f);
    std::vector<glm::vec3> points(count), normals(count);
    for (uint32_t i = 0; i < count; ++i) {
        for (int k = 0; k < 3; ++k) points[i][k] = (sign(rng) < 0 ? -1.0f : 1.0f) * std::exp2(exponent(rng));
        if (i % 11 == 0) points[i].y = 0.0f;
        if (i % 13 == 0) points[i].z = -0.0f;
        normals[i] = randomUnitVector(rng);
    }
    auto buffer = [&](const std::vector<glm::vec3>& data, const char* name) {
        return vk::createBufferWithData(ctx(), {count * sizeof(glm::vec3), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                vk::MemoryUsage::GpuOnly, name, "test"},
                                        data.data(), count * sizeof(glm::vec3));
    };
    vk::Buffer p = buffer(points, "offset points"), n = buffer(normals, "offset normals"), out = buffer(points, "offset out");
    const vk::Pipeline& pipeline =
        shaders().compute({vk::ShaderId::bvh_offset_ray_origin_comp, {}, sizeof(gpu::BvhOffsetPush), {{64, 1, 1}}});
    const gpu::BvhOffsetPush push{p.address, n.address, out.address, count, 0};
    ctx().runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, pipeline);
        vk::pushConstants(cmd, ctx(), push);
        vkCmdDispatch(cmd, vk::groupCount(count, 64), 1, 1);
    });
    const std::vector<glm::vec3> got = vk::downloadBuffer<glm::vec3>(ctx(), out, count);
    uint32_t different = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 expected = bvh::offsetRayOrigin(points[i], normals[i]);
        if (std::memcmp(&got[i], &expected, sizeof expected) != 0 && different++ < 3) {
            ADD_FAILURE() << "point " << i << ": gpu " << got[i].x << "," << got[i].y << "," << got[i].z << " cpu "
                          << expected.x << "," << expected.y << "," << expected.z;
        }
    }
    EXPECT_EQ(different, 0u);
    for (vk::Buffer* b : {&p, &n, &out}) ctx().destroy(*b);
}

}  // namespace
}  // namespace idk::test
