// bvh_wide_gpu.cpp: wide BLAS/TLAS buffers and the recording of trace_rays_wide.comp.glsl (outside the render graph,
// like bvh_gpu.cpp: callers order inputs and outputs as recordTraceRays documents).
#include "render/bvh_wide_gpu.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

constexpr const char* kCategory = "bvh";

// Read through device addresses only; storage is the honest usage. Never zero-sized (16 bytes, never read).
template <class T>
vk::Buffer createFilled(vk::Context& ctx, std::span<const T> values, const std::string& name) {
    vk::Buffer buffer = ctx.createBuffer({std::max<VkDeviceSize>(values.size_bytes(), 16), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          vk::MemoryUsage::GpuOnly, name, kCategory});
    if (!values.empty()) vk::uploadBuffer(ctx, buffer, values);
    return buffer;
}

}  // namespace

GpuWideBlas::GpuWideBlas(vk::Context& ctx, const bvh::Bvh8& wide, const GpuBlas& binary, const std::string& name)
    : ctx_(ctx), positions_(binary.positionBuffer().address), nodeCount_(uint32_t(wide.nodes.size())),
      stackSize_(wide.stackSize) {
    if (wide.nodes.empty()) throw std::invalid_argument("GpuWideBlas " + name + ": a wide BLAS has a root node");
    nodes_ = createFilled(ctx, std::span<const gpu::GpuWideNode>(wide.nodes), name + " wide nodes");
    triangles_ = createFilled(ctx, std::span<const gpu::GpuBlasTriangle>(wide.triangles), name + " wide triangles");
}

GpuWideBlas::~GpuWideBlas() {
    ctx_.destroyDeferred(nodes_);
    ctx_.destroyDeferred(triangles_);
}

gpu::GpuBlasDesc GpuWideBlas::desc() const { return {nodes_.address, triangles_.address, positions_, 3u, nodeCount_}; }

void GpuWideBlas::uploadNodes(std::span<const gpu::GpuWideNode> nodes) {
    if (nodes.size() != nodeCount_) {
        throw std::invalid_argument("GpuWideBlas::uploadNodes: " + std::to_string(nodes.size()) + " nodes given, the BLAS has " +
                                    std::to_string(nodeCount_));
    }
    vk::uploadBuffer(ctx_, nodes_, nodes);
}

void refitWide(vk::Context& ctx, const BvhKernels& kernels, const GpuBlas& binary, bvh::Bvh8& wide, GpuWideBlas& gpuWide) {
    ctx.runImmediate([&](VkCommandBuffer cmd) { recordRefit(cmd, kernels, binary); });
    const std::vector<gpu::GpuBlasNode> nodes = binary.downloadNodes();
    bvh::refitBvh8(wide, nodes);
    gpuWide.uploadNodes(wide.nodes);
}

GpuWideTlas::GpuWideTlas(vk::Context& ctx, std::span<const gpu::GpuTlasNode> nodes, std::span<const uint32_t> instanceOrder,
                         std::span<const gpu::GpuBvhInstance> instances, std::span<const GpuWideBlas* const> blases,
                         uint32_t stackSize, const std::string& name)
    : ctx_(ctx), stackSize_(stackSize) {
    if (nodes.size() < 4) throw std::invalid_argument("GpuWideTlas " + name + ": a flattened TLAS has at least 4 nodes");
    std::vector<gpu::GpuBlasDesc> descs;
    for (const GpuWideBlas* blas : blases) {
        descs.push_back(blas->desc());
        blasStackSize_ = std::max(blasStackSize_, blas->stackSize());
    }
    for (const gpu::GpuBvhInstance& inst : instances) {
        if (inst.blasIndex >= descs.size()) throw std::invalid_argument("GpuWideTlas " + name + ": instance BLAS index out of range");
    }
    nodes_ = createFilled(ctx, nodes, name + " nodes");
    order_ = createFilled(ctx, instanceOrder, name + " instance order");
    instances_ = createFilled(ctx, instances, name + " instances");
    blases_ = createFilled(ctx, std::span<const gpu::GpuBlasDesc>(descs), name + " wide BLAS descriptors");
    const gpu::GpuTlasDesc desc{nodes_.address, order_.address, instances_.address, blases_.address};
    desc_ = createFilled(ctx, std::span<const gpu::GpuTlasDesc>(&desc, 1), name + " descriptor");
}

GpuWideTlas::~GpuWideTlas() {
    for (vk::Buffer* b : {&nodes_, &order_, &instances_, &blases_, &desc_}) ctx_.destroyDeferred(*b);
}

void recordTraceRaysWide(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuWideBlas& blas, TraceMode mode,
                         VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count, uint32_t stackSize) {
    gpu::BvhTracePush push{};
    push.blas = blas.desc();
    push.rays = rays;
    push.hits = hits;
    push.count = count;
    dispatchTraceKernel(cmd, kernels, vk::ShaderId::bvh_trace_rays_wide_comp, push, mode, false,
                        stackSize != 0 ? stackSize : blas.stackSize(), 1);
}

void recordTraceRaysWide(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuWideTlas& tlas, TraceMode mode,
                         VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count) {
    gpu::BvhTracePush push{};
    push.tlas = tlas.descAddress();
    push.rays = rays;
    push.hits = hits;
    push.count = count;
    dispatchTraceKernel(cmd, kernels, vk::ShaderId::bvh_trace_rays_wide_comp, push, mode, true, tlas.blasStackSize(),
                        tlas.stackSize());
}

}  // namespace idk::render
