// culling_feature.cpp: the culling records, visibility bits, per-slot view planes and stats buffers, and the
// camera view's culled G-buffer (see culling_feature.hpp).
#include "frame/culling_feature.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <string>

#include "frame/frame_inputs.hpp"
#include "render/culling_math.hpp"
#include "render/meshlets.hpp"
#include "shared/depth_pyramid.h"
#include "vk/transfer.hpp"

namespace idk::frame {
namespace {

constexpr uint32_t kMaxViews = 1;   // the camera
constexpr uint32_t kMaxPhases = 2;  // early and late
constexpr uint32_t kCountersPerPhase = 2;  // the culling pass's and (mesh rung) the task shader's

vk::Buffer createBuffer(vk::Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, vk::MemoryUsage memory,
                        const std::string& name) {
    vk::BufferDesc desc;
    desc.size = size;
    desc.usage = usage;
    desc.memory = memory;
    desc.name = name;
    desc.category = "culling";
    return ctx.createBuffer(desc);
}

}  // namespace

CullingFeature::~CullingFeature() { release(); }

void CullingFeature::release() {
    if (draws_) ctx_.destroyDeferred(draws_);
    for (vk::Buffer* b : {&visibility_, &meshlets_, &meshletIndices_, &meshletVisibility_, &capturedPyramid_})
        if (*b) ctx_.destroyDeferred(*b);
    meshlets_ = meshletIndices_ = meshletVisibility_ = capturedPyramid_ = {};
    for (vk::Buffer& b : views_) ctx_.destroyDeferred(b);
    for (vk::Buffer& b : stats_) ctx_.destroyDeferred(b);
    draws_ = visibility_ = {};
    hizLevels_.release();
    views_.clear();
    stats_.clear();
    lastPhases_ = 0;
    frozen_.reset();
}

void CullingFeature::setScene() { release(); }

bool CullingFeature::usesMeshShaders(const vk::Context& ctx, const CullingSettings& settings) {
    switch (settings.geometry) {
    case GeometryPath::Mesh: return ctx.capabilities().meshShaderExt;
    case GeometryPath::Mdi: return false;
    case GeometryPath::Auto: break;
    }
    return ctx.ladder("mesh-shading").chosen == vk::Rung::Native;
}

std::string CullingFeature::geometryError(const vk::Context& ctx, const CullingSettings& settings) {
    if (settings.geometry == GeometryPath::Auto) return {};
    const char* name = settings.geometry == GeometryPath::Mesh ? "mesh" : "mdi";
    if (settings.mode == CullingMode::Off)
        return std::string("--geometry ") + name + ": it draws the culled commands; use --culling frustum or hiz "
               "(--culling off draws every instance with one vkCmdDrawIndexedIndirect)";
    if (settings.geometry == GeometryPath::Mesh && !ctx.capabilities().meshShaderExt)
        return "--geometry mesh: the device lacks VK_EXT_mesh_shader (task and mesh shaders); use --geometry mdi";
    return {};
}

void CullingFeature::createResources(const render::GpuScene& scene, uint32_t framesInFlight, bool meshRung) {
    if (draws_ && meshRung != meshRung_) {  // --geometry changed: records (and meshlets) for the other path
        for (vk::Buffer* b : {&draws_, &visibility_, &meshlets_, &meshletIndices_, &meshletVisibility_})
            if (*b) ctx_.destroyDeferred(*b);
        draws_ = visibility_ = meshlets_ = meshletIndices_ = meshletVisibility_ = {};
    }
    if (!draws_) {
        meshRung_ = meshRung;
        render::MeshletData meshlets;
        if (meshRung_) {
            meshlets = render::buildMeshlets(scene.data());
            auto upload = [&](vk::Buffer& b, const auto& v, const char* name) {
                const VkDeviceSize bytes = std::max<VkDeviceSize>(v.size() * sizeof(v[0]), 4);
                b = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, name);
                if (!v.empty()) vk::uploadBuffer(ctx_, b, v.data(), v.size() * sizeof(v[0]));
            };
            // One index buffer (vertex indices, then triangle bytes) keeps the mesh push block within 128 bytes.
            std::vector<gpu::GpuMeshlet> gpuMeshlets = meshlets.meshlets;
            for (gpu::GpuMeshlet& m : gpuMeshlets) m.triangleOffset += uint32_t(4 * meshlets.vertices.size());
            std::vector<uint32_t> indices = meshlets.vertices;
            indices.insert(indices.end(), meshlets.triangles.begin(), meshlets.triangles.end());
            upload(meshlets_, gpuMeshlets, "meshlets");
            upload(meshletIndices_, indices, "meshlet indices");
        }
        const std::vector<gpu::GpuCullDraw> records =
            render::packCullDraws(scene.data(), meshRung_ ? &meshlets : nullptr);
        if (meshRung_) {  // no meshlet drawn before the first frame: its late phase tests them all
            const std::vector<uint32_t> zeros(std::max(render::meshletVisibilityWords(records), 1u), 0u);
            meshletWords_ = uint32_t(zeros.size());
            meshletVisibility_ = createBuffer(ctx_, zeros.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                              vk::MemoryUsage::GpuOnly, "cull meshlet visibility");
            vk::uploadBuffer(ctx_, meshletVisibility_, zeros.data(), zeros.size() * sizeof(uint32_t));
        }
        const VkDeviceSize bytes = records.size() * sizeof(gpu::GpuCullDraw);
        draws_ = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "cull draws");
        vk::uploadBuffer(ctx_, draws_, records.data(), bytes);
        // Nothing was drawn before the first frame: its early phase draws nothing, its late phase everything visible.
        drawCount_ = uint32_t(records.size());
        const std::vector<uint32_t> zeros(records.size(), 0u);
        visibility_ = createBuffer(ctx_, zeros.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   vk::MemoryUsage::GpuOnly, "cull visibility");
        vk::uploadBuffer(ctx_, visibility_, zeros.data(), zeros.size() * sizeof(uint32_t));
    }
    while (views_.size() < framesInFlight) {
        const std::string n = std::to_string(views_.size());
        views_.push_back(createBuffer(ctx_, kMaxViews * sizeof(gpu::GpuCullView), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                      vk::MemoryUsage::Upload, "cull views " + n));
        stats_.push_back(createBuffer(ctx_, kMaxViews * kMaxPhases * kCountersPerPhase * sizeof(gpu::GpuCullCounters),
                                      VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback, "cull stats " + n));
    }
}

