// bvh_gpu.hpp: BVHs on the GPU: upload of flattened BLAS/TLAS arrays (engine/bvh/flatten.hpp) with their
// triangles and vertex positions into buffers read by buffer device address (shaders_glsl/shared/bvh_trace_types.h),
// recording of the trace-rays kernel (closest/any hit through include/bvh_traverse.glsl) and of the per-level
// BLAS refit after the vertices moved. Port of IDKEngine's BVH GPU side (BVH.cs buffers, BLASRefit/compute.glsl).
// Works on the GPU structs only: engine/bvh builds and flattens, this file uploads and records.
#pragma once
#include <volk.h>

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "shader_manifest.hpp"
#include "shared/bvh_trace_types.h"
#include "vk/resources.hpp"

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk
namespace idk::scene {
struct Scene;
}  // namespace idk::scene

namespace idk::render {

// One BLAS as the GPU reads it. positions are packed vec3 (vertexStride 3) and are what the triangles'
// vertexIndices index; stackSize is bvh::requiredStackSize(blas.nodes) (the traversal's stack constant).
struct BlasData {
    std::span<const gpu::GpuBlasNode> nodes;          // bvh::flatten(blas)
    std::span<const gpu::GpuBlasTriangle> triangles;  // bvh::flattenTriangles(blas, indices)
    std::span<const glm::vec3> positions;
    uint32_t stackSize = 0;
};

// Owns the node, triangle and position buffers of one BLAS and its refit plan: the reachable non-empty nodes
// grouped by depth, deepest level first (a level's nodes depend only on deeper ones).
class GpuBlas {
public:
    GpuBlas(vk::Context& ctx, const BlasData& data, const std::string& name);
    ~GpuBlas();
    GpuBlas(const GpuBlas&) = delete;
    GpuBlas& operator=(const GpuBlas&) = delete;

    gpu::GpuBlasDesc desc() const;
    uint32_t stackSize() const { return stackSize_; }
    uint32_t nodeCount() const { return nodeCount_; }
    uint32_t vertexCount() const { return vertexCount_; }
    uint64_t gpuBytes() const;
    const vk::Buffer& positionBuffer() const { return positions_; }
    const vk::Buffer& nodeBuffer() const { return nodes_; }

    // Replaces the vertex positions (same count; throws std::invalid_argument otherwise). Uploads through the
    // transfer path and waits; record a refit afterwards.
    void uploadPositions(std::span<const glm::vec3> positions);
    std::vector<gpu::GpuBlasNode> downloadNodes() const;  // waits for the queue's work on the buffer

    const std::vector<std::pair<uint32_t, uint32_t>>& refitLevels() const { return refitLevels_; }  // (start, count)
    VkDeviceAddress refitOrderAddress() const { return refitOrder_.address; }

private:
    vk::Context& ctx_;
    vk::Buffer nodes_, triangles_, positions_, refitOrder_;
    uint32_t nodeCount_ = 0;
    uint32_t vertexCount_ = 0;
    uint32_t stackSize_ = 0;
    std::vector<std::pair<uint32_t, uint32_t>> refitLevels_;
};

// The nodes a refit updates, grouped by depth, deepest first (exposed for tests): nodes reachable from the root
// whose box is not empty (the padding node, the empty partner of a single-leaf root and an empty mesh's nodes stay
// untouched). `levels` receives (start, count) ranges of the returned order.
std::vector<uint32_t> refitOrder(std::span<const gpu::GpuBlasNode> nodes,
                                 std::vector<std::pair<uint32_t, uint32_t>>& levels);

// A TLAS over instances of GpuBlas objects (which must outlive it). nodes/instanceOrder come from
// bvh::flatten(tlas) / tlas.instanceOrder; instances[i].blasIndex indexes `blases`.
struct TlasData {
    std::span<const gpu::GpuTlasNode> nodes;
    std::span<const uint32_t> instanceOrder;
    std::span<const gpu::GpuBvhInstance> instances;
    std::span<const GpuBlas* const> blases;
    uint32_t stackSize = 0;  // bvh::requiredStackSize(tlas.nodes)
};

// The GPU form of one instance: both matrices as glm columns (the traversal uses worldToObject, which must be the
// CPU Tlas::worldToObject entry for identical results).
gpu::GpuBvhInstance makeGpuInstance(const glm::mat4& objectToWorld, const glm::mat4& worldToObject,
                                    uint32_t blasIndex);

class GpuTlas {
public:
    GpuTlas(vk::Context& ctx, const TlasData& data, const std::string& name);
    ~GpuTlas();
    GpuTlas(const GpuTlas&) = delete;
    GpuTlas& operator=(const GpuTlas&) = delete;

    VkDeviceAddress descAddress() const { return desc_.address; }  // a GpuTlasDesc
    uint32_t stackSize() const { return stackSize_; }
    uint32_t blasStackSize() const { return blasStackSize_; }     // the largest of its BLASes
    uint64_t gpuBytes() const;

private:
    vk::Context& ctx_;
    vk::Buffer nodes_, order_, instances_, blases_, desc_;
    uint32_t stackSize_ = 0;
    uint32_t blasStackSize_ = 0;
};

struct BvhKernels {
    vk::Context& ctx;
    vk::ShaderLibrary& shaders;
};

enum class TraceMode : uint32_t { Closest = gpu::kBvhTraceClosest, Any = gpu::kBvhTraceAny };

// Contract (as in compute_primitives.hpp): the caller has made the inputs visible to compute-shader reads and
// orders later reads of the outputs after COMPUTE_SHADER / SHADER_STORAGE_WRITE. Both functions bind the pipeline
// and the bindless set and push their constants.

// rays: GpuBvhRay[count], hits: GpuBvhHit[count], by device address. stackSize 0 uses the BVH's required stack;
// a smaller value is allowed (tests: overflow is flagged per ray, nothing is read or written out of bounds).
void recordTraceRays(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuBlas& blas, TraceMode mode,
                     VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count, uint32_t stackSize = 0);
void recordTraceRays(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuTlas& tlas, TraceMode mode,
                     VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count);
// The dispatch behind every trace-rays kernel (binary, 8-wide): stack sizes, trace mode and BLAS/TLAS as spec
// constants, the push constants, one invocation per ray; nothing for count 0.
void dispatchTraceKernel(VkCommandBuffer cmd, const BvhKernels& kernels, shaders::ShaderId kernel,
                         const gpu::BvhTracePush& push, TraceMode mode, bool useTlas, uint32_t blasStack,
                         uint32_t tlasStack);

// Recomputes every box of `blas` from its current positions, one dispatch per level with compute->compute
// barriers between levels. The result equals bvh::refitBlas on the same positions, flattened.
void recordRefit(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuBlas& blas);

// An indexed triangle mesh: the input of the BVH builders (bvh::Triangle i = positions[indices[i]]).
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;
};

// Every placed instance of a glTF scene in world space, one mesh: morph targets at the node's weights, skinned
// instances in the rest pose of their joints (glTF skinning with Node::jointMatrices). What `idk bvh`, the BVH
// conformance tests and benchmarks build over.
TriangleMesh worldTriangles(const scene::Scene& scene);
// One mesh's triangles in object space (all its primitives, morph targets at the mesh's default weights), for a
// BLAS per mesh under a TLAS.
TriangleMesh meshTriangles(const scene::Scene& scene, uint32_t mesh);

}  // namespace idk::render
