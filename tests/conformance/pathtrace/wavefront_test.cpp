// wavefront_test.cpp: the wavefront path tracer's ray sorting on an asset scene, MetalRoughSpheresNoTextures at
// 64x64 (one sample, state captured after a bounce's shade stage), by the registered check's oracle
// (conformance::expectSortedByKey: a permutation of the unsorted queue in non-decreasing key order, the CPU's keys,
// dead slots last, exact compaction after it). Sorting, compaction and every traversal rung on the embedded Cornell
// box are registered checks (engine/conformance/pt_wavefront_checks.cpp: `idk conformance`, and ctest through
// tests/conformance/registry/).
#include <gtest/gtest.h>

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

TEST_F(PtWavefrontTest, SortingIsAPermutationOrderedByKey) {
    const scene::Scene spheres = sphereScene();
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(spheres, nullptr, 1.0f, glm::vec3(0.5f));
    for (uint32_t bounce : {0u, 1u}) {
        const std::string what = "spheres bounce " + std::to_string(bounce);
        conformance::Verdict v;
        conformance::expectSortedByKey(v, pts, capture(spheres, pts, render::PtTraversal::Bvh, true, bounce),
                                       capture(spheres, pts, render::PtTraversal::Bvh, false, bounce), what);
        EXPECT_TRUE(v.passed()) << v.messages();
    }
}

}  // namespace
}  // namespace idk::test