passes::GBufferOutputs CullingFeature::addGBuffer(FrameContext& f, const render::GpuScene& scene) {
    lastPhases_ = 0;
    const passes::HizMinmaxResources* minmax = nullptr;  // the pyramids' rung (nullptr: compute)
    if (!f.settings.culling.freeze) frozen_.reset();
    const bool frozen = f.settings.culling.freeze && frozen_.has_value();
    const CullingMode mode = frozen && f.settings.culling.mode == CullingMode::Hiz ? CullingMode::Frustum
                                                                                     : f.settings.culling.mode;
    if (mode == CullingMode::Off || scene.drawCount() == 0) {
        f.gbuffer = passes::addGBufferPass(f.graph, f.ctx, f.shaders, f.scene, f.frameConstants, &f.log);
        lastGeometry_ = "indirect";
    } else {
        createResources(scene, f.framesInFlight, usesMeshShaders(ctx_, f.settings.culling));
        lastGeometry_ = meshRung_ ? "mesh" : "mdi";
        // This slot's buffers: the frame ring has waited until the GPU finished the slot's previous frame.
        const gpu::GpuCullView camera =
            frozen ? *frozen_ : render::frustumView(f.viewProjection, {f.width, f.height});
        if (f.settings.culling.freeze) frozen_ = camera;
        vk::uploadBuffer(ctx_, views_[f.slot], &camera, sizeof(camera));
        graph::BufferHandle stats = importBuffer(f.graph, "cull stats", stats_[f.slot]);

        passes::CullInputs in;
        in.instances = f.scene.instances;
        in.draws = importBuffer(f.graph, "cull draws", draws_);
        in.views = importBuffer(f.graph, "cull views", views_[f.slot]);
        in.drawCount = scene.drawCount();
        in.meshTasks = meshRung_;
        const graph::BufferHandle meshlets = importBuffer(f.graph, "meshlets", meshlets_);
        const graph::BufferHandle meshletIndices = importBuffer(f.graph, "meshlet indices", meshletIndices_);
        // The last frame's late task shader wrote the meshlet bits; this frame's early one reads them.
        graph::BufferHandle meshletVisibility;
        if (meshRung_ && mode == CullingMode::Hiz)
            meshletVisibility = importBuffer(f.graph, "cull meshlet visibility", meshletVisibility_,
                                             graph::stateAfterAccess(graph::Access::StorageReadWrite,
                                                                     graph::ResourceKind::Buffer,
                                                                     VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT));
        std::vector<graph::BufferHandle> counters;  // per phase: the culling pass's, then the task shader's
        // One view's culled G-buffer draw for `in.phase`, over `drawOver` in the late phase.
        auto draw = [&](const std::string& name, const passes::GBufferOutputs* drawOver, bool keepDepth) {
            passes::CulledDraws c = passes::addCullPass(f.graph, f.ctx, f.shaders, in, name);
            c.keepDepth = keepDepth;
            c.meshlets = meshlets;
            c.meshletIndices = meshletIndices;
            c.meshletVisibility = meshletVisibility;
            const passes::GBufferOutputs out = passes::addGBufferPass(f.graph, f.ctx, f.shaders, f.scene,
                                                                      f.frameConstants, &f.log, &c, drawOver);
            counters.push_back(c.counters);
            if (meshRung_) counters.push_back(*c.meshCountersWritten);
            f.cameraDraws = c;
            return out;
        };
        if (mode == CullingMode::Frustum) {
            f.gbuffer = draw("camera", nullptr, false);
        } else {
            // The last frame's late phase wrote the bits (compute); this frame's early phase reads them.
            in.visibility = importBuffer(f.graph, "cull visibility", visibility_,
                                         graph::stateAfterAccess(graph::Access::StorageReadWrite,
                                                                 graph::ResourceKind::Buffer,
                                                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT));
            in.phase = gpu::kCullEarly;
            const passes::GBufferOutputs early = draw("camera early", nullptr, true);
            in.phase = gpu::kCullLate;
            if (ctx_.ladder("hiz-reduction").chosen == vk::Rung::Native)
                minmax = hizLevels_.forSize({f.width, f.height});
            in.pyramid = passes::addDepthPyramidPass(f.graph, f.ctx, f.shaders, early.depth, {f.width, f.height},
                                                     "depth_pyramid_early", minmax);
            if (capturePyramid_) capture(f, in.pyramid);
            f.gbuffer = draw("camera late", &early, false);
        }
        passes::addCullStatsCopyPass(f.graph, counters, stats);
        lastPhases_ = mode == CullingMode::Frustum ? 1 : 2;
        lastSlot_ = f.slot;
    }
    f.depthPyramid = passes::addDepthPyramidPass(f.graph, f.ctx, f.shaders, f.gbuffer.depth, {f.width, f.height},
                                                 "depth_pyramid", minmax);
    return f.gbuffer;
}

