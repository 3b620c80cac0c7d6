// culling_feature.cpp: the culling records, visibility bits, per-slot view planes and stats buffers, and the
// camera view's culled G-buffer (see culling_feature.hpp).
#include "frame/culling_feature.hpp"

#include <string>

#include "frame/frame_inputs.hpp"
#include "render/culling_math.hpp"
#include "vk/transfer.hpp"

namespace idk::frame {
namespace {

constexpr uint32_t kMaxViews = 1;   // the camera
constexpr uint32_t kMaxPhases = 2;  // early and late

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
    if (visibility_) ctx_.destroyDeferred(visibility_);
    for (vk::Buffer& b : views_) ctx_.destroyDeferred(b);
    for (vk::Buffer& b : stats_) ctx_.destroyDeferred(b);
    draws_ = visibility_ = {};
    views_.clear();
    stats_.clear();
    lastPhases_ = 0;
}

void CullingFeature::setScene() { release(); }

void CullingFeature::createResources(const render::GpuScene& scene, uint32_t framesInFlight) {
    if (!draws_) {
        const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(scene.data());
        const VkDeviceSize bytes = records.size() * sizeof(gpu::GpuCullDraw);
        draws_ = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "cull draws");
        vk::uploadBuffer(ctx_, draws_, records.data(), bytes);
        // Nothing was drawn before the first frame: its early phase draws nothing, its late phase everything visible.
        const std::vector<uint32_t> zeros(records.size(), 0u);
        visibility_ = createBuffer(ctx_, zeros.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   vk::MemoryUsage::GpuOnly, "cull visibility");
        vk::uploadBuffer(ctx_, visibility_, zeros.data(), zeros.size() * sizeof(uint32_t));
    }
    while (views_.size() < framesInFlight) {
        const std::string n = std::to_string(views_.size());
        views_.push_back(createBuffer(ctx_, kMaxViews * sizeof(gpu::GpuCullView), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                      vk::MemoryUsage::Upload, "cull views " + n));
        stats_.push_back(createBuffer(ctx_, kMaxViews * kMaxPhases * sizeof(gpu::GpuCullCounters),
                                      VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback, "cull stats " + n));
    }
}

passes::GBufferOutputs CullingFeature::addGBuffer(FrameContext& f, const render::GpuScene& scene) {
    lastPhases_ = 0;
    const CullingMode mode = f.settings.culling.mode;
    if (mode == CullingMode::Off || scene.drawCount() == 0) {
        f.gbuffer = passes::addGBufferPass(f.graph, f.ctx, f.shaders, f.scene, f.frameConstants, &f.log);
    } else {
        createResources(scene, f.framesInFlight);
        // This slot's buffers: the frame ring has waited until the GPU finished the slot's previous frame.
        const gpu::GpuCullView camera = render::frustumView(f.viewProjection, {f.width, f.height});
        vk::uploadBuffer(ctx_, views_[f.slot], &camera, sizeof(camera));
        graph::BufferHandle stats = importBuffer(f.graph, "cull stats", stats_[f.slot]);

        passes::CullInputs in;
        in.instances = f.scene.instances;
        in.draws = importBuffer(f.graph, "cull draws", draws_);
        in.views = importBuffer(f.graph, "cull views", views_[f.slot]);
        in.drawCount = scene.drawCount();
        if (mode == CullingMode::Frustum) {
            f.cameraDraws = passes::addCullPass(f.graph, f.ctx, f.shaders, in, "camera");
            f.gbuffer = passes::addGBufferPass(f.graph, f.ctx, f.shaders, f.scene, f.frameConstants, &f.log,
                                               &f.cameraDraws);
            passes::addCullStatsCopyPass(f.graph, {f.cameraDraws.counters}, stats);
            lastPhases_ = 1;
        } else {
            // The last frame's late phase wrote the bits (compute); this frame's early phase reads them.
            in.visibility = importBuffer(f.graph, "cull visibility", visibility_,
                                         graph::stateAfterAccess(graph::Access::StorageReadWrite,
                                                                 graph::ResourceKind::Buffer,
                                                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT));
            in.phase = gpu::kCullEarly;
            passes::CulledDraws early = passes::addCullPass(f.graph, f.ctx, f.shaders, in, "camera early");
            early.keepDepth = true;
            const passes::GBufferOutputs first =
                passes::addGBufferPass(f.graph, f.ctx, f.shaders, f.scene, f.frameConstants, &f.log, &early);
            in.phase = gpu::kCullLate;
            in.pyramid = passes::addDepthPyramidPass(f.graph, f.ctx, f.shaders, first.depth, {f.width, f.height},
                                                     "depth_pyramid_early");
            f.cameraDraws = passes::addCullPass(f.graph, f.ctx, f.shaders, in, "camera late");
            f.gbuffer = passes::addGBufferPass(f.graph, f.ctx, f.shaders, f.scene, f.frameConstants, &f.log,
                                               &f.cameraDraws, &first);
            passes::addCullStatsCopyPass(f.graph, {early.counters, f.cameraDraws.counters}, stats);
            lastPhases_ = 2;
        }
        lastSlot_ = f.slot;
    }
    f.depthPyramid = passes::addDepthPyramidPass(f.graph, f.ctx, f.shaders, f.gbuffer.depth, {f.width, f.height},
                                                 "depth_pyramid");
    return f.gbuffer;
}

std::vector<passes::CullingViewStats> CullingFeature::lastStats() const {
    if (lastPhases_ == 0) return {};
    const auto c = vk::downloadBuffer<gpu::GpuCullCounters>(ctx_, stats_[lastSlot_], lastPhases_);
    passes::CullingViewStats camera{"camera", c.back().instancesTested, 0, 0};  // the late phase tests every draw
    for (const gpu::GpuCullCounters& phase : c) {
        camera.instancesDrawn += phase.drawCount;
        camera.trianglesDrawn += phase.trianglesDrawn;
    }
    return {camera};
}

}  // namespace idk::frame
