// bvh_trace_test.cpp: the GLSL traversal (include/bvh_traverse.glsl through shaders_glsl/bvh/trace_rays) against the
// CPU traversal (engine/bvh/traverse.hpp) on lavapipe: closest hit and any hit over camera-like, random, segment,
// vertex/edge-aimed and axis-parallel rays on bunny, the procedural atrium rotated 45 degrees (pre-split) and
// BrainStem (glTF, world space), about 1.2M rays in all, each traced twice (closest, any); a TLAS over
// MetalRoughSpheres' instances; the stack-overflow guard. The hard cases (single triangle, empty, degenerate, far
// offset) and the TLAS of transformed and mirrored instances are registered checks on procedural scenes
// (engine/conformance/bvh_checks.cpp: "bvh/blas binary", "bvh/tlas binary"), run by `idk conformance` and ctest.
// Rule (compareClosest): same hit/miss, triangle and instance, t within 1e-5 relative; ties only at equal t.
#include <chrono>

#include "bvh/tlas.hpp"
#include "bvh_gpu_test_util.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

using render::TraceMode;

class BvhTraceTest : public GpuTest {
protected:
    // Closest and any hit of `rays` on one BLAS against the CPU; expects agreement and returns the counts.
    Agreement traceBoth(const TestBlas& scene, const std::vector<bvh::Ray>& rays, const std::string& what) {
        RayBatch batch(ctx(), shaders(), 1u << 17);
        const auto start = std::chrono::steady_clock::now();
        const std::vector<gpu::GpuBvhHit> closest = batch.trace(*scene.gpu, TraceMode::Closest, rays);
        const std::vector<gpu::GpuBvhHit> any = batch.trace(*scene.gpu, TraceMode::Any, rays);
        const double gpuSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        Agreement a = compareClosest(rays, closest, [&](const bvh::Ray& r) { return bvh::closestHit(scene.blas, r); });
        a.add(compareAny(rays, any, [&](const bvh::Ray& r) { return bvh::anyHit(scene.blas, r); }));
        a.rays = rays.size();
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.2f", gpuSeconds);
        report(what + " (GPU " + seconds + " s for closest + any)", a);
        EXPECT_EQ(a.mismatches, 0u) << what << "\n" << a.firstProblems;
        EXPECT_EQ(a.anyMismatches, 0u) << what << "\n" << a.firstProblems;
        EXPECT_EQ(a.overflows, 0u) << what;
        return a;
    }
};

TEST_F(BvhTraceTest, BunnyMatchesCpu) {
    const TestBlas bunny(ctx(), bunnyMesh(), {}, "bunny");
    const bvh::Box box = bunny.blas.bounds();
    std::vector<bvh::Ray> rays = outsideCameraRays(box, {0.3f, 0.4f, 1.0f}, 384, 384);
    append(rays, randomRays(box, 150000, 11));
    append(rays, segmentRays(box, 50000, 12));
    append(rays, vertexEdgeRays(bunny.triangles, box, 100000, 13));  // shared edges and vertices: no leaks
    const Agreement a = traceBoth(bunny, rays, "bunny (camera, random, segments, vertex/edge-aimed)");
    EXPECT_GT(a.hits, rays.size() / 3);
    EXPECT_EQ(a.bitExact, a.hits);  // the port is operation for operation: t, u and v come out bit-identical
}

TEST_F(BvhTraceTest, RotatedAtriumWithPresplitMatchesCpu) {
    bvh::IndexedMesh atrium = bvh::makeAtrium();
    const glm::mat4 rotation = bvh::rotationAboutCenter(atrium, 45.0f);
    bvh::rotateAboutCenter(atrium, 45.0f);
    const TestBlas rotated(ctx(), fromIndexed(atrium), bvh::BuildOptions{.splitFactor = 0.3f}, "rotated atrium");
    const bvh::Box box = rotated.blas.bounds();
    // A camera inside the hall and one outside, random rays, segments (shadow rays between galleries).
    const glm::vec3 eye(rotation * glm::vec4(-25.0f, 5.0f, -8.0f, 1.0f));
    const glm::vec3 target(rotation * glm::vec4(20.0f, 10.0f, 5.0f, 1.0f));
    std::vector<bvh::Ray> rays = cameraRays(eye, target, 384, 384);
    append(rays, outsideCameraRays(box, {1.0f, 0.5f, 0.2f}, 128, 128));
    append(rays, randomRays(box, 150000, 21));
    append(rays, segmentRays(box, 100000, 22));
    const Agreement a = traceBoth(rotated, rays, "rotated atrium, split 0.3 (cameras, random, segments)");
    EXPECT_GT(a.hits, rays.size() / 2);
    EXPECT_EQ(a.bitExact, a.hits);
}

TEST_F(BvhTraceTest, AxisAlignedAtriumWithAxisParallelRaysMatchesCpu) {
    // Unrotated: walls and slabs on integer planes, origins on the integer grid, directions with +-0 components.
    const TestBlas atrium(ctx(), fromIndexed(bvh::makeAtrium()), {}, "atrium");
    std::vector<bvh::Ray> rays = axisRays(atrium.blas.bounds(), 100000, 31);
    const Agreement a = traceBoth(atrium, rays, "atrium, axis-parallel and invalid rays");
    EXPECT_GT(a.hits, rays.size() / 3);
}

