// ui_renderer.hpp: draws Dear ImGui's draw data with the engine's own UI pass (ImGui's Vulkan backend is never
// used: it loads Vulkan through its own prototypes, which break under volk). The font atlas becomes a bindless
// sampled texture; each frame's vertices and indices are copied into host-visible buffers of that frame slot;
// one indexed draw per ImGui command with its clip rectangle as scissor, alpha-blended over the frame. Replaces
// IDKEngine's ImGuiBackend (an OpenGL renderer of the same draw data).
#pragma once
#include <volk.h>

#include <cstdint>
#include <vector>

#include "graph/render_graph.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

struct ImDrawData;

namespace idk::ui {

struct UiFrameStats {
    uint32_t drawCalls = 0;  // indexed draws recorded (commands with an empty scissor are skipped)
    uint32_t vertices = 0;
    uint32_t indices = 0;
};

class UiRenderer {
public:
    // Requires a current ImGui context: builds and uploads its font atlas and sets the atlas's TexID.
    UiRenderer(vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t frameSlots = 2);
    ~UiRenderer();
    UiRenderer(const UiRenderer&) = delete;
    UiRenderer& operator=(const UiRenderer&) = delete;

    // Copies `drawData` now (it may change after this call) and adds the pass "ui" drawing it over `target`
    // (ColorReadWrite: the frame below is kept). Returns the target's new version. Each call takes the next of
    // `frameSlots` buffer sets: the caller must not have more frames than that in flight.
    graph::TextureHandle addPass(graph::RenderGraph& graph, const ImDrawData& drawData, graph::TextureHandle target);

    const UiFrameStats& lastFrame() const noexcept { return stats_; }

private:
    struct Slot {
        vk::Buffer vertices;
        vk::Buffer indices;
    };
    void ensureCapacity(Slot& slot, VkDeviceSize vertexBytes, VkDeviceSize indexBytes);

    vk::Context& ctx_;
    vk::ShaderLibrary& shaders_;
    vk::Image fontImage_;
    vk::SampledIndex fontTexture_;
    vk::SamplerIndex sampler_;
    std::vector<Slot> slots_;
    uint32_t nextSlot_ = 0;
    UiFrameStats stats_;
};

}  // namespace idk::ui
