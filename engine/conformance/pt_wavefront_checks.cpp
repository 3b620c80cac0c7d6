// pt_wavefront_checks.cpp: the wavefront path tracer's kernels (engine/render/path_tracer.*, shaders_glsl/pathtrace/)
// against CPU oracles on the embedded Cornell box at 64x64, one sample, state captured after a bounce's shade stage:
// * "pathtrace/traversal" runs on each rung of the "ray traversal" ladder: native = VK_KHR_ray_query, fallback =
//   our GLSL BVH (both walks: 8-wide compressed and binary fp32). Every rung must return the CPU BVH's closest hit
//   (engine/bvh/traverse.hpp) for the camera rays and the first bounce's rays: our walks port the CPU traversal
//   operation for operation (identical triangle and t within 1e-4); the driver's structures use their own
//   watertight but differently rounded test, so up to 0.2% of ray-query rays may pick a neighbour at an edge.
// * "pathtrace/compaction" is exact: the next ray queue holds exactly the pixels whose path the shade stage
//   extended (a CPU filter over the path states), each once, and the indirect dispatch size is ceil(count / 64).
// * "pathtrace/ray sorting": the sort by (material, direction octant) before shading is a permutation of the
//   unsorted queue into non-decreasing key order, every key the CPU's for its hit, dead slots last, and compaction
//   after a sorted trace stays exact (bounces 0 and 1).
// Moved here from tests/conformance/pathtrace/wavefront_test.cpp (which keeps the sorting sweep on an asset scene,
// through expectSortedByKey).
#include <algorithm>
#include <cmath>
#include <set>

#include "app/default_scene.hpp"
#include "bvh/traverse.hpp"
#include "conformance/pt_wavefront_checks.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/path_tracer.hpp"

