// shadow_culling.cpp: the point-shadow faces' culling records, views and stats (see shadow_culling.hpp).
#include "frame/shadow_culling.hpp"

#include <string>

#include "frame/frame_inputs.hpp"
#include "render/cube_face_views.hpp"
#include "render/culling_math.hpp"
#include "vk/transfer.hpp"

namespace idk::frame {
namespace {

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

// Copies the faces' counters into this slot's readback buffer (read by the CPU after the frame's fence).
void addStatsCopyPass(graph::RenderGraph& graph, graph::BufferHandle counters, graph::BufferHandle host,
                      VkDeviceSize bytes) {
    auto written = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "cull_stats_shadows",
        [&](graph::PassBuilder& b) {
            b.read(counters, graph::Access::TransferSrc);
            *written = b.write(host, graph::Access::TransferDst);
            b.sideEffect();
        },
        [counters, written, bytes](graph::PassContext& pc) {
            VkBufferCopy region{0, 0, bytes};
            vkCmdCopyBuffer(pc.commandBuffer(), pc.vkBuffer(counters), pc.vkBuffer(*written), 1, &region);
        });
}

}  // namespace

void ShadowCulling::release() {
    if (!ctx_) return;
    if (draws_) ctx_->destroyDeferred(draws_);
    for (vk::Buffer& b : views_) ctx_->destroyDeferred(b);
    for (vk::Buffer& b : stats_) ctx_->destroyDeferred(b);
    draws_ = {};
    views_.clear();
    stats_.clear();
    viewCapacity_ = 0;
    lastLights_.clear();
}

std::optional<passes::ShadowCulledDraws> ShadowCulling::addPasses(FrameContext& f, const render::GpuScene& scene,
                                                                  const render::PointShadowMaps& maps,
                                                                  const render::PointShadowFrame& cubes) {
    beginFrame();
    const uint32_t viewCount = uint32_t(maps.casters().size()) * 6;
    if (f.settings.culling.mode == CullingMode::Off || scene.drawCount() == 0 || viewCount == 0) {
        if (ctx_ && f.settings.culling.mode == CullingMode::Off) release();  // model only what the frame needs
        return std::nullopt;
    }
    ctx_ = &f.ctx;
    if (!draws_) {
        // BLEND draws cast too (by coverage, as in the unculled cubes): culled per face like the others.
        const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(scene.data(), nullptr, true);
        const VkDeviceSize bytes = records.size() * sizeof(gpu::GpuCullDraw);
        draws_ = createBuffer(f.ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly,
                              "shadow cull draws");
        vk::uploadBuffer(f.ctx, draws_, records.data(), bytes);
    }
    if (viewCapacity_ < viewCount) {  // more cubes than before: new per-slot buffers
        for (vk::Buffer& b : views_) f.ctx.destroyDeferred(b);
        for (vk::Buffer& b : stats_) f.ctx.destroyDeferred(b);
        views_.clear();
        stats_.clear();
        viewCapacity_ = viewCount;
    }
    while (views_.size() < f.framesInFlight) {
        const std::string n = std::to_string(views_.size());
        views_.push_back(createBuffer(f.ctx, viewCapacity_ * sizeof(gpu::GpuCullView),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Upload,
                                      "shadow cull views " + n));
        stats_.push_back(createBuffer(f.ctx, viewCapacity_ * sizeof(gpu::GpuCullCounters),
                                      VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback,
                                      "shadow cull stats " + n));
    }
    // This slot's buffers: the frame ring has waited until the GPU finished the slot's previous frame.
    std::vector<gpu::GpuCullView> views;
    for (uint32_t c = 0; c < maps.casters().size(); ++c) {
        const uint32_t light = maps.casters()[c];
        for (uint32_t face = 0; face < 6; ++face)
            views.push_back(render::frustumView(
                render::cubeFaceViewProjection(cubes.table[light].position, face, cubes.planes[c].x,
                                               cubes.planes[c].y),
                glm::uvec2(maps.resolution())));
        lastLights_.push_back(light);
    }
    vk::uploadBuffer(f.ctx, views_[f.slot], views.data(), views.size() * sizeof(gpu::GpuCullView));

    passes::CullInputs in;
    in.instances = f.scene.instances;
    in.draws = importBuffer(f.graph, "shadow cull draws", draws_);
    in.views = importBuffer(f.graph, "shadow cull views", views_[f.slot]);
    in.drawCount = scene.drawCount();
    passes::ShadowCulledDraws out = passes::addShadowCullPass(f.graph, f.ctx, f.shaders, in, viewCount);
    addStatsCopyPass(f.graph, out.counters, importBuffer(f.graph, "shadow cull stats", stats_[f.slot]),
                     viewCount * sizeof(gpu::GpuCullCounters));
    lastSlot_ = f.slot;
    return out;
}

std::vector<passes::CullingViewStats> ShadowCulling::lastStats() const {
    if (lastLights_.empty()) return {};
    const uint32_t viewCount = uint32_t(lastLights_.size()) * 6;
    const auto c = vk::downloadBuffer<gpu::GpuCullCounters>(*ctx_, stats_[lastSlot_], viewCount);
    static constexpr const char* kFaces[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    std::vector<passes::CullingViewStats> out;
    for (uint32_t v = 0; v < viewCount; ++v) {
        passes::CullingViewStats s;
        s.view = "light " + std::to_string(lastLights_[v / 6]) + " face " + kFaces[v % 6];
        s.instancesTested = c[v].instancesTested;
        s.instancesDrawn = c[v].drawCount;
        s.trianglesDrawn = c[v].trianglesDrawn;
        out.push_back(s);
    }
    return out;
}

}  // namespace idk::frame
