// wavefront_test.cpp: the wavefront path tracer's ray sorting on MetalRoughSpheresNoTextures at 64x64 (one sample,
// state captured after a bounce's shade stage): sorting permutes the queue (the same set as without sorting) into
// non-decreasing key order, the keys equal the CPU's (material, direction octant) of each hit, dead slots sort last,
// and compaction after a sorted trace is still exact. Compaction on the Cornell box and every traversal rung against
// the CPU BVH are registered checks (engine/conformance/pt_wavefront_checks.cpp: `idk conformance`, and ctest
// through tests/conformance/registry/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "conformance/pt_wavefront_checks.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/path_tracer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"

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
};

// Compaction after a sorted trace, by the registry's oracle.
void expectExactCompaction(const render::PtCapture& c, const std::string& what) {
    conformance::Verdict v;
    conformance::expectExactCompaction(v, c, what);
    EXPECT_TRUE(v.passed()) << v.messages();
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
        std::vector<uint32_t> a = conformance::queueItems(sorted.queueIn), b = conformance::queueItems(plain.queueIn);
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

}  // namespace
}  // namespace idk::test
