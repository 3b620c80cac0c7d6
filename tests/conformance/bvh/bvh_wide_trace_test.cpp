// bvh_wide_trace_test.cpp: the 8-wide compressed BVH on the GPU (include/bvh_traverse_wide.glsl through
// shaders_glsl/bvh/trace_rays_wide, engine/render/bvh_wide_gpu.hpp) against the binary traversal on the three
// conformance scenes (bunny, the rotated pre-split atrium, BrainStem in world space): for every ray the wide GPU walk,
// the binary GPU walk and the CPU binary walk report the same triangle with t within 1e-6 relative (in fact
// bit-identical: the same triangle test runs on the same ray), and the same any-hit answer; the CPU wide walk
// (the shader's oracle) agrees too. Also: the wide BVH after a GPU refit (re-quantised on the CPU) and the
// stack-overflow flag. The hard cases and a TLAS over wide BLASes are registered checks ("bvh/blas 8-wide",
// "bvh/tlas 8-wide" in engine/conformance/bvh_checks.cpp).
#include <cstring>

#include "bvh/refit.hpp"
#include "bvh/tlas.hpp"
#include "bvh/wide8.hpp"
#include "bvh_gpu_test_util.hpp"
#include "render/bvh_wide_gpu.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

using render::TraceMode;

struct TestWide {
    bvh::Bvh8 wide;
    std::unique_ptr<render::GpuWideBlas> gpu;

    TestWide(vk::Context& ctx, const TestBlas& binary, const std::string& name) {
        wide = bvh::buildBvh8(bvh::flatten(binary.blas), bvh::flattenTriangles(binary.blas, binary.mesh.indices));
        gpu = std::make_unique<render::GpuWideBlas>(ctx, wide, *binary.gpu, name);
    }
};

struct WideAgreement {
    uint64_t rays = 0, hits = 0, anyHits = 0, mismatches = 0, anyMismatches = 0, overflows = 0;
    std::string problems;
};

bool sameHit(const gpu::GpuBvhHit& g, const bvh::Hit& c) {
    const bool gpuHit = (g.flags & gpu::kBvhHitFlagHit) != 0;
    if (gpuHit != c.hit()) return false;
    return !gpuHit || (g.triangleId == c.triangleId && g.instanceId == c.instanceId && relClose(g.t, c.t, 1e-6f));
}

class BvhWideTraceTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
    }

    // Wide GPU vs binary GPU vs CPU binary (closest and any) and CPU wide (closest) on `rays`.
    WideAgreement expectSameAsBinary(const TestBlas& binary, const TestWide& wide, const std::vector<bvh::Ray>& rays,
                                     const std::string& what) {
        RayBatch batch(ctx(), shaders(), 1u << 17);
        const auto traceWide = [&](TraceMode mode) {
            return batch.trace(rays, [&](VkCommandBuffer cmd, VkDeviceAddress r, VkDeviceAddress h, uint32_t n) {
                render::recordTraceRaysWide(cmd, {ctx(), shaders()}, *wide.gpu, mode, r, h, n);
            });
        };
        const std::vector<gpu::GpuBvhHit> closest = traceWide(TraceMode::Closest);
        const std::vector<gpu::GpuBvhHit> any = traceWide(TraceMode::Any);
        const std::vector<gpu::GpuBvhHit> binaryGpu = batch.trace(*binary.gpu, TraceMode::Closest, rays);
        std::vector<bvh::Hit> cpu(rays.size()), cpuWide(rays.size());
        std::vector<char> cpuAny(rays.size());
        parallelFor(rays.size(), [&](size_t i) {
            cpu[i] = bvh::closestHit(binary.blas, rays[i]);
            cpuWide[i] = bvh::closestHitWide(wide.wide, binary.mesh.positions, rays[i]);
            cpuAny[i] = bvh::anyHit(binary.blas, rays[i]) ? 1 : 0;
        });
        WideAgreement a;
        a.rays = rays.size();
        for (size_t i = 0; i < rays.size(); ++i) {
            a.hits += cpu[i].hit() ? 1 : 0;
            a.anyHits += uint64_t(cpuAny[i]);
            a.overflows += ((closest[i].flags | any[i].flags) & gpu::kBvhHitFlagStackOverflow) ? 1 : 0;
            const bool binaryAgrees = binaryGpu[i].triangleId == closest[i].triangleId && binaryGpu[i].t == closest[i].t;
            const bool cpuWideAgrees = cpuWide[i].triangleId == cpu[i].triangleId && cpuWide[i].t == cpu[i].t;
            if (!sameHit(closest[i], cpu[i]) || !binaryAgrees || !cpuWideAgrees) {
                if (a.mismatches++ < 5) {
                    char line[256];
                    std::snprintf(line, sizeof line, "  ray %zu: wide gpu tri %u t %.9g, binary gpu tri %u t %.9g, cpu tri %u t %.9g, cpu wide tri %u\n",
                                  i, closest[i].triangleId, double(closest[i].t), binaryGpu[i].triangleId,
                                  double(binaryGpu[i].t), cpu[i].triangleId, double(cpu[i].t), cpuWide[i].triangleId);
                    a.problems += line;
                }
            }
            a.anyMismatches += (((any[i].flags & gpu::kBvhHitFlagHit) != 0) != bool(cpuAny[i])) ? 1 : 0;
        }
        std::printf("[ bvh wide ] %s: %llu rays, %llu closest hits, %llu any hits, %llu mismatches, %llu any-hit "
                    "mismatches, %llu overflows (%u wide nodes, stack %u)\n%s",
                    what.c_str(), (unsigned long long)a.rays, (unsigned long long)a.hits, (unsigned long long)a.anyHits,
                    (unsigned long long)a.mismatches, (unsigned long long)a.anyMismatches,
                    (unsigned long long)a.overflows, wide.gpu->nodeCount(), wide.gpu->stackSize(), a.problems.c_str());
        EXPECT_EQ(a.mismatches, 0u) << what << "\n" << a.problems;
        EXPECT_EQ(a.anyMismatches, 0u) << what;
        EXPECT_EQ(a.overflows, 0u) << what;
        return a;
    }
};

TEST_F(BvhWideTraceTest, BunnyWideEqualsBinary) {
    const TestBlas bunny(ctx(), bunnyMesh(), {}, "bunny");
    const TestWide wide(ctx(), bunny, "bunny");
    const bvh::Box box = bunny.blas.bounds();
    std::vector<bvh::Ray> rays = outsideCameraRays(box, {0.3f, 0.4f, 1.0f}, 192, 192);
    append(rays, randomRays(box, 50000, 111));
    append(rays, segmentRays(box, 20000, 112));
    append(rays, vertexEdgeRays(bunny.triangles, box, 40000, 113));
    const WideAgreement a = expectSameAsBinary(bunny, wide, rays, "bunny (camera, random, segments, vertex/edge-aimed)");
    EXPECT_GT(a.hits, rays.size() / 3);
}

TEST_F(BvhWideTraceTest, RotatedPresplitAtriumWideEqualsBinary) {
    bvh::IndexedMesh atrium = bvh::makeAtrium();
    const glm::mat4 rotation = bvh::rotationAboutCenter(atrium, 45.0f);
    bvh::rotateAboutCenter(atrium, 45.0f);
    const TestBlas rotated(ctx(), fromIndexed(atrium), bvh::BuildOptions{.splitFactor = 0.3f}, "rotated atrium");
    const TestWide wide(ctx(), rotated, "rotated atrium");
    const bvh::Box box = rotated.blas.bounds();
    const glm::vec3 eye(rotation * glm::vec4(-25.0f, 5.0f, -8.0f, 1.0f));
    const glm::vec3 target(rotation * glm::vec4(20.0f, 10.0f, 5.0f, 1.0f));
    std::vector<bvh::Ray> rays = cameraRays(eye, target, 192, 192);
    append(rays, randomRays(box, 50000, 121));
    append(rays, segmentRays(box, 30000, 122));
    append(rays, axisRays(box, 20000, 123));
    const WideAgreement a = expectSameAsBinary(rotated, wide, rays, "rotated atrium, split 0.3 (camera, random, segments, axis-parallel)");
    EXPECT_GT(a.hits, rays.size() / 2);
}

