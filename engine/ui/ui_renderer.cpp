// ui_renderer.cpp: the UI pass: ImGui draw lists -> per-slot host-visible vertex/index buffers -> one indexed
// draw per command (vertex pulling by device address, scissor = the command's clip rectangle).
#include "ui/ui_renderer.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>

#include "passes/rendering.hpp"
#include "shared/ui_types.h"
#include "vk/transfer.hpp"

namespace idk::ui {
namespace {

static_assert(sizeof(ImDrawVert) == sizeof(gpu::UiVertex), "ImDrawVert must match shared/ui_types.h UiVertex");
static_assert(offsetof(ImDrawVert, pos) == offsetof(gpu::UiVertex, position));
static_assert(offsetof(ImDrawVert, uv) == offsetof(gpu::UiVertex, uv));
static_assert(offsetof(ImDrawVert, col) == offsetof(gpu::UiVertex, color));
constexpr VkIndexType kIndexType = sizeof(ImDrawIdx) == 2 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32;

// One draw, resolved on the CPU while the graph is built (ImGui's draw data does not outlive the frame).
struct UiDraw {
    VkRect2D scissor;
    uint32_t texture;
    uint32_t indexCount;
    uint32_t firstIndex;
    int32_t vertexOffset;
};

}  // namespace

UiRenderer::UiRenderer(vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t frameSlots)
    : ctx_(ctx), shaders_(shaders), slots_(std::max(frameSlots, 1u)) {
    ImGuiIO& io = ImGui::GetIO();
    io.BackendRendererName = "idk_ui";
    io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // vertexOffset per draw: 16-bit indices suffice
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.extent = {uint32_t(width), uint32_t(height), 1};
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = "ui font atlas";
    desc.category = "ui";
    fontImage_ = ctx_.createImage(desc);
    vk::uploadImage(ctx_, fontImage_, pixels, VkDeviceSize(width) * height * 4, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    fontTexture_ = ctx_.bindless().addSampled(fontImage_.view);
    vk::SamplerDesc sampler;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler_ = ctx_.bindless().addSampler(sampler);
    io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(fontTexture_.value)));
}

UiRenderer::~UiRenderer() {
    ctx_.waitIdle();
    for (Slot& s : slots_) {
        if (s.vertices) ctx_.destroy(s.vertices);
        if (s.indices) ctx_.destroy(s.indices);
    }
    ctx_.bindless().release(fontTexture_);
    ctx_.bindless().release(sampler_);
    ctx_.destroy(fontImage_);
}

void UiRenderer::ensureCapacity(Slot& slot, VkDeviceSize vertexBytes, VkDeviceSize indexBytes) {
    auto grow = [&](vk::Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage, const char* name) {
        if (buffer && buffer.size >= bytes) return;
        if (buffer) ctx_.destroyDeferred(buffer);
        vk::BufferDesc desc;
        desc.size = std::max<VkDeviceSize>(bytes + bytes / 2, 64 * 1024);  // headroom: windows grow
        desc.usage = usage;
        desc.memory = vk::MemoryUsage::Upload;  // written by the CPU each frame, read once by the GPU
        desc.name = name;
        desc.category = "ui";
        buffer = ctx_.createBuffer(desc);
    };
    grow(slot.vertices, vertexBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "ui vertices");
    grow(slot.indices, indexBytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "ui indices");
}

