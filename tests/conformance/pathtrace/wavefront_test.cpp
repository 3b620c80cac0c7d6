// wavefront_test.cpp: the wavefront path tracer's GPU bookkeeping against CPU oracles, on the Cornell box and
// MetalRoughSpheresNoTextures at 64x64 (one sample, state captured after a bounce's shade stage):
// * compaction is exact: the next ray queue holds exactly the pixels whose path the shade stage extended (a CPU
//   filter over the path states), each once, and the indirect dispatch size is ceil(count / group size);
// * ray sorting permutes the queue (the same set as without sorting) into non-decreasing key order, the keys
//   equal the CPU's (material, direction octant) of each hit, and dead slots sort last;
// * every traversal rung (our GLSL BVH, 8-wide and binary, VK_KHR_ray_query) returns the CPU BVH's closest hits for the
//   primary rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "app/default_scene.hpp"
#include "bvh/tlas.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/path_tracer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/acceleration_structure.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

scene::Scene sphereScene() {
    return scene::loadGltf(std::string(IDK_SHARED_DIR) +
                           "/scenes/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb");
}

class PtWavefrontTest : public GpuTest {
protected:
    render::PtCapture capture(const scene::Scene& scene, const pathtrace::PathTraceScene& pts,
                              render::PtTraversal traversal, bool sort, uint32_t bounce) {
        render::PathTracerOptions options;
        options.traversal = traversal;
        options.sortRays = sort;
        render::PathTracer tracer(ctx(), shaders(), scene, pts, options);
        render::PathTraceSettings settings;
        settings.maxDepth = 4;
        settings.seed = 7;
        return tracer.capture(scene::defaultCamera(scene), kSize, kSize, settings, bounce);
    }
    bool rayQuery() { return vk::rayQuerySupported(ctx()); }
};

std::vector<uint32_t> items(const std::vector<uint32_t>& queue) {
    const uint32_t count = queue.at(0);
    return std::vector<uint32_t>(queue.begin() + gpu::kPtQueueHeaderWords,
                                 queue.begin() + gpu::kPtQueueHeaderWords + count);
}

void expectExactCompaction(const render::PtCapture& c, const std::string& what) {
    const std::vector<uint32_t> in = items(c.queueIn), out = items(c.queueOut);
    std::set<uint32_t> expected;  // CPU filter: rays of this bounce whose path shade extended
    for (uint32_t pixel : in)
        if (c.paths.at(pixel).flags & gpu::kPtPathAlive) expected.insert(pixel);
    const std::set<uint32_t> got(out.begin(), out.end());
    EXPECT_EQ(got.size(), out.size()) << what << ": a pixel was appended twice";
    EXPECT_EQ(out.size(), expected.size()) << what;
    EXPECT_TRUE(got == expected) << what << ": the compacted set differs from the CPU filter";
    ASSERT_EQ(c.argsOut.size(), 3u);
    EXPECT_EQ(c.argsOut[0], (uint32_t(out.size()) + gpu::kPtGroupSize - 1) / gpu::kPtGroupSize) << what;
    EXPECT_EQ(c.argsOut[1], 1u);
    EXPECT_EQ(c.argsOut[2], 1u);
    // Sanity of the scenario itself: some paths die and some survive, or the test could not fail.
    EXPECT_GT(expected.size(), 0u) << what;
    EXPECT_LT(expected.size(), in.size()) << what;
}

TEST_F(PtWavefrontTest, CompactionEqualsCpuFilter) {
    const scene::Scene cornell = app::loadDefaultScene();
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(cornell, nullptr, 1.0f);
    for (uint32_t bounce : {0u, 1u, 2u}) {
        const render::PtCapture c = capture(cornell, pts, render::PtTraversal::Bvh, false, bounce);
        if (bounce == 0) {
            EXPECT_EQ(c.queueIn.at(0), kSize * kSize) << "every pixel starts a path";
        }
        expectExactCompaction(c, "Cornell bounce " + std::to_string(bounce));
    }
}

// The CPU's sort key of a traced ray (wf_trace_stage.h): material << 3 | direction octant; misses after all hits.
uint32_t cpuKey(const pathtrace::PathTraceScene& pts, const gpu::GpuPtHit& hit, const glm::vec3& d) {
    if (hit.triangle == gpu::kPtInvalid) return gpu::kPtSortKeyMiss;
    const uint32_t geometry = pts.instances.at(hit.instance).blasIndex;
    const uint32_t material = pts.geometries.at(geometry).triangleMaterial.at(hit.triangle);
    const uint32_t octant = (d.x < 0.0f ? 1u : 0u) | (d.y < 0.0f ? 2u : 0u) | (d.z < 0.0f ? 4u : 0u);
    return std::min((material << 3u) | octant, gpu::kPtSortKeyMiss - 1u);
}

