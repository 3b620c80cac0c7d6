// pt_pose_bench.cpp: the path tracer's animated geometry (issue 16 item 4): posing a skinned scene at a new time
// with PathTracer::setPose (the rasterizer's skinning compute, pt_pose, GPU refit of the posed BLASes with the
// 8-wide re-quantisation, TLAS rebuilt; render/pt_pose.hpp) against rebuilding the path-tracing geometry from
// scratch as the tracer did before (CPU skinning into world-space copies, SAH BLAS and TLAS builds, upload:
// pathtrace::buildPathTraceScene + uploadPtGeometry). Fox (one skinned mesh) and BrainStem (many skinned
// meshes); wall time per pose, each iteration at another time of the first animation. Texture decoding, lights
// and environment tables are not part of either row (the refit row never touches them).
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>

#include "bench_support.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/path_tracer.hpp"
#include "render/pt_geometry.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::bench {
namespace {

double poseTime(int64_t iteration) { return 0.1 + 0.07 * double(iteration % 16); }

void BM_PtPose(benchmark::State& state, const char* name, bool refit) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    scene::Scene rest = scene::loadGltf(sharedScene(name));
    // Geometry only: buildPathTraceScene would otherwise decode the textures in the rebuild row (the refit row
    // never touches them), and that is not what a pose costs.
    rest.textures.clear();
    scene::Scene posed = rest;
    size_t triangles = 0;
    for (const scene::Instance& inst : rest.instances)
        for (const scene::Primitive& p : rest.meshes[inst.mesh].primitives) triangles += p.indices.size() / 3;
    std::unique_ptr<render::PathTracer> tracer;
    if (refit) {
        render::PathTracerOptions options;
        options.traversal = render::PtTraversal::Bvh;
        options.environment = std::filesystem::path();  // constant environment: no HDR tables to build
        tracer = std::make_unique<render::PathTracer>(ctx, *shaders(), rest, options);
    }
    int64_t iteration = 0;
    for (auto _ : state) {
        scene::evaluateAnimations(posed, poseTime(iteration++), 0);
        const auto start = std::chrono::steady_clock::now();
        if (refit) {
            tracer->setPose(posed);
        } else {
            const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(posed, nullptr, 0.0f);
            render::PtGpuGeometry geometry = render::uploadPtGeometry(ctx, pts, true);
            render::destroyPtGeometry(ctx, geometry);
        }
        state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    const std::string input = std::string(name) + ".glb, " + std::to_string(triangles) + " triangles, skinned";
    setRow(state, {"pathtrace animation", input,
                   refit ? "ours: GPU skinning + pt_pose + BLAS refit (wide re-quantised) + TLAS rebuild"
                         : "rebuild: CPU skinning, SAH BLAS + wide + TLAS builds, upload",
                   ctx.info().name, refit ? std::string("BM_PtPose/") + name + "/rebuild" : "", refit ? "ours" : "peer",
                   "manual"});
}

int registerAll() {
    for (const char* name : {"Fox", "BrainStem"})
        for (bool refit : {true, false})
            benchmark::RegisterBenchmark((std::string("BM_PtPose/") + name + (refit ? "/refit" : "/rebuild")).c_str(),
                                         BM_PtPose, name, refit)
                ->UseManualTime()
                ->Iterations(4)
                ->Unit(benchmark::kMillisecond);
    return 0;
}
[[maybe_unused]] const int kRegistered = registerAll();

}  // namespace
}  // namespace idk::bench