graph::TextureHandle UiRenderer::addPass(graph::RenderGraph& graph, const ImDrawData& data, graph::TextureHandle target) {
    stats_ = {};
    Slot& slot = slots_[nextSlot_];
    nextSlot_ = (nextSlot_ + 1) % uint32_t(slots_.size());
    ensureCapacity(slot, std::max<VkDeviceSize>(VkDeviceSize(data.TotalVtxCount) * sizeof(ImDrawVert), 1),
                   std::max<VkDeviceSize>(VkDeviceSize(data.TotalIdxCount) * sizeof(ImDrawIdx), 1));

    // Copy every list into the slot's mapped buffers (host writes before vkQueueSubmit are visible to the GPU
    // without a barrier) and resolve each command's scissor in framebuffer pixels.
    auto draws = std::make_shared<std::vector<UiDraw>>();
    auto* vertexOut = static_cast<ImDrawVert*>(slot.vertices.mapped());
    auto* indexOut = static_cast<ImDrawIdx*>(slot.indices.mapped());
    uint32_t vertexBase = 0, indexBase = 0;
    const ImVec2 scale = data.FramebufferScale;
    for (int l = 0; l < data.CmdListsCount; ++l) {
        const ImDrawList* list = data.CmdLists[l];
        std::memcpy(vertexOut + vertexBase, list->VtxBuffer.Data, size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert));
        std::memcpy(indexOut + indexBase, list->IdxBuffer.Data, size_t(list->IdxBuffer.Size) * sizeof(ImDrawIdx));
        for (const ImDrawCmd& cmd : list->CmdBuffer) {
            if (cmd.UserCallback) continue;  // the viewer registers no callbacks
            float x0 = std::max((cmd.ClipRect.x - data.DisplayPos.x) * scale.x, 0.0f);
            float y0 = std::max((cmd.ClipRect.y - data.DisplayPos.y) * scale.y, 0.0f);
            float x1 = std::min((cmd.ClipRect.z - data.DisplayPos.x) * scale.x, data.DisplaySize.x * scale.x);
            float y1 = std::min((cmd.ClipRect.w - data.DisplayPos.y) * scale.y, data.DisplaySize.y * scale.y);
            if (x1 <= x0 || y1 <= y0 || cmd.ElemCount == 0) continue;
            UiDraw d;
            d.scissor = {{int32_t(x0), int32_t(y0)}, {uint32_t(std::ceil(x1 - std::floor(x0))), uint32_t(std::ceil(y1 - std::floor(y0)))}};
            d.texture = uint32_t(reinterpret_cast<intptr_t>(cmd.GetTexID()));
            d.indexCount = cmd.ElemCount;
            d.firstIndex = indexBase + cmd.IdxOffset;
            d.vertexOffset = int32_t(vertexBase + cmd.VtxOffset);
            draws->push_back(d);
            stats_.indices += cmd.ElemCount;
        }
        vertexBase += uint32_t(list->VtxBuffer.Size);
        indexBase += uint32_t(list->IdxBuffer.Size);
    }
    stats_.vertices = vertexBase;
    stats_.drawCalls = uint32_t(draws->size());

    gpu::UiPush push{};
    push.vertices = slot.vertices.address;
    push.scale = {2.0f / std::max(data.DisplaySize.x, 1.0f), 2.0f / std::max(data.DisplaySize.y, 1.0f)};
    push.translate = {-1.0f - data.DisplayPos.x * push.scale.x, -1.0f - data.DisplayPos.y * push.scale.y};
    push.samplerIndex = sampler_.value;
    VkBuffer indexBuffer = slot.indices.buffer;

    auto written = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "ui",
        [&](graph::PassBuilder& b) { *written = b.write(target, graph::Access::ColorReadWrite); },
        [this, written, draws, push, indexBuffer](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            const graph::PhysicalTexture& out = pc.texture(*written);
            VkExtent2D extent{out.extent.width, out.extent.height};
            vk::GraphicsPipelineDesc desc;
            desc.vertex = vk::ShaderId::ui_ui_vert;
            desc.fragment = vk::ShaderId::ui_ui_frag;
            desc.colorFormats = {out.format};
            desc.blend = {vk::BlendMode::Alpha};
            desc.cull = VK_CULL_MODE_NONE;
            desc.depthTest = desc.depthWrite = false;
            desc.pushBytes = sizeof(gpu::UiPush);
            const vk::Pipeline& pipeline = shaders_.graphics(desc);

            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = out.view;
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // draw over the frame
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            passes::beginRendering(cmd, extent, {&color, 1});
            if (!draws->empty()) {
                vk::bindPipeline(cmd, pipeline);
                ctx_.bindless().bind(cmd);
                vkCmdBindIndexBuffer(cmd, indexBuffer, 0, kIndexType);
                for (const UiDraw& d : *draws) {
                    VkRect2D scissor = d.scissor;
                    scissor.offset.x = std::min<int32_t>(scissor.offset.x, int32_t(extent.width));
                    scissor.offset.y = std::min<int32_t>(scissor.offset.y, int32_t(extent.height));
                    scissor.extent.width = std::min(scissor.extent.width, extent.width - uint32_t(scissor.offset.x));
                    scissor.extent.height = std::min(scissor.extent.height, extent.height - uint32_t(scissor.offset.y));
                    if (scissor.extent.width == 0 || scissor.extent.height == 0) continue;
                    vkCmdSetScissor(cmd, 0, 1, &scissor);
                    gpu::UiPush p = push;
                    p.textureIndex = d.texture;
                    vk::pushConstants(cmd, ctx_, p);
                    vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
                }
            }
            vkCmdEndRendering(cmd);
        });
    return *written;
}

}  // namespace idk::ui
