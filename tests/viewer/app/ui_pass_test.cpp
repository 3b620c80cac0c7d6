// ui_pass_test.cpp: the engine's UI pass (engine/ui/ui_renderer.cpp) on the Vulkan device, headless: ImGui draw
// lists with known geometry are drawn over a black image and read back. Oracle: exact coverage of axis-aligned
// rectangles (pixel centres inside), "over" alpha blending in 8-bit codes, scissor = the command's clip rectangle,
// and glyphs sampled from the bindless font atlas only inside the text's box.
#include <gtest/gtest.h>
#include <imgui.h>

#include <memory>

#include "graph/resource_pool.hpp"
#include "render/vk_graph_backend.hpp"
#include "support/gpu_fixture.hpp"
#include "ui/ui_renderer.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

struct Box {
    int x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1)
    bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

class UiPassTest : public GpuTest {};

TEST_F(UiPassTest, RectanglesBlendingScissorAndGlyphs) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(float(kSize), float(kSize));
    std::vector<uint8_t> pixels;
    ui::UiFrameStats stats;
    {
        ui::UiRenderer ui(ctx(), shaders());
        ImGui::NewFrame();
        ImDrawList* draw = ImGui::GetForegroundDrawList();
        draw->AddRectFilled(ImVec2(8, 8), ImVec2(24, 24), IM_COL32(255, 0, 0, 255));    // opaque red
        draw->AddRectFilled(ImVec2(32, 8), ImVec2(48, 24), IM_COL32(0, 0, 255, 128));   // blue, alpha 128/255
        draw->PushClipRect(ImVec2(40, 32), ImVec2(48, 40));
        draw->AddRectFilled(ImVec2(32, 28), ImVec2(56, 56), IM_COL32(0, 255, 0, 255));  // only the clip shows
        draw->PopClipRect();
        draw->AddText(ImVec2(4, 44), IM_COL32_WHITE, "Hi");
        ImGui::Render();

        vk::ImageDesc desc;
        desc.extent = {kSize, kSize, 1};
        desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        desc.name = "ui test target";
        vk::Image image = ctx().createImage(desc);
        {
            render::VkGraphBackend backend(ctx());
            graph::ResourcePool pool(backend);
            graph::RenderGraph graph(pool, {kSize, kSize});
            graph::PhysicalTexture p;
            p.image = image.image;
            p.view = image.view;
            p.format = image.format;
            p.extent = image.extent;
            graph::TextureHandle target = graph.importTexture("target", p, graph::ResourceState{},
                                                              graph::FinalUse{graph::Access::TransferSrc});
            auto cleared = std::make_shared<graph::TextureHandle>();
            graph.addPass(
                "clear", [&](graph::PassBuilder& b) { *cleared = b.write(target, graph::Access::TransferDst); },
                [cleared](graph::PassContext& pc) {
                    VkClearColorValue black{};
                    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                    vkCmdClearColorImage(pc.commandBuffer(), pc.image(*cleared), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                         &black, 1, &range);
                });
            graph.markOutput(ui.addPass(graph, *ImGui::GetDrawData(), *cleared));
            graph.compile();
            ctx().runImmediate([&](VkCommandBuffer cmd) { graph.execute(cmd); });
            ctx().waitIdle();
        }
        stats = ui.lastFrame();
        pixels = vk::readbackImage(ctx(), image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        ctx().destroy(image);
    }
    ImGui::DestroyContext();

    EXPECT_GE(stats.drawCalls, 2u);  // the clip rectangle splits the list into commands
    const Box red{8, 8, 24, 24}, blue{32, 8, 48, 24}, green{40, 32, 48, 40}, text{4, 44, 24, 60};
    uint32_t glyphPixels = 0, wrong = 0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            const uint8_t* px = &pixels[(size_t(y) * kSize + size_t(x)) * 4];
            int r = px[0], g = px[1], b = px[2];
            if (text.contains(x, y)) {
                glyphPixels += (r > 0);
                wrong += (r != g || g != b);  // white glyphs blended over black stay grey
                continue;
            }
            int er = 0, eg = 0, eb = 0;
            if (red.contains(x, y)) er = 255;
            if (blue.contains(x, y)) eb = 128;  // 255 * 128/255 over black
            if (green.contains(x, y)) eg = 255;
            bool ok = r == er && g == eg && std::abs(b - eb) <= 1;
            if (!ok && wrong < 8)
                ADD_FAILURE() << "pixel (" << x << ", " << y << ") = " << r << " " << g << " " << b << ", expected " << er
                              << " " << eg << " " << eb;
            wrong += !ok;
        }
    }
    EXPECT_EQ(wrong, 0u);
    // "Hi" at 13 px: its strokes cover part of the box, not all of it and not nothing.
    EXPECT_GT(glyphPixels, 15u);
    EXPECT_LT(glyphPixels, uint32_t(text.x1 - text.x0) * uint32_t(text.y1 - text.y0) / 2);
}

}  // namespace
}  // namespace idk::test
