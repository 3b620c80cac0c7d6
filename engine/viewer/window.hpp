// window.hpp: the viewer's GLFW window (no client API: Vulkan presents to it) and its Vulkan surface, with
// fullscreen toggling on the current monitor. GLFW is initialised here; a machine without a display makes the
// constructor throw NoDisplayError.
#pragma once
#include <volk.h>

#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace idk::viewer {

class NoDisplayError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class Window {
public:
    Window(uint32_t width, uint32_t height, const std::string& title);  // throws NoDisplayError
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // The instance extensions presentation to this window needs (VK_KHR_surface + the platform's).
    static std::vector<const char*> requiredInstanceExtensions();
    VkSurfaceKHR createSurface(VkInstance instance);  // owned by the caller (vkDestroySurfaceKHR)

    GLFWwindow* handle() const noexcept { return window_; }
    VkExtent2D framebufferSize() const;  // 0x0 while minimised
    bool shouldClose() const;
    void requestClose();
    void toggleFullscreen();
    void setTitle(const std::string& title);
    void resize(uint32_t width, uint32_t height);  // asks for a new window size (takes effect once the WM agrees)
    bool fullscreen() const noexcept { return fullscreen_; }
    void setCursorCaptured(bool captured);  // FPS mode: hidden and unbounded (mouse look)

private:
    GLFWwindow* window_ = nullptr;
    bool fullscreen_ = false;
    int windowedX_ = 0, windowedY_ = 0, windowedW_ = 0, windowedH_ = 0;
};

}  // namespace idk::viewer
