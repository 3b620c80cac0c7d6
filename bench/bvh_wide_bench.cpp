// bvh_wide_bench.cpp: GPU ray traversal on the scenes and rays of bvh_bench.cpp (primary camera rays and diffuse
// bounce rays, split-0.3 BLAS): the 8-wide compressed BVH walk (include/bvh_traverse_wide.glsl, issue 19) against the
// driver's VK_KHR_ray_query (trace_rays_rq.comp.glsl over engine/vk/acceleration_structure.hpp), each in one dispatch
// timed by timestamp queries; the binary GLSL walk is bvh_bench.cpp's BM_BvhTraceGpu on the same rays. Mismatches
// are counted against our CPU traversal (same triangle and t; the ray query's closed interval and its own triangle
// test may differ on edges).
#include <array>
#include <functional>
#include <stdexcept>

#include "bvh/flatten.hpp"
#include "bvh/metrics.hpp"
#include "bvh/wide8.hpp"
#include "bvh_bench_scenes.hpp"
#include "render/bvh_wide_gpu.hpp"
#include "vk/acceleration_structure.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::bench {
namespace {

// The scenes of bvh_bench.cpp (bvhBenchScene rejects any other name).
constexpr std::array<const char*, 6> kWideScenes = {"bunny", "BrainStem", "ToyCar", "MetalRoughSpheres", "atrium",
                                                    "atrium_rotated"};

const char* rayKind(bool diffuse) { return diffuse ? "diffuse" : "primary"; }

bool skipWithError(benchmark::State& state, const std::string& why) {
    state.SkipWithError(why.c_str());
    for (auto _ : state) {
    }
    return false;
}

void BM_BvhTraceGpuWide(benchmark::State& state, const char* scene, bool diffuse) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    const BvhBenchScene s = bvhBenchScene(scene);
    const std::vector<gpu::GpuBlasNode> nodes = bvh::flatten(*s.blas);
    const std::vector<gpu::GpuBlasTriangle> refs = bvh::flattenTriangles(*s.blas, s.mesh->indices);
    const render::GpuBlas binary(ctx, {nodes, refs, s.mesh->positions, bvh::requiredStackSize(s.blas->nodes)}, "bench blas");
    const bvh::Bvh8 wide = bvh::buildBvh8(nodes, refs);
    const render::GpuWideBlas gpuWide(ctx, wide, binary, "bench wide blas");
    runGpuTrace(state, s, diffuse, [&](VkCommandBuffer cmd, VkDeviceAddress rays, VkDeviceAddress hits, uint32_t n) {
        render::recordTraceRaysWide(cmd, {ctx, *shaders()}, gpuWide, render::TraceMode::Closest, rays, hits, n);
    });
    state.counters["wide_nodes"] = double(wide.nodes.size());
    state.counters["stack"] = double(wide.stackSize);
    setBvhBenchRow(state,
                   {"bvh", s.input,
                    std::string("ours: GLSL closest hit, 8-wide compressed BVH (include/bvh_traverse_wide.glsl), ") +
                        rayKind(diffuse) + " rays, one dispatch, " + s.blasText,
                    ctx.info().name,
                    std::string("BM_BvhTraceGpuRayQuery/") + scene + "/" + rayKind(diffuse)},
                   "gpu", rayKind(diffuse));
}

void BM_BvhTraceGpuRayQuery(benchmark::State& state, const char* scene, bool diffuse) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    if (!vk::rayQuerySupported(ctx)) return void(skipWithError(state, "the device lacks VK_KHR_ray_query"));
    const BvhBenchScene s = bvhBenchScene(scene);
    // Lavapipe's ray query costs ~0.3 ms per ray on the 70k-triangle bunny (its acceleration structure behaves like
    // a linear scan at these sizes): the ~1M-triangle scene would take the better part of an hour per row.
    if (s.big && ctx.info().name.find("llvmpipe") != std::string::npos) {
        return void(skipWithError(state, "lavapipe's ray query on ~1M triangles takes too long for this run"));
    }
    const std::array<vk::AccelMesh, 1> meshes = {vk::AccelMesh{s.mesh->positions, s.mesh->indices}};
    const std::array<vk::AccelInstance, 1> instances = {vk::AccelInstance{}};
    const vk::AccelerationStructures accel(ctx, meshes, instances);
    const vk::Pipeline& pipeline = shaders()->compute({vk::ShaderId::bvh_trace_rays_rq_comp, {}, sizeof(gpu::BvhTracePush),
                                                       std::array<uint32_t, 3>{gpu::kBvhTraceGroupSize, 1, 1}});
    runGpuTrace(state, s, diffuse, [&](VkCommandBuffer cmd, VkDeviceAddress rays, VkDeviceAddress hits, uint32_t n) {
        gpu::BvhTracePush push{};
        push.tlas = accel.tlasAddress();
        push.rays = rays;
        push.hits = hits;
        push.count = n;
        ctx.bindless().bind(cmd);
        vk::bindPipeline(cmd, pipeline);
        vk::pushConstants(cmd, ctx, push);
        vkCmdDispatch(cmd, vk::groupCount(n, gpu::kBvhTraceGroupSize), 1, 1);
    });
    setBvhBenchRow(state,
                   {"bvh", s.input,
                    std::string("driver: VK_KHR_ray_query closest hit (bvh/trace_rays_rq.comp.glsl), opaque, ") +
                        rayKind(diffuse) + " rays, one dispatch, the driver's acceleration structure",
                    ctx.info().name + ", ray query", "", "peer"},
                   "gpu", rayKind(diffuse));
}

int registerWide() {
    for (const char* scene : kWideScenes) {
        const bool big = std::string(scene) == "MetalRoughSpheres";
        for (bool diffuse : {false, true}) {
            const std::string suffix = std::string("/") + scene + "/" + rayKind(diffuse);
            auto* wide = benchmark::RegisterBenchmark(("BM_BvhTraceGpuWide" + suffix).c_str(), BM_BvhTraceGpuWide, scene, diffuse);
            auto* query = benchmark::RegisterBenchmark(("BM_BvhTraceGpuRayQuery" + suffix).c_str(), BM_BvhTraceGpuRayQuery, scene, diffuse);
            for (auto* b : {wide, query}) b->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
            if (big) wide->Repetitions(3);
            // Lavapipe's ray query takes 20-100 s per row on bunny and ToyCar: 2 repetitions instead of the command
            // line's 5 keep `make bench` within minutes (a GPU's would not need this).
            query->Repetitions(2);
        }
    }
    return 0;
}
[[maybe_unused]] const int kRegistered = registerWide();

}  // namespace
}  // namespace idk::bench
