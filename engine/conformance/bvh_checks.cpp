// bvh_checks.cpp: the GLSL BVH traversal (include/bvh_traverse.glsl, the binary fp32 walk, and
// include/bvh_traverse_wide.glsl, the 8-wide compressed walk) against the CPU traversal (engine/bvh/traverse.hpp),
// closest hit and any hit, on scenes the engine builds itself so that `idk conformance` needs no asset files:
// * BLAS: the procedural atrium rotated 45 degrees with pre-splitting (a camera inside the hall, random rays,
//   shadow-ray segments), the unrotated atrium under axis-parallel and invalid rays, a sphere under rays aimed at
//   its vertices and edges (from inside, where every one must hit: watertightness; and from outside), the same
//   sphere moved 1e6 units away, a single triangle, an empty mesh and degenerate plus scene-spanning triangles;
// * TLAS: 48 rotated, non-uniformly scaled and mirrored instances of four BLASes (one empty).
// Rule (bvh_trace_support.hpp compareClosest): same hit/miss, triangle and instance, t within 1e-5 relative, ties
// only at equal t; any hit exact; no stack overflow. Both walks port the CPU code operation for operation, so the
// rotated atrium's hits must also be bit-identical (t, u, v). The asset-based sweeps (bunny, BrainStem, 1.3M rays)
// stay in tests/conformance/bvh/ and use the same comparison.
#include <glm/gtc/matrix_transform.hpp>

#include "bvh/tlas.hpp"
#include "bvh/wide8.hpp"
#include "conformance/bvh_trace_support.hpp"
#include "conformance/conformance.hpp"
#include "render/bvh_wide_gpu.hpp"

