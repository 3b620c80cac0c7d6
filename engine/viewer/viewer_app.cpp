// viewer_app.cpp: the viewer's set-up, frame loop, controls and presentation.
#include "viewer/viewer_app.hpp"

#include "frame/settings_table.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/cli_context.hpp"
#include "app/default_scene.hpp"
#include "core/cli.hpp"
#include "core/image_file.hpp"
#include "core/log.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "vk/check.hpp"

namespace idk::viewer {

Viewer::Viewer(const ViewerOptions& opts) : options(opts) {
    state.pt = options.pathTrace;
    // The window first: without a display nothing else is worth loading.
    window = std::make_unique<Window>(options.width, options.height, "idk-viewer");
    std::vector<ScriptEvent> script;
    if (options.script) script = parseInputScript(*options.script);
    scene = options.scene ? scene::loadGltf(*options.scene, options.load) : app::loadDefaultScene();
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "idk-viewer: warning: %s\n", w.c_str());

    createDevice();
    if (options.memoryLog) memoryLog.emplace(*options.memoryLog, 100);

    collision = tools::CollisionWorld::fromScene(scene);
    flyParams = tools::flyParamsForBounds(scene.bounds);
    lens = scene::defaultCamera(scene);
    camera = tools::fromCameraView(lens);

    input.attach(window->handle());  // before ImGui's backend, which chains to these callbacks
    input.setScript(std::move(script));
    if (options.ui) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
        ImGui::StyleColorsDark();
        ImGui_ImplGlfw_InitForVulkan(window->handle(), true);
        imguiReady_ = true;
        ui = std::make_unique<ui::UiRenderer>(*ctx, *shaders);
    }
    window->setCursorCaptured(!state.guiMode);
}

