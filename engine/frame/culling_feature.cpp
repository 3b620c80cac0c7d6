// culling_feature.cpp: the culling records, visibility bits, per-slot view planes and stats buffers, and the
// camera view's culled G-buffer (see culling_feature.hpp).
#include "frame/culling_feature.hpp"

#include <algorithm>
#include <string>

#include "frame/frame_inputs.hpp"
#include "render/culling_math.hpp"
#include "render/meshlets.hpp"
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
    for (vk::Buffer* b : {&visibility_, &meshlets_, &meshletVertices_, &meshletTriangles_})
        if (*b) ctx_.destroyDeferred(*b);
    meshlets_ = meshletVertices_ = meshletTriangles_ = {};
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
        for (vk::Buffer* b : {&draws_, &visibility_, &meshlets_, &meshletVertices_, &meshletTriangles_})
            if (*b) ctx_.destroyDeferred(*b);
        draws_ = visibility_ = meshlets_ = meshletVertices_ = meshletTriangles_ = {};
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
            upload(meshlets_, meshlets.meshlets, "meshlets");
            upload(meshletVertices_, meshlets.vertices, "meshlet vertices");
            upload(meshletTriangles_, meshlets.triangles, "meshlet triangles");
        }
        const std::vector<gpu::GpuCullDraw> records =
            render::packCullDraws(scene.data(), meshRung_ ? &meshlets : nullptr);
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
        const graph::BufferHandle meshletVertices = importBuffer(f.graph, "meshlet vertices", meshletVertices_);
        const graph::BufferHandle meshletTriangles = importBuffer(f.graph, "meshlet triangles", meshletTriangles_);
        std::vector<graph::BufferHandle> counters;  // per phase: the culling pass's, then the task shader's
        // One view's culled G-buffer draw for `in.phase`, over `drawOver` in the late phase.
        auto draw = [&](const std::string& name, const passes::GBufferOutputs* drawOver, bool keepDepth) {
            passes::CulledDraws c = passes::addCullPass(f.graph, f.ctx, f.shaders, in, name);
            c.keepDepth = keepDepth;
            c.meshlets = meshlets;
            c.meshletVertices = meshletVertices;
            c.meshletTriangles = meshletTriangles;
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

std::vector<uint32_t> CullingFeature::visibilityBits() const {
    if (!visibility_) return {};
    return vk::downloadBuffer<uint32_t>(ctx_, visibility_, drawCount_);
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
        camera.instancesDrawn += cull.drawCount;
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
