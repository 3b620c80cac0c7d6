// pt_pose.cpp: the GPU pose of the path tracer's skinned and morphed geometry (see pt_pose.hpp): the pose ranges,
// the pt_pose pass, and the refit of the posed BLASes after it.
#include "render/pt_pose.hpp"

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "graph/render_graph.hpp"
#include "graph/resource_pool.hpp"
#include "passes/passes.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/bvh_gpu.hpp"
#include "render/gpu_scene.hpp"
#include "render/pt_geometry.hpp"
#include "render/vk_graph_backend.hpp"
#include "shared/pt_pose_types.h"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

graph::BufferHandle importBuffer(graph::RenderGraph& graph, const std::string& name, const vk::Buffer& buffer) {
    graph::PhysicalBuffer p;
    p.buffer = buffer.buffer;
    p.size = buffer.size;
    p.address = buffer.address;
    // Nothing earlier to wait for: uploads end with a full barrier, and so does every pose submission (below).
    return graph.importBuffer(name, p, graph::ResourceState{});
}

// PtGpuGeometry::buffers holds [vertices, triangles, materials] per geometry, in geometry order.
const vk::Buffer& shadingVertices(const PtGpuGeometry& g, uint32_t geometry) { return g.buffers.at(3 * size_t(geometry)); }

}  // namespace

std::vector<PtPoseRange> ptPoseRanges(const scene::Scene& scene, const pathtrace::PathTraceScene& pts,
                                      const GpuSceneData& data) {
    // GpuSceneData::meshes: one GpuMesh per primitive, mesh after mesh (packGpuScene).
    std::vector<uint32_t> firstMesh;
    uint32_t primitives = 0;
    for (const scene::Mesh& mesh : scene.meshes) {
        firstMesh.push_back(primitives);
        primitives += uint32_t(mesh.primitives.size());
    }
    if (primitives != data.meshes.size())
        throw std::invalid_argument("ptPoseRanges: the GPU scene was not packed from this scene");
    std::vector<PtPoseRange> ranges;
    for (uint32_t i : pts.gpuPosedInstances) {
        const scene::Instance& inst = scene.instances.at(i);
        const scene::Mesh& mesh = scene.meshes.at(inst.mesh);
        uint32_t dest = 0;
        for (uint32_t p = 0; p < mesh.primitives.size(); ++p) {
            const auto count = uint32_t(mesh.primitives[p].positions.size());
            auto copy = data.deformation.copies.find({inst.node, firstMesh[inst.mesh] + p});
            if (copy != data.deformation.copies.end())
                ranges.push_back({pts.instances.at(i).blasIndex, uint32_t(copy->second), dest, count});
            dest += count;
        }
    }
    return ranges;
}

void posePtGeometry(vk::Context& ctx, vk::ShaderLibrary& shaders, GpuScene& gpuScene,
                    std::span<const PtPoseRange> ranges, PtGpuGeometry& geometry) {
    GpuAnimation* animation = gpuScene.animation();
    if (ranges.empty() || !animation) return;
    std::map<uint32_t, size_t> targetOf;  // posed geometry -> index of its (vertices, positions) handle pair
    for (const PtPoseRange& r : ranges) {
        if (r.geometry >= geometry.geometryBlas.size() || geometry.geometryBlas[r.geometry] < 0)
            throw std::invalid_argument("posePtGeometry: range of a geometry without a BLAS");
        targetOf.emplace(r.geometry, targetOf.size());
    }

    VkGraphBackend backend(ctx);
    graph::ResourcePool pool(backend);
    graph::RenderGraph graph(pool, {1, 1});
    passes::SceneBuffers sb;
    sb.vertices = importBuffer(graph, "scene vertices", gpuScene.vertices());
    sb.instances = importBuffer(graph, "scene instances", gpuScene.instances());
    animation->addPasses(graph, shaders, 0, 1, sb);  // skinning into the deformed copies

    auto targets = std::make_shared<std::vector<graph::BufferHandle>>(2 * targetOf.size());
    for (const auto& [geo, k] : targetOf) {
        const GpuBlas& blas = *geometry.blases[size_t(geometry.geometryBlas[geo])];
        (*targets)[2 * k] = importBuffer(graph, "pt vertices " + std::to_string(geo), shadingVertices(geometry, geo));
        (*targets)[2 * k + 1] = importBuffer(graph, "pt blas positions " + std::to_string(geo), blas.positionBuffer());
    }
    const graph::BufferHandle source = sb.vertices;
    std::vector<PtPoseRange> work(ranges.begin(), ranges.end());
    graph.addPass(
        "pt_pose",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(source, graph::Access::StorageRead, kCs);
            for (graph::BufferHandle& t : *targets) t = b.write(t, graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, source, targets, targetOf, work](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            vk::ComputePipelineDesc desc;
            desc.shader = vk::ShaderId::pathtrace_pose_comp;
            desc.pushBytes = sizeof(gpu::PtPosePush);
            desc.localSize = {gpu::kPtPoseGroupSize, 1, 1};
            vk::bindPipeline(cmd, shaders.compute(desc));
            ctx.bindless().bind(cmd);
            for (const PtPoseRange& r : work) {
                const size_t k = targetOf.at(r.geometry);
                gpu::PtPosePush push{};
                push.source = pc.buffer(source).address;
                push.vertices = pc.buffer((*targets)[2 * k]).address;
                push.positions = pc.buffer((*targets)[2 * k + 1]).address;
                push.sourceFirst = r.sourceFirst;
                push.destFirst = r.destFirst;
                push.count = r.count;
                vk::pushConstants(cmd, ctx, push);
                vkCmdDispatch(cmd, vk::groupCount(r.count, gpu::kPtPoseGroupSize), 1, 1);
            }
        });
    for (graph::BufferHandle t : *targets) graph.markOutput(t);

    // The refit runs outside the graph (recordRefit records its own level barriers), after the pose's writes.
    const BvhKernels kernels{ctx, shaders};
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        graph.execute(cmd);
        vk::computeToComputeBarrier(cmd);
        for (const auto& [geo, k] : targetOf) recordRefit(cmd, kernels, *geometry.blases[size_t(geometry.geometryBlas[geo])]);
        // Later submissions (the trace, the next pose) read what this one wrote.
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    });

    // The TLAS needs the refit root boxes, and the 8-wide copy its re-quantised nodes (bvh::refitBvh8 runs on the
    // CPU: the wide layout has no GPU refit; on a real GPU this readback is the cost to remove first).
    for (const auto& [geo, k] : targetOf) {
        const auto b = size_t(geometry.geometryBlas[geo]);
        const std::vector<gpu::GpuBlasNode> nodes = geometry.blases[b]->downloadNodes();
        geometry.bounds[geo] = bvh::Box{nodes[gpu::kBvhRootNode].min, nodes[gpu::kBvhRootNode].max};
        if (b < geometry.wideBlases.size()) {
            bvh::refitBvh8(geometry.wideTrees[b], nodes);
            geometry.wideBlases[b]->uploadNodes(geometry.wideTrees[b].nodes);
        }
    }
}

}  // namespace idk::render