namespace idk::conformance {
namespace {

using render::TraceMode;

enum class Walk { Binary, Wide };

// One BLAS with both GPU forms.
struct Scene {
    UploadedBlas binary;
    std::unique_ptr<render::GpuWideBlas> wide;
    Scene(vk::Context& ctx, render::TriangleMesh mesh, const bvh::BuildOptions& options, const std::string& name)
        : binary(ctx, std::move(mesh), options, name) {
        const bvh::Bvh8 w = bvh::buildBvh8(bvh::flatten(binary.blas), bvh::flattenTriangles(binary.blas, binary.mesh.indices));
        wide = std::make_unique<render::GpuWideBlas>(ctx, w, *binary.gpu, name + " (8-wide)");
    }
};

// Closest and any hit of `rays` through `walk` against the CPU; records the verdict and returns the agreement.
Agreement traceBoth(CheckEnv& env, Verdict& v, Walk walk, const Scene& s, const std::vector<bvh::Ray>& rays,
                    const std::string& what) {
    RayBatch batch(env.ctx, env.shaders, 1u << 15);
    const auto trace = [&](TraceMode mode) {
        if (walk == Walk::Binary) return batch.trace(*s.binary.gpu, mode, rays);
        return batch.trace(rays, [&](VkCommandBuffer cmd, VkDeviceAddress r, VkDeviceAddress h, uint32_t n) {
            render::recordTraceRaysWide(cmd, {env.ctx, env.shaders}, *s.wide, mode, r, h, n);
        });
    };
    Agreement a = compareClosest(rays, trace(TraceMode::Closest), [&](const bvh::Ray& r) { return bvh::closestHit(s.binary.blas, r); });
    a.add(compareAny(rays, trace(TraceMode::Any), [&](const bvh::Ray& r) { return bvh::anyHit(s.binary.blas, r); }));
    a.rays = rays.size();
    v.recordError(a.maxRelativeT);
    v.expect(a.mismatches == 0, what + ": " + std::to_string(a.mismatches) + " closest-hit mismatches\n" + a.firstProblems);
    v.expect(a.anyMismatches == 0, what + ": " + std::to_string(a.anyMismatches) + " any-hit mismatches\n" + a.firstProblems);
    v.expect(a.overflows == 0, what + ": " + std::to_string(a.overflows) + " stack overflows");
    return a;
}

render::TriangleMesh sphere() { return fromIndexed(bvh::makeIcosphere(4)); }

// Rays from points near the centre of the unit sphere aimed exactly at a vertex or an edge point of a triangle.
std::vector<bvh::Ray> insideAimedRays(const std::vector<bvh::Triangle>& tris, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<bvh::Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        const bvh::Triangle& t = tris[rng() % tris.size()];
        const glm::vec3 target = i % 3 == 0 ? t.v0 : t.v1 + u(rng) * (t.v2 - t.v1);
        const glm::vec3 origin = 0.3f * u(rng) * randomUnitVector(rng);
        rays[i] = {origin, target - origin};
    }
    return rays;
}

void blasAgainstCpu(CheckEnv& env, Verdict& v, Walk walk) {
    bvh::IndexedMesh atrium = bvh::makeAtrium();
    const glm::mat4 rotation = bvh::rotationAboutCenter(atrium, 45.0f);
    bvh::rotateAboutCenter(atrium, 45.0f);
    const Scene rotated(env.ctx, fromIndexed(atrium), bvh::BuildOptions{.splitFactor = 0.3f}, "rotated atrium");
    const bvh::Box box = rotated.binary.blas.bounds();
    std::vector<bvh::Ray> rays = cameraRays(glm::vec3(rotation * glm::vec4(-25.0f, 5.0f, -8.0f, 1.0f)),
                                            glm::vec3(rotation * glm::vec4(20.0f, 10.0f, 5.0f, 1.0f)), 96, 96);
    append(rays, randomRays(box, 12000, 21));
    append(rays, segmentRays(box, 8000, 22));
    const Agreement a = traceBoth(env, v, walk, rotated, rays, "rotated atrium, split 0.3");
    v.expect(a.hits > rays.size() / 2, "rotated atrium: too few hits for a real test");
    v.expect(a.bitExact == a.hits, "rotated atrium: " + std::to_string(a.hits - a.bitExact) +
                                       " hits not bit-identical to the CPU (t, u, v)");

    const Scene axisAtrium(env.ctx, fromIndexed(bvh::makeAtrium()), {}, "atrium");
    v.expect(traceBoth(env, v, walk, axisAtrium, axisRays(axisAtrium.binary.blas.bounds(), 12000, 31),
                       "atrium, axis-parallel and invalid rays").hits > 4000, "atrium: too few axis-parallel hits");

    // From inside a closed convex mesh every ray crosses the surface, so a miss is a leak; from outside, a ray at a
    // silhouette vertex may only graze it (either answer is right there, the CPU decides).
    const Scene ball(env.ctx, sphere(), {}, "sphere");
    const Agreement inside = traceBoth(env, v, walk, ball, insideAimedRays(ball.binary.triangles, 10000, 41),
                                       "sphere, rays from inside aimed at vertices and edges");
    v.expect(inside.hits == 10000, "sphere: " + std::to_string(10000 - inside.hits) + " rays from inside leaked");
    traceBoth(env, v, walk, ball, vertexEdgeRays(ball.binary.triangles, ball.binary.blas.bounds(), 5000, 44),
              "sphere, rays from outside aimed at vertices and edges");
    render::TriangleMesh far = sphere();
    for (glm::vec3& p : far.positions) p += glm::vec3(1e6f, -1e6f, 1e6f);
    const Scene offset(env.ctx, far, {}, "sphere at 1e6");
    std::vector<bvh::Ray> farRays = randomRays(offset.binary.blas.bounds(), 5000, 42);
    append(farRays, vertexEdgeRays(offset.binary.triangles, offset.binary.blas.bounds(), 5000, 43));
    v.expect(traceBoth(env, v, walk, offset, farRays, "sphere offset by 1e6").hits > 5000, "sphere at 1e6: too few hits");

    const bvh::Box unit{{-2, -2, -2}, {2, 2, 2}};
    const Scene single(env.ctx, render::TriangleMesh{{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}}}, {}, "single");
    v.expect(traceBoth(env, v, walk, single, randomRays(unit, 4000, 51), "single triangle").hits > 100,
             "single triangle: too few hits");
    const Scene none(env.ctx, render::TriangleMesh{}, {}, "empty");
    const Agreement empty = traceBoth(env, v, walk, none, randomRays(unit, 1000, 52), "empty mesh");
    v.expect(empty.hits + empty.anyHits == 0, "empty mesh: the CPU oracle reports hits");
    render::TriangleMesh mixed = sphere();
    const uint32_t base = uint32_t(mixed.positions.size());
    mixed.positions.insert(mixed.positions.end(), {{-1, -1, -1}, {1, 1, 1}, {0, 0, 0}, {5, 5, 5}, {-5, 0.1f, -5},
                                                   {5, 0.1f, -5}, {0, 0.1f, 8}});
    mixed.indices.push_back({base, base + 1, base + 2});      // collinear: zero area
    mixed.indices.push_back({base + 3, base + 3, base + 3});  // a point
    mixed.indices.push_back({base + 4, base + 5, base + 6});  // spans the whole sphere
    const Scene degenerate(env.ctx, mixed, {}, "sphere + degenerate + huge");
    traceBoth(env, v, walk, degenerate, randomRays(degenerate.binary.blas.bounds(), 8000, 53),
              "sphere with degenerate and huge triangles");
}

void binaryBlas(CheckEnv& env, Verdict& v) { blasAgainstCpu(env, v, Walk::Binary); }
void wideBlas(CheckEnv& env, Verdict& v) { blasAgainstCpu(env, v, Walk::Wide); }

