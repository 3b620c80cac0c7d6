// window.cpp: GLFW window creation (GLFW_NO_API), the Vulkan surface through GLFW, fullscreen and cursor mode.
#include "viewer/window.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "vk/check.hpp"

namespace idk::viewer {
namespace {

std::string lastGlfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown GLFW error";
}

}  // namespace

Window::Window(uint32_t width, uint32_t height, const std::string& title) {
    if (!glfwInit()) throw NoDisplayError("cannot open a display (" + lastGlfwError() + ")");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw NoDisplayError("GLFW finds no Vulkan loader with window-system support");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);  // Vulkan presents; no OpenGL context
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!window_) {
        std::string error = lastGlfwError();
        glfwTerminate();
        throw NoDisplayError("cannot create a window (" + error + ")");
    }
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<const char*> Window::requiredInstanceExtensions() {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) throw NoDisplayError("GLFW reports no Vulkan surface extensions (" + lastGlfwError() + ")");
    return {names, names + count};
}

VkSurfaceKHR Window::createSurface(VkInstance instance) {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    vk::check(glfwCreateWindowSurface(instance, window_, nullptr, &surface));
    return surface;
}

VkExtent2D Window::framebufferSize() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {uint32_t(w < 0 ? 0 : w), uint32_t(h < 0 ? 0 : h)};
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void Window::toggleFullscreen() {
    if (!fullscreen_) {
        GLFWmonitor* monitor = glfwGetPrimaryMonitor();
        const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
        if (!mode) return;  // no monitor to fill (e.g. some virtual displays): stay windowed
        glfwGetWindowPos(window_, &windowedX_, &windowedY_);
        glfwGetWindowSize(window_, &windowedW_, &windowedH_);
        glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
        fullscreen_ = true;
    } else {
        glfwSetWindowMonitor(window_, nullptr, windowedX_, windowedY_, windowedW_, windowedH_, 0);
        fullscreen_ = false;
    }
}

void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

void Window::resize(uint32_t width, uint32_t height) { glfwSetWindowSize(window_, int(width), int(height)); }

void Window::setCursorCaptured(bool captured) {
    glfwSetInputMode(window_, GLFW_CURSOR, captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
}

}  // namespace idk::viewer
