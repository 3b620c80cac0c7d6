// scene_update.cpp: copies the GPU scene's patched materials (GpuScene::setTexture, when a streamed texture
// arrives) into the material buffer with vkCmdUpdateBuffer, so the update is ordered by the render graph
// against this frame's readers and earlier frames' (the import state says "last read by the G-buffer").
// Ports the role of IDKEngine's MainThreadQueue texture-arrival action (reference 1.5 step 1).
#include "passes/passes.hpp"

#include <algorithm>
#include <memory>

namespace idk::passes {

graph::BufferHandle addSceneUpdatePass(graph::RenderGraph& graph, graph::BufferHandle materials,
                                       std::vector<gpu::GpuMaterial> contents) {
    auto written = std::make_shared<graph::BufferHandle>();
    auto data = std::make_shared<std::vector<gpu::GpuMaterial>>(std::move(contents));
    graph.addPass(
        "scene_update", [&](graph::PassBuilder& b) { *written = b.write(materials, graph::Access::TransferDst); },
        [written, data](graph::PassContext& pc) {
            // SPEC: vkCmdUpdateBuffer takes at most 65536 bytes per call, in multiples of 4.
            constexpr VkDeviceSize kMaxUpdate = 65536;
            const auto* bytes = reinterpret_cast<const uint8_t*>(data->data());
            VkDeviceSize total = data->size() * sizeof(gpu::GpuMaterial);
            for (VkDeviceSize offset = 0; offset < total; offset += kMaxUpdate) {
                VkDeviceSize size = std::min(kMaxUpdate, total - offset);
                vkCmdUpdateBuffer(pc.commandBuffer(), pc.vkBuffer(*written), offset, size, bytes + offset);
            }
        });
    return *written;
}

}  // namespace idk::passes
