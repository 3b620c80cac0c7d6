// device_recovery.cpp: the viewer's device objects (context, surface, swapchain, shaders, renderer, texture
// stream, UI pass) created and destroyed as one, and what happens when the device fails mid-run. On
// VK_ERROR_DEVICE_LOST or VK_ERROR_OUT_OF_DEVICE_MEMORY the viewer does not exit: it destroys every device object
// (after a loss the spec requires exactly that before anything renders again), keeps the window, the scene and its
// state, names the error on stderr and in the window title, and offers a retry with smaller settings (Enter): half
// the window size (at least 64 pixels a side; fewer pixels means smaller render targets) and the portable rung of
// every capability ladder (--fallback: the features most likely to have failed are left out). Esc quits with the
// error's exit code (3 lost, 4 out of memory, as `idk render`). No UI can be drawn while there is no device, so the
// message lives in the title bar; after a successful retry the panel's status line says what was changed.
#include "viewer/viewer_app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>

#include "app/cli_context.hpp"
#include "core/cli.hpp"
#include "core/log.hpp"
#include "frame/culling_feature.hpp"
#include "vk/check.hpp"

namespace idk::viewer {

void Viewer::createDevice() {
    vk::ContextDesc desc;
    desc.validation = desc.validation && options.validation;
    desc.forceFallbackRungs = options.fallback;
    for (const std::string& spec : options.rungs) desc.forcedRungs.push_back(vk::parseRungForce(spec));
    desc.instanceExtensions = Window::requiredInstanceExtensions();
    desc.presentation = true;
    ctx = std::make_unique<vk::Context>(desc);
    app::checkForcedRungs(*ctx);  // a rung this device cannot run: exit 2
    if (std::string e = frame::CullingFeature::geometryError(*ctx, options.settings.culling); !e.empty())
        throw core::CliError(e);  // --geometry mesh without mesh shaders: exit 2 too
    surface = window->createSurface(ctx->instance());
    vk::SwapchainDesc sc;
    sc.surface = surface;
    sc.preferredExtent = window->framebufferSize();
    sc.vsync = options.vsync;
    swapchain = std::make_unique<vk::Swapchain>(*ctx, sc);
    shaders = std::make_unique<vk::ShaderLibrary>(*ctx, shaders::kSpirvDir,
                                                  options.shaderDir.value_or(shaders::kShaderSourceDir));
    reloader = std::make_unique<ShaderReloader>(*shaders);

    renderer = std::make_unique<render::Renderer>(*ctx, *shaders, options.settings);
    renderer->setScene(scene);
    textures = std::make_unique<render::SceneTextureStream>(*ctx, *renderer, scene);
    if (options.syncTextures) textures->finishSynchronously();
    if (imguiReady_) ui = std::make_unique<ui::UiRenderer>(*ctx, *shaders);  // a retry (the first is in the ctor)
}

void Viewer::destroyDevice() {
    if (ctx) {
        ctx->waitIdle();  // returns at once on a lost device (Context::deviceLost)
        earlierValidationErrors_ += ctx->validationErrors();
        for (const std::string& m : ctx->validationMessages()) std::fprintf(stderr, "  %s\n", m.c_str());
    }
    ui.reset();
    pathTracer.reset();  // a new device builds a new tracer (the settings stay in state.pt)
    textures.reset();
    if (renderer) options.settings = renderer->settings();  // a recovered device keeps the panels' settings
    renderer.reset();
    swapchain.reset();
    if (surface) vkDestroySurfaceKHR(ctx->instance(), surface, nullptr);
    surface = VK_NULL_HANDLE;
    reloader.reset();
    shaders.reset();
    ctx.reset();
}

void Viewer::onDeviceFailure(const std::string& kind, const std::exception& error, int exitCode) {
    if (ctx && exitCode == 3) ctx->markLost();  // e.g. seen at present: the context must not wait for the GPU
    std::fprintf(stderr,
                 "idk-viewer: frame %llu: %s (%s). The window stays open: press Enter to retry at half the size "
                 "with the portable feature rungs, Esc to quit.\n",
                 static_cast<unsigned long long>(state.frame), kind.c_str(), error.what());
    state.deviceFailure = ViewerState::DeviceFailure{kind + " (" + error.what() + ")", exitCode};
    try {
        destroyDevice();
    } catch (const std::exception& e) {  // a second failure while tearing down: nothing left to render with anyway
        std::fprintf(stderr, "idk-viewer: while releasing the failed device: %s\n", e.what());
    }
    window->setTitle("idk-viewer: " + kind + " - Enter: retry at half size with portable features, Esc: quit");
}

void Viewer::retryWithSmallerSettings() {
    const VkExtent2D size = window->framebufferSize();
    const uint32_t width = std::max(64u, size.width / 2), height = std::max(64u, size.height / 2);
    window->resize(width, height);
    options.fallback = true;
    options.rungs.clear();  // a forced rung may be what failed; the retry takes the portable rung everywhere
    ++state.deviceRetries;
    try {
        createDevice();
    } catch (const vk::Error& e) {
        const bool lost = e.result() == VK_ERROR_DEVICE_LOST;
        onDeviceFailure(lost ? "device lost again" : "retry failed", e, lost ? 3 : 4);
        return;
    }
    state.status = core::concat("recovered from ", state.deviceFailure->message, ": retry ", state.deviceRetries,
                                " at ", width, "x", height, " with the portable feature rungs");
    std::printf("idk-viewer: %s\n", state.status.c_str());
    state.deviceFailure.reset();
    window->setTitle("idk-viewer");
}

}  // namespace idk::viewer