Viewer::~Viewer() {
    destroyDevice();
    if (imguiReady_) {
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    window.reset();
}

void Viewer::toggleRecording() {
    if (!recorder.recording()) {
        recorder.start({0.0, camera.position, camera.yaw, camera.pitch, lens.yfov, state.sceneTime, state.timePaused});
        state.status = "recording to " + options.captureFile.string();
        return;
    }
    recorder.stop();
    try {
        tools::writeCapture(options.captureFile, recorder.capture());
        state.status = core::concat("saved ", recorder.capture().frames.size(), " frames to ", options.captureFile.string());
    } catch (const std::exception& e) {
        state.status = e.what();
    }
    std::printf("idk-viewer: %s\n", state.status.c_str());
}

void Viewer::toggleReplay() {
    if (state.replaying) {
        state.replaying = false;
        state.status = "replay stopped";
        return;
    }
    try {
        replay = tools::readCapture(options.captureFile);
        if (replay->frames.empty()) throw tools::CaptureError(options.captureFile.string() + ": no frames recorded");
        state.replaying = true;
        state.replayTime = 0.0;
        state.status = core::concat("replaying ", replay->frames.size(), " frames of ", options.captureFile.string());
    } catch (const std::exception& e) {
        state.status = e.what();
    }
    std::printf("idk-viewer: %s\n", state.status.c_str());
}

void Viewer::handleKey(const KeyEvent& e) {
    if (!e.down) return;
    if (e.key == GLFW_KEY_ESCAPE) {
        window->requestClose();
        return;
    }
    // While an ImGui text field has the keyboard, keys are typing, not commands.
    if (imguiReady_ && state.guiMode && ImGui::GetIO().WantTextInput) return;
    const bool ctrl = (e.mods & GLFW_MOD_CONTROL) != 0;
    switch (e.key) {
        case GLFW_KEY_E:
            state.guiMode = !state.guiMode;
            window->setCursorCaptured(!state.guiMode);
            break;
        case GLFW_KEY_T: state.timePaused = !state.timePaused; break;
        case GLFW_KEY_G: state.guiVisible = !state.guiVisible; break;
        case GLFW_KEY_V: swapchain->setVsync(!swapchain->vsync()); break;
        case GLFW_KEY_F11: window->toggleFullscreen(); break;
        case GLFW_KEY_1: reloader->reloadAll(); break;
        case GLFW_KEY_P: state.pt.enabled = !state.pt.enabled; break;
        case GLFW_KEY_R:
            if (ctrl) toggleRecording();
            break;
        case GLFW_KEY_SPACE:
            if (ctrl) toggleReplay();
            break;
        default:
            if (e.key == mouseButtonCode(GLFW_MOUSE_BUTTON_RIGHT)) {
                VkExtent2D extent = swapchain->extent();
                if (state.guiMode) {
                    if (imguiReady_ && state.guiVisible && ImGui::GetIO().WantCaptureMouse) break;  // clicked a panel
                    state.selected = pickInstance(scene, collision, currentView(), input.cursor(), extent.width, extent.height);
                    if (state.selected)
                        std::printf("idk-viewer: selected instance %u (node %u '%s') at distance %.3f\n",
                                    state.selected->instance, state.selected->node,
                                    scene.nodes[state.selected->node].name.c_str(), state.selected->distance);
                    else
                        std::printf("idk-viewer: selected nothing\n");
                } else {
                    // Speed and size follow the scene's scale as the camera's do (flyParamsForBounds).
                    const float scale = flyParams.radius / tools::FlyCameraParams{}.radius;
                    shotLights.shoot(camera.position, tools::flyForward(camera.yaw, camera.pitch), 20.0f * scale,
                                     0.2f * scale, 5.0f * scale * scale);
                }
            }
            break;
    }
}

void Viewer::handleEvents() {
    for (const KeyEvent& e : input.events()) handleKey(e);
}

void Viewer::update(float dt) {
    renderer->settings().vrs.frameSeconds = std::max(dt, 1e-4f);  // VRS: screen motion per frame -> per second
    if (state.replaying && replay) {
        state.replayTime += dt;
        double duration = tools::captureDuration(*replay);
        double t = duration > 0 ? std::fmod(state.replayTime, duration) : 0.0;  // loops, as the original
        tools::CaptureFrame f = tools::sampleCapture(*replay, t);
        camera.position = f.position;
        camera.yaw = f.yaw;
        camera.pitch = f.pitch;
        camera.velocity = glm::vec3(0.0f);
        lens.yfov = f.yfov;
        state.sceneTime = f.sceneTime;
        state.timePaused = f.paused;
    } else {
        tools::FlyInput in;
        if (!state.guiMode) {
            in.forward = input.down(GLFW_KEY_W);
            in.back = input.down(GLFW_KEY_S);
            in.left = input.down(GLFW_KEY_A);
            in.right = input.down(GLFW_KEY_D);
            in.up = input.down(GLFW_KEY_SPACE);
            in.fast = input.down(GLFW_KEY_LEFT_SHIFT) || input.down(GLFW_KEY_RIGHT_SHIFT);
            in.slow = input.down(GLFW_KEY_LEFT_CONTROL) || input.down(GLFW_KEY_RIGHT_CONTROL);
            in.mouseDelta = input.mouseDelta();
        }
        camera = tools::stepFlyCamera(camera, in, dt, flyParams, &collision);
        if (!state.timePaused) state.sceneTime += dt;
    }
    // Animated scenes: pose at the scene time (the collision world keeps the rest pose: rebuilding its BVH every
    // frame would cost more than the frame).
    if (!scene.animations.empty() && (!state.timePaused || state.replaying)) {
        scene::evaluateAnimations(scene, state.sceneTime);
        renderer->setPose(scene);
    }
    if (!shotLights.lights().empty()) {
        shotLights.step(collision, dt);
        renderer->setExtraLights(shotLights.gpuLights());
    }
    if (recorder.recording())
        recorder.update(dt, {0.0, camera.position, camera.yaw, camera.pitch, lens.yfov, state.sceneTime, state.timePaused});
    if (options.watch) reloader->reloadChanged();
}

bool Viewer::renderAndPresent() {
    // The window's size decides the swapchain's (some platforms never report the old swapchain out of date).
    const VkExtent2D size = window->framebufferSize();
    if (size.width == 0 || size.height == 0) return false;  // minimised: render nothing while 0x0
    if (size.width != swapchain->extent().width || size.height != swapchain->extent().height) swapchain->resize(size);
    std::optional<vk::AcquiredImage> image = swapchain->acquire();
    if (!image) return false;
    const VkExtent2D extent = swapchain->extent();
    render::FrameTarget target;
    target.image.image = image->image;
    target.image.view = image->view;
    target.image.format = swapchain->format();
    target.image.extent = {extent.width, extent.height, 1};
    // SYNC: the frame's first access to the image (its layout transition) must follow the acquire semaphore's
    // wait, which happens at COLOR_ATTACHMENT_OUTPUT: naming that stage as the image's "last write" makes the
    // graph's first barrier start there, chaining it to the wait.
    target.image.backendData = 0;
    target.initial.writeStages = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    target.finalUse = graph::FinalUse{graph::Access::Present};
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = image->acquired;
    wait.stageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = image->renderFinished;
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    target.waits = {wait};
    target.signals = {signal};
    if (state.pt.enabled) {
        try {
            if (!pathTracer) pathTracer = std::make_unique<PtView>(*ctx, *shaders);
            pathTracer->update(scene, state.sceneTime, currentView(), extent.width, extent.height, state.pt,
                               renderer->settings(), state.lastFrame.timelineValue);
        } catch (const vk::Error&) {
            throw;  // device lost / out of memory: run() recovers
        } catch (const std::runtime_error& e) {  // e.g. a traversal this device cannot run: back to the rasterizer
            state.pt.enabled = false;
            pathTracer.reset();
            state.status = std::string("path tracer: ") + e.what();
            std::fprintf(stderr, "idk-viewer: %s\n", state.status.c_str());
        }
    }
    const bool pathTraced = state.pt.enabled, drawUi = ui && state.guiVisible;
    if (pathTraced || drawUi) {
        target.addPasses = [this, pathTraced, drawUi](graph::RenderGraph& graph, graph::TextureHandle color) {
            if (pathTraced) color = pathTracer->addPass(graph, color);  // over the raster frame, under the UI
            return drawUi ? ui->addPass(graph, *ImGui::GetDrawData(), color) : color;
        };
    }
    renderer->prepareSourceScene(scene);  // a shadow mode switched to ray-traced builds its geometry here
    state.lastFrame = renderer->renderFrame(currentView(), target);
    swapchain->present(*image);
    return true;
}

void Viewer::writeScreenshot() {
    uint32_t width = 0, height = 0;
    // In the path-traced mode, the image it showed last (the raster frame under it is not what was displayed).
    std::vector<uint8_t> bytes = state.pt.enabled && pathTracer ? pathTracer->displayed(width, height)
                                                                : renderer->readLastFrame(width, height);
    if (bytes.empty()) throw std::runtime_error(options.screenshot->string() + ": no frame was rendered");
    core::ImageRgba32f image;
    image.width = width;
    image.height = height;
    image.pixels.resize(bytes.size());
    // As FrameResult: decoded to linear so that writeImage's sRGB encoding reproduces the displayed bytes.
    for (size_t i = 0; i < bytes.size(); ++i) {
        float v = float(bytes[i]) / 255.0f;
        image.pixels[i] = i % 4 == 3 ? v : core::srgbToLinear(v);
    }
    core::writeImage(*options.screenshot, image);
    std::printf("idk-viewer: wrote %s (%ux%u)\n", options.screenshot->string().c_str(), width, height);
}

int Viewer::run() {
    auto last = std::chrono::steady_clock::now();
    while (!window->shouldClose() && (options.frames == 0 || state.frame < options.frames)) {
        glfwPollEvents();
        auto now = std::chrono::steady_clock::now();
        float wall = std::chrono::duration<float>(now - last).count();
        last = now;
        // A fixed step for scripts; the wall clock otherwise, capped so a stall (shader reload) is no jump.
        float dt = options.fixedDt ? *options.fixedDt : std::min(wall, 0.1f);
        input.beginFrame(state.frame, !state.guiMode);
        if (state.deviceFailure) {  // no device: only Enter (retry) and Esc (quit) do anything
            for (const KeyEvent& e : input.events()) {
                if (e.down && e.key == GLFW_KEY_ESCAPE) window->requestClose();
                if (e.down && e.key == GLFW_KEY_ENTER && !window->shouldClose()) retryWithSmallerSettings();
            }
            ++state.frame;  // counts loop turns, so scripts and --frames go on while waiting
            if (state.deviceFailure) glfwWaitEventsTimeout(0.01);
            continue;
        }
        bool imguiFrame = false;
        try {
            if (!runFrame(dt, wall, imguiFrame)) break;
        } catch (const vk::DeviceLostError& e) {
            if (imguiFrame) ImGui::EndFrame();
            onDeviceFailure("device lost", e, 3);
        } catch (const vk::OutOfDeviceMemoryError& e) {
            if (imguiFrame) ImGui::EndFrame();
            onDeviceFailure("out of device memory", e, 4);
        }
    }
    if (state.deviceFailure) {
        std::fprintf(stderr, "idk-viewer: exiting after %s\n", state.deviceFailure->message.c_str());
        return state.deviceFailure->exitCode;
    }
    return finish();
}

// One frame: UI, events, update, render and present. False when the window is closing.
bool Viewer::runFrame(float dt, float wall, bool& imguiFrame) {
    if (imguiReady_) {
        ImGuiIO& io = ImGui::GetIO();
        // FPS mode: the mouse steers the camera, not the panels.
        if (state.guiMode) io.ConfigFlags &= ~ImGuiConfigFlags_NoMouse;
        else io.ConfigFlags |= ImGuiConfigFlags_NoMouse;
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        imguiFrame = true;
    }
    handleEvents();
    if (glm::uvec2 size = input.resizeRequest(); size.x > 0) window->resize(size.x, size.y);
    if (window->shouldClose()) {
        if (imguiReady_) ImGui::EndFrame();
        return false;
    }
    update(dt);
    if (imguiReady_) {
        if (state.guiVisible) drawPanels(*this);
        ImGui::Render();
        imguiFrame = false;
    }
    if (!renderAndPresent()) {
        glfwWaitEventsTimeout(0.05);  // minimised: sleep until something happens
        return true;
    }
    state.frameMs.push_back(wall * 1000.0f);
    if (state.frameMs.size() > 240) state.frameMs.pop_front();
    if (memoryLog) memoryLog->sample(state.frame, ctx->allocator());
    ++state.frame;
    return true;
}

// After the loop: screenshot, recording, validation report and the final camera line (tests read it).
int Viewer::finish() {
    ctx->waitIdle();
    if (options.screenshot) writeScreenshot();
    if (recorder.recording()) toggleRecording();  // closing while recording keeps the recording
    if (ctx->validationErrors() + earlierValidationErrors_ != 0) {
        std::fprintf(stderr, "idk-viewer: %u Vulkan validation error(s)\n",
                     ctx->validationErrors() + earlierValidationErrors_);
        for (const std::string& m : ctx->validationMessages()) std::fprintf(stderr, "  %s\n", m.c_str());
        return 1;
    }
    // The final camera, for scripted runs (tests read it).
    std::printf("idk-viewer: camera position %.5f %.5f %.5f yaw %.5f pitch %.5f radius %.5f\n", camera.position.x,
                camera.position.y, camera.position.z, camera.yaw, camera.pitch, flyParams.radius);
    if (pathTracer)  // scripted runs of the path-traced mode (tests read it)
        std::printf("idk-viewer: path tracer %s, %u samples, %u restarts\n", state.pt.enabled ? "on" : "off",
                    pathTracer->samples(), pathTracer->restarts());
    double totalMs = 0.0;
    for (float ms : state.frameMs) totalMs += ms;
    std::printf("idk-viewer: %llu frames, %.2f ms per frame over the last %zu\n",
                static_cast<unsigned long long>(state.frame), state.frameMs.empty() ? 0.0 : totalMs / double(state.frameMs.size()),
                state.frameMs.size());
    return 0;
}

int runViewer(const std::vector<std::string>& argv) {
    try {
        ViewerOptions options = parseViewerOptions(argv);
        if (options.help) {
            std::fputs(kViewerHelp, stdout);
            std::fputs("rasterizer settings (also in the Renderer panel):\n", stdout);
            std::fputs(frame::settingOptionsHelp().c_str(), stdout);
            return 0;
        }
        Viewer viewer(options);
        return viewer.run();
    } catch (const NoDisplayError& e) {
        std::fprintf(stderr,
                     "idk-viewer: no display: %s.\n"
                     "  The viewer needs a window system (X11 or Wayland). To render without one, use\n"
                     "  `idk render SCENE --out image.png` (headless, any Vulkan device).\n",
                     e.what());
        return 1;
    } catch (const core::CliError& e) {
        std::fprintf(stderr, "idk-viewer: %s\n%s", e.what(), kViewerHelp);
        return 2;
    } catch (const vk::DeviceLostError& e) {  // while starting: no window worth keeping yet
        std::fprintf(stderr, "idk-viewer: device lost while starting (%s)\n", e.what());
        return 3;
    } catch (const vk::OutOfDeviceMemoryError& e) {
        std::fprintf(stderr, "idk-viewer: out of device memory while starting (%s)\n", e.what());
        return 4;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "idk-viewer: %s\n", e.what());
        return 1;
    }
}

}  // namespace idk::viewer