TEST_F(BvhWideTraceTest, BrainStemWideEqualsBinary) {
    const scene::Scene brainStem = scene::loadGltf(sharedPath("scenes/BrainStem/glTF-Binary/BrainStem.glb"));
    const TestBlas stem(ctx(), render::worldTriangles(brainStem), {}, "BrainStem");
    const TestWide wide(ctx(), stem, "BrainStem");
    const bvh::Box box = stem.blas.bounds();
    std::vector<bvh::Ray> rays = outsideCameraRays(box, {0.2f, 0.1f, 1.0f}, 192, 192);
    append(rays, randomRays(box, 50000, 131));
    append(rays, vertexEdgeRays(stem.triangles, box, 30000, 132));
    const WideAgreement a = expectSameAsBinary(stem, wide, rays, "BrainStem (camera, random, vertex/edge-aimed)");
    EXPECT_GT(a.hits, rays.size() / 4);
}

TEST_F(BvhWideTraceTest, StackOverflowIsFlaggedNeverOutOfBounds) {
    const TestBlas bunny(ctx(), bunnyMesh(), {}, "bunny");
    const TestWide wide(ctx(), bunny, "bunny");
    const std::vector<bvh::Ray> rays = randomRays(bunny.blas.bounds(), 20000, 151);
    RayBatch batch(ctx(), shaders(), 1u << 15);
    const std::vector<gpu::GpuBvhHit> hits = batch.trace(rays, [&](VkCommandBuffer cmd, VkDeviceAddress r, VkDeviceAddress h, uint32_t n) {
        render::recordTraceRaysWide(cmd, {ctx(), shaders()}, *wide.gpu, TraceMode::Closest, r, h, n, 1);
    });
    uint32_t overflows = 0, wrongWithoutOverflow = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (hits[i].flags & gpu::kBvhHitFlagStackOverflow) {
            ++overflows;
            continue;
        }
        const bvh::Hit cpu = bvh::closestHit(bunny.blas, rays[i]);
        wrongWithoutOverflow += (cpu.triangleId != hits[i].triangleId || cpu.t != hits[i].t) ? 1 : 0;
    }
    std::printf("[ bvh wide ] stack of 1 (needs %u): %u of %zu rays flagged\n", wide.gpu->stackSize(), overflows, rays.size());
    EXPECT_GT(overflows, 0u);
    EXPECT_EQ(wrongWithoutOverflow, 0u);
}

TEST_F(BvhWideTraceTest, WideAfterGpuRefitEqualsCpuRefit) {
    TestBlas bunny(ctx(), bunnyMesh(), {}, "bunny");
    TestWide wide(ctx(), bunny, "bunny");
    render::TriangleMesh moved = bunny.mesh;
    for (glm::vec3& v : moved.positions) v += 0.02f * glm::vec3(std::sin(40.0f * v.y), std::cos(30.0f * v.z), std::sin(50.0f * v.x));
    bvh::Bvh8 cpuWide = wide.wide;  // same topology, re-quantised below from the CPU refit
    bunny.gpu->uploadPositions(moved.positions);
    render::refitWide(ctx(), {ctx(), shaders()}, *bunny.gpu, wide.wide, *wide.gpu);
    // The CPU path (refit the binary BLAS, flatten, re-quantise the same topology) gives the same nodes bit for bit.
    bvh::refitBlas(bunny.blas, trianglesOf(moved));
    bunny.mesh = moved;
    bunny.triangles = trianglesOf(moved);
    bvh::refitBvh8(cpuWide, bvh::flatten(bunny.blas));
    EXPECT_EQ(std::memcmp(cpuWide.nodes.data(), wide.wide.nodes.data(), cpuWide.nodes.size() * sizeof(gpu::GpuWideNode)), 0);
    expectSameAsBinary(bunny, wide, randomRays(bunny.blas.bounds(), 40000, 161), "bunny after GPU refit");
}

}  // namespace
}  // namespace idk::test