TEST_F(BvhTraceTest, BrainStemWorldSpaceMatchesCpu) {
    const scene::Scene brainStem = scene::loadGltf(sharedPath("scenes/BrainStem/glTF-Binary/BrainStem.glb"));
    const TestBlas stem(ctx(), render::worldTriangles(brainStem), {}, "BrainStem");
    ASSERT_GT(stem.triangles.size(), 50000u);
    const bvh::Box box = stem.blas.bounds();
    std::vector<bvh::Ray> rays = outsideCameraRays(box, {0.2f, 0.1f, 1.0f}, 384, 384);
    append(rays, randomRays(box, 150000, 41));
    append(rays, vertexEdgeRays(stem.triangles, box, 50000, 42));
    const Agreement a = traceBoth(stem, rays, "BrainStem (camera, random, vertex/edge-aimed)");
    EXPECT_GT(a.hits, rays.size() / 4);
    EXPECT_EQ(a.bitExact, a.hits);
}

TEST_F(BvhTraceTest, StackOverflowIsFlaggedNeverOutOfBounds) {
    const TestBlas bunny(ctx(), bunnyMesh(), {}, "bunny");
    ASSERT_GT(bunny.gpu->stackSize(), 3u);
    const std::vector<bvh::Ray> rays = randomRays(bunny.blas.bounds(), 20000, 61);
    RayBatch batch(ctx(), shaders(), 1u << 15);
    const std::vector<gpu::GpuBvhHit> hits = batch.trace(*bunny.gpu, TraceMode::Closest, rays, 2);
    uint32_t overflows = 0, wrongWithoutOverflow = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (hits[i].flags & gpu::kBvhHitFlagStackOverflow) {
            ++overflows;
            continue;
        }
        const bvh::Hit cpu = bvh::closestHit(bunny.blas, rays[i]);
        wrongWithoutOverflow += (cpu.triangleId != hits[i].triangleId || cpu.t != hits[i].t) ? 1 : 0;
    }
    std::printf("[ bvh gpu ] stack of 2 (needs %u): %u of %zu rays flagged\n", bunny.gpu->stackSize(), overflows,
                rays.size());
    EXPECT_GT(overflows, 0u);
    EXPECT_EQ(wrongWithoutOverflow, 0u);  // a ray that never overflowed visited everything
}

// ---- TLAS --------------------------------------------------------------------------------------------------------

struct TestTlas {
    std::vector<std::unique_ptr<TestBlas>> blases;
    std::vector<bvh::Blas> cpuBlases;
    std::vector<bvh::BlasInstance> instances;
    bvh::Tlas tlas;
    std::unique_ptr<render::GpuTlas> gpu;

    void finish(vk::Context& ctx) {
        for (const auto& b : blases) cpuBlases.push_back(b->blas);
        tlas = bvh::buildTlas(instances, cpuBlases);
        std::vector<gpu::GpuBvhInstance> gpuInstances;
        for (size_t i = 0; i < instances.size(); ++i) {
            gpuInstances.push_back(render::makeGpuInstance(instances[i].objectToWorld, tlas.worldToObject[i],
                                                           instances[i].blasIndex));
        }
        std::vector<const render::GpuBlas*> gpuBlases;
        for (const auto& b : blases) gpuBlases.push_back(b->gpu.get());
        const std::vector<gpu::GpuTlasNode> nodes = bvh::flatten(tlas);
        gpu = std::make_unique<render::GpuTlas>(
            ctx, render::TlasData{nodes, tlas.instanceOrder, gpuInstances, gpuBlases, bvh::requiredStackSize(tlas.nodes)},
            "test tlas");
    }
    bvh::Box worldBounds() const {
        bvh::Box b;
        for (const bvh::Box& w : tlas.worldBoxes) b.grow(w);
        return b;
    }
};

class BvhTlasTraceTest : public BvhTraceTest {
protected:
    void expectTlasAgreement(const TestTlas& t, const std::vector<bvh::Ray>& rays, const std::string& what) {
        RayBatch batch(ctx(), shaders(), 1u << 17);
        const std::vector<gpu::GpuBvhHit> closest = batch.trace(*t.gpu, TraceMode::Closest, rays);
        const std::vector<gpu::GpuBvhHit> any = batch.trace(*t.gpu, TraceMode::Any, rays);
        Agreement a = compareClosest(rays, closest, [&](const bvh::Ray& r) {
            return bvh::closestHit(t.tlas, t.instances, t.cpuBlases, r);
        });
        a.add(compareAny(rays, any, [&](const bvh::Ray& r) { return bvh::anyHit(t.tlas, t.instances, t.cpuBlases, r); }));
        a.rays = rays.size();
        report(what, a);
        EXPECT_EQ(a.mismatches, 0u) << what << "\n" << a.firstProblems;
        EXPECT_EQ(a.anyMismatches, 0u) << what << "\n" << a.firstProblems;
        EXPECT_EQ(a.overflows, 0u) << what;
        EXPECT_GT(a.hits, rays.size() / 5) << what;
    }
};

TEST_F(BvhTlasTraceTest, MetalRoughSpheresInstancesMatchCpu) {
    const scene::Scene spheres =
        scene::loadGltf(sharedPath("scenes/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb"));
    TestTlas t;
    for (uint32_t m = 0; m < spheres.meshes.size(); ++m) {
        t.blases.push_back(std::make_unique<TestBlas>(ctx(), render::meshTriangles(spheres, m), bvh::BuildOptions{},
                                                      "sphere mesh " + std::to_string(m)));
    }
    for (const scene::Instance& inst : spheres.instances) t.instances.push_back({inst.world, inst.mesh});
    ASSERT_GT(t.instances.size(), 10u);
    t.finish(ctx());
    const bvh::Box box = t.worldBounds();
    std::vector<bvh::Ray> rays = outsideCameraRays(box, {0.1f, 0.2f, 1.0f}, 256, 256);
    append(rays, randomRays(box, 60000, 71));
    expectTlasAgreement(t, rays, "MetalRoughSpheres TLAS (" + std::to_string(t.instances.size()) + " instances)");
}

}  // namespace
}  // namespace idk::test