void tlasAgainstCpu(CheckEnv& env, Verdict& v, Walk walk) {
    std::vector<std::unique_ptr<Scene>> scenes;
    scenes.push_back(std::make_unique<Scene>(env.ctx, fromIndexed(bvh::makeAtrium()), bvh::BuildOptions{}, "atrium"));
    scenes.push_back(std::make_unique<Scene>(env.ctx, fromIndexed(bvh::makeIcosphere(3)), bvh::BuildOptions{}, "sphere"));
    scenes.push_back(std::make_unique<Scene>(env.ctx, render::TriangleMesh{}, bvh::BuildOptions{}, "empty"));
    scenes.push_back(std::make_unique<Scene>(env.ctx, fromIndexed(bvh::makeBox(glm::vec3(-1), glm::vec3(1), 4)),
                                             bvh::BuildOptions{.splitFactor = 0.3f}, "box"));
    std::vector<bvh::Blas> cpuBlases;
    std::vector<const render::GpuBlas*> binaries;
    std::vector<const render::GpuWideBlas*> wides;
    for (const auto& s : scenes) {
        cpuBlases.push_back(s->binary.blas);
        binaries.push_back(s->binary.gpu.get());
        wides.push_back(s->wide.get());
    }
    std::vector<bvh::BlasInstance> instances;
    std::mt19937 rng(72);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (uint32_t i = 0; i < 48; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1.0f), 20.0f * glm::vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, 6.28f * u(rng), randomUnitVector(rng));
        m = glm::scale(m, glm::vec3(0.5f + 2.0f * u(rng), 0.5f + 2.0f * u(rng), (i % 5 == 0 ? -1.0f : 1.0f) * (0.5f + u(rng))));
        if (i % 4 == 0) m = glm::scale(m, glm::vec3(0.05f));  // the atrium is ~60 units wide
        instances.push_back({m, i % 4});
    }
    const bvh::Tlas tlas = bvh::buildTlas(instances, cpuBlases);
    std::vector<gpu::GpuBvhInstance> gpuInstances;
    for (size_t i = 0; i < instances.size(); ++i)
        gpuInstances.push_back(render::makeGpuInstance(instances[i].objectToWorld, tlas.worldToObject[i], instances[i].blasIndex));
    const std::vector<gpu::GpuTlasNode> nodes = bvh::flatten(tlas);
    const uint32_t stack = bvh::requiredStackSize(tlas.nodes);
    const render::GpuTlas binaryTlas(env.ctx, {nodes, tlas.instanceOrder, gpuInstances, binaries, stack}, "check tlas");
    const render::GpuWideTlas wideTlas(env.ctx, nodes, tlas.instanceOrder, gpuInstances, wides, stack, "check wide tlas");
    bvh::Box world;
    for (const bvh::Box& w : tlas.worldBoxes) world.grow(w);
    const std::vector<bvh::Ray> rays = randomRays(world, 20000, 73);

    RayBatch batch(env.ctx, env.shaders, 1u << 15);
    const auto trace = [&](TraceMode mode) {
        if (walk == Walk::Binary) return batch.trace(binaryTlas, mode, rays);
        return batch.trace(rays, [&](VkCommandBuffer cmd, VkDeviceAddress r, VkDeviceAddress h, uint32_t n) {
            render::recordTraceRaysWide(cmd, {env.ctx, env.shaders}, wideTlas, mode, r, h, n);
        });
    };
    Agreement a = compareClosest(rays, trace(TraceMode::Closest), [&](const bvh::Ray& r) {
        return bvh::closestHit(tlas, instances, cpuBlases, r);
    });
    a.add(compareAny(rays, trace(TraceMode::Any), [&](const bvh::Ray& r) { return bvh::anyHit(tlas, instances, cpuBlases, r); }));
    v.recordError(a.maxRelativeT);
    v.expect(a.mismatches == 0, std::to_string(a.mismatches) + " closest-hit mismatches\n" + a.firstProblems);
    v.expect(a.anyMismatches == 0, std::to_string(a.anyMismatches) + " any-hit mismatches\n" + a.firstProblems);
    v.expect(a.overflows == 0, std::to_string(a.overflows) + " stack overflows");
    v.expect(a.hits > rays.size() / 5, "too few hits for a real test: " + std::to_string(a.hits));
}

void binaryTlas(CheckEnv& env, Verdict& v) { tlasAgainstCpu(env, v, Walk::Binary); }
void wideTlas(CheckEnv& env, Verdict& v) { tlasAgainstCpu(env, v, Walk::Wide); }

}  // namespace

std::vector<Check> bvhChecks() {
    const std::string rule = "same triangle, t 1e-5 relative (ties at equal t); any hit exact";
    return {
        {"bvh/blas binary", "", rule + "; rotated atrium bit-identical", binaryBlas},
        {"bvh/blas 8-wide", "", rule + "; rotated atrium bit-identical", wideBlas},
        {"bvh/tlas binary", "", rule, binaryTlas},
        {"bvh/tlas 8-wide", "", rule, wideTlas},
    };
}

}  // namespace idk::conformance