TEST_F(PtWavefrontTest, SortingIsAPermutationOrderedByKey) {
    const scene::Scene spheres = sphereScene();
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(spheres, nullptr, 1.0f, glm::vec3(0.5f));
    for (uint32_t bounce : {0u, 1u}) {
        const std::string what = "spheres bounce " + std::to_string(bounce);
        const render::PtCapture sorted = capture(spheres, pts, render::PtTraversal::Bvh, true, bounce);
        const render::PtCapture plain = capture(spheres, pts, render::PtTraversal::Bvh, false, bounce);
        std::vector<uint32_t> a = items(sorted.queueIn), b = items(plain.queueIn);
        ASSERT_EQ(a.size(), b.size()) << what;
        ASSERT_EQ(sorted.keys.size(), size_t(kSize) * kSize);
        std::set<uint32_t> distinct;
        for (size_t i = 0; i < a.size(); ++i) {
            const uint32_t pixel = a[i];
            EXPECT_EQ(sorted.keys[i], cpuKey(pts, sorted.hits.at(pixel), sorted.rays.at(pixel).direction))
                << what << " slot " << i;
            if (i > 0) {
                EXPECT_LE(sorted.keys[i - 1], sorted.keys[i]) << what << " slot " << i;
            }
            distinct.insert(sorted.keys[i]);
        }
        for (size_t i = a.size(); i < sorted.keys.size(); ++i) EXPECT_EQ(sorted.keys[i], gpu::kPtSortKeyDead) << what;
        EXPECT_GT(distinct.size(), 2u) << what << ": the scene must give several keys";
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        EXPECT_TRUE(a == b) << what << ": sorting changed the set of rays";
        expectExactCompaction(sorted, what + " (sorted)");
    }
}

struct HitAgreement {
    size_t rays = 0, sameTriangle = 0, tClose = 0, hits = 0;
};

HitAgreement compareWithCpu(const pathtrace::PathTraceScene& pts, const render::PtCapture& c) {
    HitAgreement a;
    for (uint32_t pixel : items(c.queueIn)) {
        const gpu::GpuPtPath& ray = c.rays.at(pixel);
        bvh::Ray r;
        r.origin = ray.origin;
        r.direction = ray.direction;
        const bvh::Hit cpu = bvh::closestHit(pts.tlas, pts.instances, pts.blases, r);
        const gpu::GpuPtHit& gpuHit = c.hits.at(pixel);
        ++a.rays;
        const bool cpuHit = cpu.hit(), gpuHitFound = gpuHit.triangle != gpu::kPtInvalid;
        a.hits += cpuHit;
        if (cpuHit != gpuHitFound) continue;
        if (!cpuHit || (cpu.triangleId == gpuHit.triangle && cpu.instanceId == gpuHit.instance)) ++a.sameTriangle;
        if (!cpuHit || std::abs(cpu.t - gpuHit.t) <= 1e-4f * std::max(1.0f, cpu.t)) ++a.tClose;
    }
    return a;
}

TEST_F(PtWavefrontTest, TraversalRungsReturnTheCpuHits) {
    for (const bool spheres : {false, true}) {
        const scene::Scene scene = spheres ? sphereScene() : app::loadDefaultScene();
        const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(scene, nullptr, 1.0f);
        for (const render::PtTraversal rung :
             {render::PtTraversal::Bvh, render::PtTraversal::Bvh2, render::PtTraversal::RayQuery}) {
            const bool rq = rung == render::PtTraversal::RayQuery;
            if (rq && !rayQuery()) {
                std::printf("device lacks VK_KHR_ray_query: ray-query rung skipped\n");
                continue;
            }
            const std::string what = std::string(spheres ? "spheres " : "Cornell ") + render::traversalName(rung);
            for (uint32_t bounce : {0u, 1u}) {
                const render::PtCapture c = capture(scene, pts, rung, false, bounce);
                const HitAgreement a = compareWithCpu(pts, c);
                ASSERT_GT(a.rays, 500u) << what;
                EXPECT_GT(a.hits, a.rays / 8) << what << ": the view must hit geometry";
                // Our BVH (both walks) ports the CPU traversal operation for operation: identical. The driver's structures use
                // their own (watertight but differently rounded) test: a few edge rays may pick a neighbour.
                const double tolerance = rq ? 0.002 : 0.0;
                EXPECT_GE(double(a.sameTriangle), double(a.rays) * (1.0 - tolerance)) << what << " bounce " << bounce;
                EXPECT_GE(double(a.tClose), double(a.rays) * (1.0 - tolerance)) << what << " bounce " << bounce;
            }
        }
    }
}

}  // namespace
}  // namespace idk::test