void CullingFeature::capture(FrameContext& f, graph::BufferHandle pyramid) {
    const glm::uvec2 size(f.width, f.height);
    const uint32_t floats = gpu::hizLevelOffset(size, gpu::hizLevelCount(size));
    if (capturedPyramid_ && capturedFloats_ != floats) {
        ctx_.destroyDeferred(capturedPyramid_);
        capturedPyramid_ = {};
    }
    if (!capturedPyramid_)
        capturedPyramid_ = createBuffer(ctx_, floats * sizeof(float), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        vk::MemoryUsage::Readback, "cull captured pyramid");
    capturedFloats_ = floats;
    const graph::BufferHandle host = importBuffer(f.graph, "cull captured pyramid", capturedPyramid_);
    auto handles = std::make_shared<std::array<graph::BufferHandle, 2>>();
    f.graph.addPass(
        "cull_capture_pyramid",
        [&](graph::PassBuilder& b) {
            (*handles)[0] = b.read(pyramid, graph::Access::TransferSrc);
            (*handles)[1] = b.write(host, graph::Access::TransferDst);
            b.sideEffect();  // read by the CPU after the frame's fence
        },
        [handles, floats](graph::PassContext& pc) {
            const VkBufferCopy region{0, 0, floats * sizeof(float)};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer((*handles)[0]), pc.vkBuffer((*handles)[1]), 1, &region);
        });
}

std::vector<float> CullingFeature::earlyPyramid() const {
    if (!capturedPyramid_) return {};
    return vk::downloadBuffer<float>(ctx_, capturedPyramid_, capturedFloats_);
}

std::vector<uint32_t> CullingFeature::visibilityBits() const {
    if (!visibility_) return {};
    return vk::downloadBuffer<uint32_t>(ctx_, visibility_, drawCount_);
}

std::vector<uint32_t> CullingFeature::meshletVisibilityBits() const {
    if (!meshletVisibility_) return {};
    return vk::downloadBuffer<uint32_t>(ctx_, meshletVisibility_, meshletWords_);
}

std::vector<passes::CullingViewStats> CullingFeature::lastStats() const {
    if (lastPhases_ == 0) return {};
    const uint32_t perPhase = meshRung_ ? 2 : 1;
    const auto c = vk::downloadBuffer<gpu::GpuCullCounters>(ctx_, stats_[lastSlot_], lastPhases_ * perPhase);
    passes::CullingViewStats camera;
    camera.view = "camera";
    camera.meshlets = meshRung_;
    for (uint32_t phase = 0; phase < lastPhases_; ++phase) {
        const gpu::GpuCullCounters& cull = c[phase * perPhase];
        camera.instancesTested = cull.instancesTested;  // every phase tests every draw: count them once
        camera.instancesDrawn += cull.drawCount - cull.relaunched;  // each instance once
        camera.trianglesDrawn += cull.trianglesDrawn;  // 0 on the mesh rung: the task shader counts
        if (meshRung_) {
            const gpu::GpuCullCounters& task = c[phase * perPhase + 1];
            camera.meshletsTested += task.meshletsTested;
            camera.meshletsDrawn += task.meshletsDrawn;
            camera.trianglesDrawn += task.trianglesDrawn;
        }
    }
    return {camera};
}

}  // namespace idk::frame
