// bvh_refit_checks.cpp: the BVH refit and ray-offset kernels against their CPU twins, bit for bit, on meshes the
// engine builds itself:
// * "bvh/refit": the GPU refit (render::recordRefit) against bvh::refitBlas on a random triangle soup with
//   per-vertex jitter (three rounds, signed zeros in the last), a pre-split rotated atrium deformed smoothly, a
//   single triangle and an empty mesh (whose refit plan is empty); every node's bytes must match.
// * "bvh/offset ray origin": bvh/offset_ray_origin.comp.glsl against bvh::offsetRayOrigin on 100k points spanning
//   2^-12..2^8 in magnitude (zeros and negative zeros included) and random unit normals, bit for bit.
// Moved from tests/conformance/bvh/bvh_refit_test.cpp, which keeps the bunny sweep (an asset) and the CPU-only
// refit-order test and calls expectExactRefit below.
#include <cstring>

#include "bvh/intersect.hpp"
#include "bvh/refit.hpp"
#include "conformance/bvh_refit_support.hpp"
#include "shared/bvh_trace_types.h"
#include "vk/shader_library.hpp"

namespace idk::conformance {

uint32_t expectExactRefit(vk::Context& ctx, vk::ShaderLibrary& shaders, Verdict& v, UploadedBlas& t,
                          const render::TriangleMesh& moved, const std::string& what) {
    bvh::Blas cpu = t.blas;
    bvh::refitBlas(cpu, trianglesOf(moved));
    const std::vector<gpu::GpuBlasNode> expected = bvh::flatten(cpu);
    t.gpu->uploadPositions(moved.positions);
    ctx.runImmediate([&](VkCommandBuffer cmd) { render::recordRefit(cmd, {ctx, shaders}, *t.gpu); });
    const std::vector<gpu::GpuBlasNode> got = t.gpu->downloadNodes();
    uint32_t different = 0;
    if (v.expectEq(got.size(), expected.size(), what + ": node count")) {
        for (size_t i = 0; i < got.size(); ++i) {
            if (std::memcmp(&got[i], &expected[i], sizeof(gpu::GpuBlasNode)) == 0) continue;
            ++different;
            for (int k = 0; k < 3; ++k) {
                v.recordError(std::abs(double(got[i].min[k]) - expected[i].min[k]));
                v.recordError(std::abs(double(got[i].max[k]) - expected[i].max[k]));
            }
            v.expect(false, what + ": node " + std::to_string(i) + " gpu min " + std::to_string(got[i].min.x) + "," +
                                std::to_string(got[i].min.y) + "," + std::to_string(got[i].min.z) + " cpu min " +
                                std::to_string(expected[i].min.x) + "," + std::to_string(expected[i].min.y) + "," +
                                std::to_string(expected[i].min.z));
        }
    }
    t.blas = std::move(cpu);
    t.mesh = moved;
    t.triangles = trianglesOf(moved);
    return different;
}

render::TriangleMesh deformed(render::TriangleMesh mesh, float amplitude) {
    for (glm::vec3& p : mesh.positions)
        p += amplitude * glm::vec3(std::sin(40.0f * p.y), std::cos(30.0f * p.z), std::sin(50.0f * p.x));
    return mesh;
}

namespace {

void refit(CheckEnv& env, Verdict& v) {
    std::vector<bvh::Triangle> soup = bvh::makeRandomTriangles(3000, 82);
    render::TriangleMesh mesh;
    for (uint32_t t = 0; t < soup.size(); ++t) {
        mesh.positions.insert(mesh.positions.end(), {soup[t].v0, soup[t].v1, soup[t].v2});
        mesh.indices.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    UploadedBlas t(env.ctx, mesh, {}, "random soup");
    std::mt19937 rng(83);
    std::normal_distribution<float> n(0.0f, 0.05f);
    for (int round = 0; round < 3; ++round) {
        render::TriangleMesh moved = t.mesh;
        for (glm::vec3& p : moved.positions) p += glm::vec3(n(rng), n(rng), n(rng));
        if (round == 2) moved.positions[7] = glm::vec3(-0.0f, 0.0f, -0.0f);  // signed zeros in the min/max order
        expectExactRefit(env.ctx, env.shaders, v, t, moved, "random soup, round " + std::to_string(round));
    }

    bvh::IndexedMesh atrium = bvh::makeAtrium();
    bvh::rotateAboutCenter(atrium, 45.0f);
    UploadedBlas presplit(env.ctx, fromIndexed(atrium), bvh::BuildOptions{.splitFactor = 0.3f}, "rotated atrium");
    expectExactRefit(env.ctx, env.shaders, v, presplit, deformed(presplit.mesh, 0.3f), "rotated atrium, split 0.3");

    UploadedBlas single(env.ctx, render::TriangleMesh{{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}}}, {}, "one triangle");
    expectExactRefit(env.ctx, env.shaders, v, single,
                     render::TriangleMesh{{{-2, -1, 0}, {1, -1, 3}, {0, 5, 0}}, {{0, 1, 2}}}, "one triangle");

    UploadedBlas empty(env.ctx, render::TriangleMesh{}, {}, "empty");
    v.expect(empty.gpu->refitLevels().empty(), "empty mesh: the refit plan has levels");
    expectExactRefit(env.ctx, env.shaders, v, empty, render::TriangleMesh{}, "empty mesh");
}

void offsetRayOrigin(CheckEnv& env, Verdict& v) {
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
        return vk::createBufferWithData(env.ctx, {count * sizeof(glm::vec3), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                  vk::MemoryUsage::GpuOnly, name, "test"},
                                        data.data(), count * sizeof(glm::vec3));
    };
    vk::Buffer p = buffer(points, "offset points"), n = buffer(normals, "offset normals"), out = buffer(points, "offset out");
    const vk::Pipeline& pipeline =
        env.shaders.compute({vk::ShaderId::bvh_offset_ray_origin_comp, {}, sizeof(gpu::BvhOffsetPush), {{64, 1, 1}}});
    const gpu::BvhOffsetPush push{p.address, n.address, out.address, count, 0};
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, pipeline);
        vk::pushConstants(cmd, env.ctx, push);
        vkCmdDispatch(cmd, vk::groupCount(count, 64), 1, 1);
    });
    const std::vector<glm::vec3> got = vk::downloadBuffer<glm::vec3>(env.ctx, out, count);
    for (vk::Buffer* b : {&p, &n, &out}) env.ctx.destroyDeferred(*b);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 expected = bvh::offsetRayOrigin(points[i], normals[i]);
        if (std::memcmp(&got[i], &expected, sizeof expected) == 0) continue;
        for (int k = 0; k < 3; ++k) v.recordError(std::abs(double(got[i][k]) - expected[k]));
        v.expect(false, "point " + std::to_string(i) + ": gpu " + std::to_string(got[i].x) + "," + std::to_string(got[i].y) +
                            "," + std::to_string(got[i].z) + " cpu " + std::to_string(expected.x) + "," +
                            std::to_string(expected.y) + "," + std::to_string(expected.z));
    }
}

}  // namespace

std::vector<Check> bvhRefitChecks() {
    return {
        {"bvh/refit", "", "every node bit-identical to the CPU refit", refit},
        {"bvh/offset ray origin", "", "bit-identical to the CPU", offsetRayOrigin},
    };
}

}  // namespace idk::conformance
