// bvh_wide_gpu.hpp: the 8-wide compressed BLAS (engine/bvh/wide8.hpp) on the GPU: its node and regrouped
// triangle-reference buffers (the vertex positions are the binary GpuBlas's, so a refit's new positions are seen by
// both), re-upload of the nodes after a refit (bvh::refitBvh8 on the downloaded binary nodes), a TLAS over wide
// BLASes, and the recording of trace_rays_wide.comp.glsl (include/bvh_traverse_wide.glsl).
#pragma once
#include <volk.h>

#include <cstdint>
#include <span>
#include <string>

#include "bvh/wide8.hpp"
#include "render/bvh_gpu.hpp"
#include "shared/bvh_trace_types.h"
#include "vk/resources.hpp"

namespace idk::render {

class GpuWideBlas {
public:
    // `binary` (the same BLAS, flattened) provides the positions and must outlive this object.
    GpuWideBlas(vk::Context& ctx, const bvh::Bvh8& wide, const GpuBlas& binary, const std::string& name);
    ~GpuWideBlas();
    GpuWideBlas(const GpuWideBlas&) = delete;
    GpuWideBlas& operator=(const GpuWideBlas&) = delete;

    // nodes: GpuWideNode[], triangles: the wide references, positions: the binary BLAS's.
    gpu::GpuBlasDesc desc() const;
    uint32_t stackSize() const { return stackSize_; }
    uint32_t nodeCount() const { return nodeCount_; }
    uint64_t gpuBytes() const { return nodes_.size + triangles_.size; }

    // After a refit: the re-quantised nodes (bvh::refitBvh8), same count (throws std::invalid_argument otherwise).
    // Uploads through the transfer path and waits.
    void uploadNodes(std::span<const gpu::GpuWideNode> nodes);

private:
    vk::Context& ctx_;
    vk::Buffer nodes_, triangles_;
    VkDeviceAddress positions_ = 0;
    uint32_t nodeCount_ = 0;
    uint32_t stackSize_ = 0;
};

// GPU refit of `binary` (recordRefit, waited for), download of its nodes and re-quantisation of `wide` (and its
// upload to `gpuWide`): the wide BVH after the vertices moved. `wide` must have been built from `binary`'s nodes.
void refitWide(vk::Context& ctx, const BvhKernels& kernels, const GpuBlas& binary, bvh::Bvh8& wide, GpuWideBlas& gpuWide);

// A binary TLAS whose instances reference wide BLASes (the same data as GpuTlas otherwise).
class GpuWideTlas {
public:
    GpuWideTlas(vk::Context& ctx, std::span<const gpu::GpuTlasNode> nodes, std::span<const uint32_t> instanceOrder,
                std::span<const gpu::GpuBvhInstance> instances, std::span<const GpuWideBlas* const> blases,
                uint32_t stackSize, const std::string& name);
    ~GpuWideTlas();
    GpuWideTlas(const GpuWideTlas&) = delete;
    GpuWideTlas& operator=(const GpuWideTlas&) = delete;

    VkDeviceAddress descAddress() const { return desc_.address; }  // a GpuTlasDesc
    uint32_t stackSize() const { return stackSize_; }
    uint32_t blasStackSize() const { return blasStackSize_; }     // the largest of its BLASes

private:
    vk::Context& ctx_;
    vk::Buffer nodes_, order_, instances_, blases_, desc_;
    uint32_t stackSize_ = 0;
    uint32_t blasStackSize_ = 0;
};

// As recordTraceRays (bvh_gpu.hpp), with the wide walk. stackSize 0 uses the BLAS's Bvh8::stackSize.
void recordTraceRaysWide(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuWideBlas& blas, TraceMode mode,
                         VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count, uint32_t stackSize = 0);
void recordTraceRaysWide(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuWideTlas& tlas, TraceMode mode,
                         VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count);

}  // namespace idk::render
