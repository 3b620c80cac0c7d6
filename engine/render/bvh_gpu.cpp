// bvh_gpu.cpp: BVH buffers on the GPU, the refit plan (nodes by depth), and the recording of the trace-rays and
// refit kernels (shaders_glsl/bvh/). These run outside the render graph, hence the refit's own barriers.
#include "render/bvh_gpu.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "scene/scene.hpp"
#include "shared/bindings.h"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

// SYNC: this runs outside the render graph, so every dispatch that reads an earlier dispatch's storage writes
// is preceded by vk::computeToComputeBarrier (engine/vk/transfer.hpp).
namespace idk::render {
namespace {

using vk::ShaderId;

static_assert(sizeof(gpu::BvhTracePush) <= gpu::kPushConstantBytes && sizeof(gpu::BvhRefitPush) <= gpu::kPushConstantBytes);

constexpr const char* kCategory = "bvh";

// Buffers are read through device addresses only, but the usage must name a buffer kind; storage is the honest one.
vk::Buffer createFilled(vk::Context& ctx, const void* data, VkDeviceSize bytes, const std::string& name) {
    // A zero-sized buffer is invalid: keep 16 bytes so the address stays valid (never read: counts are 0).
    vk::Buffer buffer = ctx.createBuffer(
        {std::max<VkDeviceSize>(bytes, 16), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, name, kCategory});
    if (bytes > 0) vk::uploadBuffer(ctx, buffer, data, bytes);
    return buffer;
}

template <class T>
vk::Buffer createFilled(vk::Context& ctx, std::span<const T> values, const std::string& name) {
    return createFilled(ctx, values.data(), values.size_bytes(), name);
}

bool emptyBox(const gpu::GpuBlasNode& n) { return !(n.min.x <= n.max.x && n.min.y <= n.max.y && n.min.z <= n.max.z); }


constexpr std::array<uint32_t, 3> kTraceGroup = {gpu::kBvhTraceGroupSize, 1, 1};
constexpr std::array<uint32_t, 3> kRefitGroup = {gpu::kBvhRefitGroupSize, 1, 1};

}  // namespace

std::vector<uint32_t> refitOrder(std::span<const gpu::GpuBlasNode> nodes,
                                 std::vector<std::pair<uint32_t, uint32_t>>& levels) {
    levels.clear();
    std::vector<std::vector<uint32_t>> byDepth;
    if (!nodes.empty()) {
        std::vector<uint32_t> current{gpu::kBvhRootNode};
        while (!current.empty()) {
            std::vector<uint32_t> next, kept;
            for (uint32_t i : current) {
                if (i >= nodes.size()) throw std::invalid_argument("refitOrder: child index past the node array");
                const gpu::GpuBlasNode& n = nodes[i];
                if (emptyBox(n)) continue;
                kept.push_back(i);
                if (n.triCount == 0) {
                    next.push_back(n.triStartOrChild);
                    next.push_back(n.triStartOrChild + 1);
                }
            }
            if (!kept.empty()) byDepth.push_back(std::move(kept));
            current = std::move(next);
        }
    }
    std::vector<uint32_t> order;
    for (auto level = byDepth.rbegin(); level != byDepth.rend(); ++level) {
        levels.emplace_back(uint32_t(order.size()), uint32_t(level->size()));
        order.insert(order.end(), level->begin(), level->end());
    }
    return order;
}

// ---- GpuBlas ----------------------------------------------------------------------------------------------------

GpuBlas::GpuBlas(vk::Context& ctx, const BlasData& data, const std::string& name) : ctx_(ctx) {
    if (data.nodes.size() < 4) throw std::invalid_argument("GpuBlas " + name + ": a flattened BLAS has at least 4 nodes");
    nodeCount_ = uint32_t(data.nodes.size());
    vertexCount_ = uint32_t(data.positions.size());
    stackSize_ = data.stackSize;
    nodes_ = createFilled(ctx, data.nodes, name + " nodes");
    triangles_ = createFilled(ctx, data.triangles, name + " triangles");
    positions_ = createFilled(ctx, data.positions, name + " positions");
    const std::vector<uint32_t> order = refitOrder(data.nodes, refitLevels_);
    refitOrder_ = createFilled(ctx, std::span<const uint32_t>(order), name + " refit order");
}

GpuBlas::~GpuBlas() {
    for (vk::Buffer* b : {&nodes_, &triangles_, &positions_, &refitOrder_}) ctx_.destroyDeferred(*b);
}

gpu::GpuBlasDesc GpuBlas::desc() const {
    return {nodes_.address, triangles_.address, positions_.address, 3u, nodeCount_};
}

uint64_t GpuBlas::gpuBytes() const { return nodes_.size + triangles_.size + positions_.size + refitOrder_.size; }

void GpuBlas::uploadPositions(std::span<const glm::vec3> positions) {
    if (positions.size() != vertexCount_) {
        throw std::invalid_argument("GpuBlas::uploadPositions: " + std::to_string(positions.size()) +
                                    " positions given, the BLAS has " + std::to_string(vertexCount_));
    }
    if (!positions.empty()) vk::uploadBuffer(ctx_, positions_, positions);
}

std::vector<gpu::GpuBlasNode> GpuBlas::downloadNodes() const {
    return vk::downloadBuffer<gpu::GpuBlasNode>(ctx_, nodes_, nodeCount_);
}

// ---- GpuTlas ----------------------------------------------------------------------------------------------------

gpu::GpuBvhInstance makeGpuInstance(const glm::mat4& objectToWorld, const glm::mat4& worldToObject,
                                    uint32_t blasIndex) {
    gpu::GpuBvhInstance inst{};
    for (int c = 0; c < 4; ++c) {
        inst.objectToWorld[c] = glm::vec3(objectToWorld[c]);
        inst.worldToObject[c] = glm::vec3(worldToObject[c]);
    }
    inst.blasIndex = blasIndex;
    return inst;
}

GpuTlas::GpuTlas(vk::Context& ctx, const TlasData& data, const std::string& name) : ctx_(ctx) {
    if (data.nodes.size() < 4) throw std::invalid_argument("GpuTlas " + name + ": a flattened TLAS has at least 4 nodes");
    std::vector<gpu::GpuBlasDesc> descs;
    for (const GpuBlas* blas : data.blases) {
        descs.push_back(blas->desc());
        blasStackSize_ = std::max(blasStackSize_, blas->stackSize());
    }
    for (const gpu::GpuBvhInstance& inst : data.instances) {
        if (inst.blasIndex >= descs.size()) throw std::invalid_argument("GpuTlas " + name + ": instance BLAS index out of range");
    }
    stackSize_ = data.stackSize;
    nodes_ = createFilled(ctx, data.nodes, name + " nodes");
    order_ = createFilled(ctx, data.instanceOrder, name + " instance order");
    instances_ = createFilled(ctx, data.instances, name + " instances");
    blases_ = createFilled(ctx, std::span<const gpu::GpuBlasDesc>(descs), name + " BLAS descriptors");
    const gpu::GpuTlasDesc desc{nodes_.address, order_.address, instances_.address, blases_.address};
    desc_ = createFilled(ctx, &desc, sizeof(desc), name + " descriptor");
}

GpuTlas::~GpuTlas() {
    for (vk::Buffer* b : {&nodes_, &order_, &instances_, &blases_, &desc_}) ctx_.destroyDeferred(*b);
}

uint64_t GpuTlas::gpuBytes() const { return nodes_.size + order_.size + instances_.size + blases_.size + desc_.size; }

// ---- recording --------------------------------------------------------------------------------------------------

void dispatchTraceKernel(VkCommandBuffer cmd, const BvhKernels& k, ShaderId kernel, const gpu::BvhTracePush& push,
                         TraceMode mode, bool useTlas, uint32_t blasStack, uint32_t tlasStack) {
    if (push.count == 0) return;
    // A stack of 0 entries is not a valid array size; 1 is the smallest pipeline variant.
    const vk::Pipeline& pipeline =
        k.shaders.compute({kernel,
                           {{gpu::kSpecBvhStackSize, std::max(blasStack, 1u)},
                            {gpu::kSpecBvhTlasStackSize, std::max(tlasStack, 1u)},
                            {gpu::kSpecBvhTraceMode, static_cast<uint32_t>(mode)},
                            {gpu::kSpecBvhUseTlas, useTlas ? 1u : 0u}},
                           sizeof(gpu::BvhTracePush),
                           kTraceGroup});
    k.ctx.bindless().bind(cmd);
    vk::bindPipeline(cmd, pipeline);
    vk::pushConstants(cmd, k.ctx, push);
    vkCmdDispatch(cmd, vk::groupCount(push.count, gpu::kBvhTraceGroupSize), 1, 1);
}


void recordTraceRays(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuBlas& blas, TraceMode mode,
                     VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count, uint32_t stackSize) {
    gpu::BvhTracePush push{};
    push.blas = blas.desc();
    push.rays = rays;
    push.hits = hits;
    push.count = count;
    dispatchTraceKernel(cmd, kernels, ShaderId::bvh_trace_rays_comp, push, mode, false,
                        stackSize != 0 ? stackSize : blas.stackSize(), 1);
}

void recordTraceRays(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuTlas& tlas, TraceMode mode,
                     VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count) {
    gpu::BvhTracePush push{};
    push.tlas = tlas.descAddress();
    push.rays = rays;
    push.hits = hits;
    push.count = count;
    dispatchTraceKernel(cmd, kernels, ShaderId::bvh_trace_rays_comp, push, mode, true, tlas.blasStackSize(),
                        tlas.stackSize());
}

void recordRefit(VkCommandBuffer cmd, const BvhKernels& kernels, const GpuBlas& blas) {
    if (blas.refitLevels().empty()) return;
    const vk::Pipeline& pipeline =
        kernels.shaders.compute({ShaderId::bvh_refit_comp, {}, sizeof(gpu::BvhRefitPush), kRefitGroup});
    kernels.ctx.bindless().bind(cmd);
    vk::bindPipeline(cmd, pipeline);
    gpu::BvhRefitPush push{};
    push.blas = blas.desc();
    push.order = blas.refitOrderAddress();
    bool first = true;
    for (const auto& [start, count] : blas.refitLevels()) {
        if (!first) vk::computeToComputeBarrier(cmd);
        first = false;
        push.levelStart = start;
        push.levelCount = count;
        vk::pushConstants(cmd, kernels.ctx, push);
        vkCmdDispatch(cmd, vk::groupCount(count, gpu::kBvhRefitGroupSize), 1, 1);
    }
}

// ---- scene triangles --------------------------------------------------------------------------------------------

namespace {

// Appends one primitive: positions morphed by `weights`, then mapped by `place` (object -> wherever).
template <class Place>
void appendPrimitive(TriangleMesh& out, const scene::Primitive& prim, const std::vector<float>& weights, Place&& place) {
    const uint32_t base = uint32_t(out.positions.size());
    for (size_t v = 0; v < prim.positions.size(); ++v) {
        glm::vec3 p = prim.positions[v];
        for (size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
            if (!prim.targets[t].positions.empty() && weights[t] != 0.0f) p += weights[t] * prim.targets[t].positions[v];
        }
        out.positions.push_back(place(p, v));
    }
    for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
        out.indices.push_back(glm::uvec3(prim.indices[i], prim.indices[i + 1], prim.indices[i + 2]) + base);
    }
}

}  // namespace