namespace idk::conformance {
namespace {

constexpr uint32_t kSize = 64;

render::PtCapture capture(CheckEnv& env, const scene::Scene& scene, const pathtrace::PathTraceScene& pts,
                          render::PtTraversal traversal, uint32_t bounce, bool sort = false) {
    render::PathTracerOptions options;
    options.traversal = traversal;
    options.sortRays = sort;
    render::PathTracer tracer(env.ctx, env.shaders, scene, pts, options);
    render::PathTraceSettings settings;
    settings.maxDepth = 4;
    settings.seed = 7;
    return tracer.capture(scene::defaultCamera(scene), kSize, kSize, settings, bounce);
}

}  // namespace

std::vector<uint32_t> queueItems(const std::vector<uint32_t>& queue) {
    const uint32_t count = queue.at(0);
    return std::vector<uint32_t>(queue.begin() + gpu::kPtQueueHeaderWords,
                                 queue.begin() + gpu::kPtQueueHeaderWords + count);
}

namespace {

// Primary and first-bounce hits of one traversal against the CPU BVH: at most `tolerance` of the rays may differ.
void hitsMatchCpu(CheckEnv& env, Verdict& v, const scene::Scene& scene, const pathtrace::PathTraceScene& pts,
                  render::PtTraversal traversal, double tolerance) {
    for (uint32_t bounce : {0u, 1u}) {
        const render::PtCapture c = capture(env, scene, pts, traversal, bounce);
        const std::string what = std::string(render::traversalName(traversal)) + " bounce " + std::to_string(bounce);
        size_t rays = 0, hits = 0, wrongTriangle = 0, wrongT = 0;
        for (uint32_t pixel : queueItems(c.queueIn)) {
            const gpu::GpuPtPath& ray = c.rays.at(pixel);
            bvh::Ray r;
            r.origin = ray.origin;
            r.direction = ray.direction;
            const bvh::Hit cpu = bvh::closestHit(pts.tlas, pts.instances, pts.blases, r);
            const gpu::GpuPtHit& gpuHit = c.hits.at(pixel);
            ++rays;
            hits += cpu.hit();
            const bool gpuFound = gpuHit.triangle != gpu::kPtInvalid;
            if (cpu.hit() != gpuFound) {
                ++wrongTriangle, ++wrongT;
                continue;
            }
            if (!cpu.hit()) continue;
            wrongTriangle += (cpu.triangleId != gpuHit.triangle || cpu.instanceId != gpuHit.instance) ? 1 : 0;
            const double error = std::abs(cpu.t - gpuHit.t) / std::max(1.0f, cpu.t);
            wrongT += error > 1e-4 ? 1 : 0;
            if (cpu.triangleId == gpuHit.triangle) v.recordError(error);
        }
        if (!v.expect(rays > 500, what + ": only " + std::to_string(rays) + " rays traced")) continue;
        v.expect(hits > rays / 8, what + ": the view must hit geometry");
        v.expect(double(wrongTriangle) <= double(rays) * tolerance,
                 what + ": " + std::to_string(wrongTriangle) + " of " + std::to_string(rays) + " rays hit another triangle");
        v.expect(double(wrongT) <= double(rays) * tolerance,
                 what + ": " + std::to_string(wrongT) + " of " + std::to_string(rays) + " rays have t off by > 1e-4");
    }
}

void traversalOnRung(CheckEnv& env, Verdict& v) {
    const scene::Scene cornell = app::loadDefaultScene();
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(cornell, nullptr, 1.0f);
    if (env.rung == vk::Rung::Native) {
        hitsMatchCpu(env, v, cornell, pts, render::PtTraversal::RayQuery, 0.002);
        return;
    }
    for (render::PtTraversal walk : {render::PtTraversal::Bvh, render::PtTraversal::Bvh2})
        hitsMatchCpu(env, v, cornell, pts, walk, 0.0);
}

void compaction(CheckEnv& env, Verdict& v) {
    const scene::Scene cornell = app::loadDefaultScene();
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(cornell, nullptr, 1.0f);
    for (uint32_t bounce : {0u, 1u, 2u}) {
        const render::PtCapture c = capture(env, cornell, pts, render::PtTraversal::Bvh, bounce);
        if (bounce == 0) v.expectEq(size_t(c.queueIn.at(0)), size_t(kSize) * kSize, "bounce 0: paths started (every pixel)");
        expectExactCompaction(v, c, "bounce " + std::to_string(bounce));
    }
}

void raySorting(CheckEnv& env, Verdict& v) {
    const scene::Scene cornell = app::loadDefaultScene();
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(cornell, nullptr, 1.0f);
    for (uint32_t bounce : {0u, 1u}) {
        const render::PtCapture sorted = capture(env, cornell, pts, render::PtTraversal::Bvh, bounce, true);
        const render::PtCapture plain = capture(env, cornell, pts, render::PtTraversal::Bvh, bounce, false);
        expectSortedByKey(v, pts, sorted, plain, "bounce " + std::to_string(bounce));
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

}  // namespace

void expectSortedByKey(Verdict& v, const pathtrace::PathTraceScene& pts, const render::PtCapture& sorted,
                       const render::PtCapture& plain, const std::string& what) {
    std::vector<uint32_t> a = queueItems(sorted.queueIn), b = queueItems(plain.queueIn);
    if (!v.expectEq(a.size(), b.size(), what + ": queue length sorted vs unsorted")) return;
    if (!v.expectEq(sorted.keys.size(), sorted.rays.size(), what + ": one key slot per pixel")) return;
    std::set<uint32_t> distinct;
    for (size_t i = 0; i < a.size(); ++i) {
        const uint32_t pixel = a[i];
        v.expectEq(sorted.keys[i], cpuKey(pts, sorted.hits.at(pixel), sorted.rays.at(pixel).direction),
                   what + ": key of slot " + std::to_string(i));
        if (i > 0) v.expect(sorted.keys[i - 1] <= sorted.keys[i], what + ": slot " + std::to_string(i) + " out of order");
        distinct.insert(sorted.keys[i]);
    }
    for (size_t i = a.size(); i < sorted.keys.size(); ++i)
        v.expectEq(sorted.keys[i], gpu::kPtSortKeyDead, what + ": dead slot " + std::to_string(i));
    v.expect(distinct.size() > 2, what + ": the scene must give several keys");
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    v.expect(a == b, what + ": sorting changed the set of rays");
    expectExactCompaction(v, sorted, what + " (sorted)");
}

void expectExactCompaction(Verdict& v, const render::PtCapture& c, const std::string& what) {
    const std::vector<uint32_t> in = queueItems(c.queueIn), out = queueItems(c.queueOut);
    std::set<uint32_t> expected;  // the CPU filter: rays of this bounce whose path shade extended
    for (uint32_t pixel : in)
        if (c.paths.at(pixel).flags & gpu::kPtPathAlive) expected.insert(pixel);
    const std::set<uint32_t> got(out.begin(), out.end());
    v.expectEq(got.size(), out.size(), what + ": pixels appended twice");
    v.expectEq(out.size(), expected.size(), what + ": compacted count");
    v.expect(got == expected, what + ": the compacted set differs from the CPU filter");
    if (!v.expectEq(c.argsOut.size(), size_t(3), what + ": indirect arguments")) return;
    v.expectEq(c.argsOut[0], (uint32_t(out.size()) + gpu::kPtGroupSize - 1) / gpu::kPtGroupSize, what + ": groups x");
    v.expectEq(c.argsOut[1], 1u, what + ": groups y");
    v.expectEq(c.argsOut[2], 1u, what + ": groups z");
    // The scenario itself: some paths die and some survive, or the check could not fail.
    v.expect(!expected.empty() && expected.size() < in.size(), what + ": no path died or none survived");
}

std::vector<Check> ptWavefrontChecks() {
    return {
        {"pathtrace/traversal", "ray-traversal", "CPU BVH hits: ours exact (t 1e-4), ray query 0.2% of rays", traversalOnRung},
        {"pathtrace/compaction", "", "exact", compaction},
        {"pathtrace/ray sorting", "", "exact (keys, order, permutation)", raySorting},
    };
}

}  // namespace idk::conformance
