// viewer_app.hpp: idk-viewer: a GLFW window presenting frames of the same render::Renderer that `idk render`
// uses (Renderer::renderFrame into the swapchain image), plus input, the engine-drawn ImGui UI, picking, the
// fly camera with collision, shot lights, camera recording/replay and shader hot reload. Ports the role of
// IDKEngine's Application.cs (its controls table: README "Controls").
#pragma once
#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/scene.hpp"
#include "tools/camera_capture.hpp"
#include "tools/camera_controller.hpp"
#include "tools/collision.hpp"
#include "ui/ui_renderer.hpp"
#include "viewer/input.hpp"
#include "viewer/options.hpp"
#include "viewer/picking.hpp"
#include "viewer/pt_view.hpp"
#include "viewer/shader_reload.hpp"
#include "viewer/shot_lights.hpp"
#include "viewer/window.hpp"
#include "vk/context.hpp"
#include "vk/memory_log.hpp"
#include "vk/shader_library.hpp"
#include "vk/swapchain.hpp"

namespace idk::viewer {

// Everything the panels show or edit (plain data; viewer_app.cpp owns the behaviour).
struct ViewerState {
    bool guiMode = true;       // E: GUI (cursor free, UI gets input) or FPS (cursor captured, mouse look)
    bool guiVisible = true;    // G
    bool timePaused = false;   // T
    bool replaying = false;    // Ctrl+Space
    double sceneTime = 0.0;
    double replayTime = 0.0;
    uint64_t frame = 0;
    std::optional<Pick> selected;
    std::deque<float> frameMs;  // last 240 frame times (CPU wall clock)
    render::FrameInfo lastFrame;
    std::string status;         // last notable event (recording saved, replay started...)
    // Set while the device has failed (lost, out of memory): nothing renders, the window stays open and offers
    // a retry with smaller settings (Enter) or quitting (Esc). See device_recovery.cpp.
    struct DeviceFailure {
        std::string message;
        int exitCode = 0;  // what the run returns if it ends in this state: 3 device lost, 4 out of memory
    };
    std::optional<DeviceFailure> deviceFailure;
    uint32_t deviceRetries = 0;
    PtViewSettings pt;          // P: path-traced mode and its settings (pt_view.hpp)
};

class Viewer {
public:
    explicit Viewer(const ViewerOptions& options);  // throws NoDisplayError without a display
    ~Viewer();
    int run();  // the frame loop; returns the exit code

    // Used by the panels (panels.cpp).
    ViewerOptions options;
    ViewerState state;
    std::unique_ptr<Window> window;
    std::unique_ptr<vk::Context> ctx;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    std::unique_ptr<vk::Swapchain> swapchain;
    std::unique_ptr<vk::ShaderLibrary> shaders;
    scene::Scene scene;
    std::unique_ptr<render::Renderer> renderer;
    std::unique_ptr<render::SceneTextureStream> textures;
    std::unique_ptr<ui::UiRenderer> ui;
    std::unique_ptr<ShaderReloader> reloader;
    tools::CollisionWorld collision;
    tools::FlyCameraParams flyParams;
    tools::FlyCameraState camera;
    scene::CameraView lens;            // projection of the scene's default camera
    tools::CaptureRecorder recorder;
    std::optional<tools::Capture> replay;
    ShotLights shotLights;
    Input input;
    std::optional<vk::MemoryLog> memoryLog;
    std::unique_ptr<PtView> pathTracer;  // created when the path-traced mode first shows a frame

    scene::CameraView currentView() const { return tools::toCameraView(camera, lens); }

private:
    // device_recovery.cpp: everything that belongs to the VkDevice, created and destroyed together so a failed
    // device can be replaced while the window, the scene and the UI state stay.
    void createDevice();
    void destroyDevice();
    void onDeviceFailure(const std::string& kind, const std::exception& error, int exitCode);
    void retryWithSmallerSettings();
    uint32_t earlierValidationErrors_ = 0;  // counted on devices destroyed by a retry
    bool runFrame(float dt, float wall, bool& imguiFrame);
    int finish();
    void handleEvents();
    void handleKey(const KeyEvent& e);
    void toggleRecording();
    void toggleReplay();
    void update(float dt);
    bool renderAndPresent();  // false when nothing was presented (minimised)
    void writeScreenshot();
    bool imguiReady_ = false;
};

// Draws every panel for the current frame (ImGui::NewFrame already called).
void drawPanels(Viewer& viewer);

// `idk-viewer ARGS`: exit code (1 with a message for a missing display or bad input).
int runViewer(const std::vector<std::string>& argv);

}  // namespace idk::viewer
