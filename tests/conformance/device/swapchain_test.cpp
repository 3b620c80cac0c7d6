// swapchain_test.cpp: the swapchain path on a headless surface (VK_EXT_headless_surface, which lavapipe has):
// acquire, a render-graph pass that clears the image and leaves it in PRESENT layout, present; then a resize
// that recreates the swapchain. Validation must stay silent throughout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "graph/render_graph.hpp"
#include "render/vk_graph_backend.hpp"
#include "vk/check.hpp"
#include "vk/frames.hpp"
#include "vk/swapchain.hpp"

namespace idk::test {
namespace {

bool hasHeadlessSurface() {
    if (volkInitialize() != VK_SUCCESS) return false;
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, exts.data());
    return std::any_of(exts.begin(), exts.end(), [](const auto& e) {
        return std::strcmp(e.extensionName, VK_EXT_HEADLESS_SURFACE_EXTENSION_NAME) == 0;
    });
}

void renderAndPresent(vk::Swapchain& swapchain, vk::FrameRing& frames, graph::ResourcePool& pool,
                      float shade) {
    std::optional<vk::AcquiredImage> acquired = swapchain.acquire();
    ASSERT_TRUE(acquired.has_value());
    graph::RenderGraph graph(pool, swapchain.extent());
    graph::PhysicalTexture physical;
    physical.image = acquired->image;
    physical.view = acquired->view;
    physical.format = swapchain.format();
    physical.extent = {swapchain.extent().width, swapchain.extent().height, 1};
    graph::ResourceState justAcquired;
    justAcquired.writeStages = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    graph::TextureHandle image =
        graph.importTexture("swapchain", physical, justAcquired, graph::FinalUse{graph::Access::Present});
    auto written = std::make_shared<graph::TextureHandle>();
    graph.addPass(
        "clear", [&](graph::PassBuilder& b) { *written = b.write(image, graph::Access::ColorWrite); },
        [written, shade](graph::PassContext& pc) {
            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = pc.view(*written);
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            color.clearValue.color = {{shade, 0.5f, 0.25f, 1.0f}};
            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
            info.renderArea = {{0, 0}, pc.outputExtent()};
            info.layerCount = 1;
            info.colorAttachmentCount = 1;
            info.pColorAttachments = &color;
            vkCmdBeginRendering(pc.commandBuffer(), &info);
            vkCmdEndRendering(pc.commandBuffer());
        });
    graph.markOutput(*written);
    VkCommandBuffer cmd = frames.begin();
    graph.execute(cmd);
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = acquired->acquired;
    wait.stageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = acquired->renderFinished;
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;  // the PRESENT transition has no later stage
    frames.end({&wait, 1}, {&signal, 1});
    swapchain.present(*acquired);
}

TEST(Swapchain, PresentsAndRecreatesOnAHeadlessSurface) {
    if (!hasHeadlessSurface()) GTEST_SKIP() << "loader has no VK_EXT_headless_surface";
    vk::ContextDesc desc;
    desc.validation = true;
    desc.presentation = true;
    desc.instanceExtensions = {VK_KHR_SURFACE_EXTENSION_NAME, VK_EXT_HEADLESS_SURFACE_EXTENSION_NAME};
    vk::Context ctx(desc);
    VkHeadlessSurfaceCreateInfoEXT surfaceInfo{VK_STRUCTURE_TYPE_HEADLESS_SURFACE_CREATE_INFO_EXT};
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    vk::check(vkCreateHeadlessSurfaceEXT(ctx.instance(), &surfaceInfo, nullptr, &surface));
    {
        vk::Swapchain swapchain(ctx, {surface, {96, 64}, true});
        EXPECT_EQ(swapchain.extent().width, 96u);
        EXPECT_EQ(swapchain.extent().height, 64u);
        EXPECT_GE(swapchain.imageCount(), 2u);
        render::VkGraphBackend backend(ctx);
        {
            graph::ResourcePool pool(backend);
            vk::FrameRing frames(ctx);
            for (int frame = 0; frame < 5; ++frame) renderAndPresent(swapchain, frames, pool, frame * 0.2f);
            swapchain.resize({48, 40});
            renderAndPresent(swapchain, frames, pool, 1.0f);
            EXPECT_EQ(swapchain.recreateCount(), 1u);
            EXPECT_EQ(swapchain.extent().width, 48u);
            ctx.waitIdle();
        }
    }
    vkDestroySurfaceKHR(ctx.instance(), surface, nullptr);
    EXPECT_EQ(ctx.validationErrors(), 0u);
    for (const std::string& m : ctx.validationMessages()) ADD_FAILURE() << m;
}

}  // namespace
}  // namespace idk::test