TriangleMesh worldTriangles(const scene::Scene& scene) {
    TriangleMesh out;
    for (const scene::Instance& inst : scene.instances) {
        const scene::Mesh& mesh = scene.meshes.at(inst.mesh);
        const scene::Node& node = scene.nodes.at(inst.node);
        const std::vector<float>& weights = node.weights.empty() ? mesh.weights : node.weights;
        for (const scene::Primitive& prim : mesh.primitives) {
            const bool skinned = inst.skin.has_value() && !node.jointMatrices.empty() && prim.joints.size() == prim.positions.size() &&
                                 prim.weights.size() == prim.positions.size();
            appendPrimitive(out, prim, weights, [&](const glm::vec3& p, size_t v) {
                glm::vec4 local(p, 1.0f);
                if (skinned) {
                    glm::mat4 skin(0.0f);
                    float total = 0.0f;
                    for (int j = 0; j < 4; ++j) {
                        const float w = prim.weights[v][j];
                        const uint32_t joint = prim.joints[v][j];
                        if (w == 0.0f || joint >= node.jointMatrices.size()) continue;
                        skin += w * node.jointMatrices[joint];
                        total += w;
                    }
                    if (total > 0.0f) local = skin * local;
                }
                return glm::vec3(inst.world * local);
            });
        }
    }
    return out;
}

TriangleMesh meshTriangles(const scene::Scene& scene, uint32_t meshIndex) {
    TriangleMesh out;
    const scene::Mesh& mesh = scene.meshes.at(meshIndex);
    for (const scene::Primitive& prim : mesh.primitives) {
        appendPrimitive(out, prim, mesh.weights, [](const glm::vec3& p, size_t) { return p; });
    }
    return out;
}

}  // namespace idk::render
