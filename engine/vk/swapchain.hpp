// swapchain.hpp: presentation to a surface (the viewer's window, or a headless surface in tests). Acquire and
// present use binary semaphores per swapchain image; an out-of-date or suboptimal swapchain is recreated at the
// next acquire with the surface's current extent.
#pragma once
#include <volk.h>

#include <optional>
#include <vector>

namespace idk::vk {

class Context;

struct SwapchainDesc {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkExtent2D preferredExtent{1280, 720};  // used when the surface does not dictate its extent
    bool vsync = true;                      // FIFO; otherwise MAILBOX or IMMEDIATE when available
};

struct AcquiredImage {
    uint32_t index = 0;
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE;      // wait on it (COLOR_ATTACHMENT_OUTPUT) before writing the image
    VkSemaphore renderFinished = VK_NULL_HANDLE; // signal it when the frame's commands are done; present waits on it
};

class Swapchain {
public:
    Swapchain(Context& ctx, const SwapchainDesc& desc);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // nullopt when the surface has zero size (minimised window): skip the frame.
    std::optional<AcquiredImage> acquire();
    void present(const AcquiredImage& image);
    void resize(VkExtent2D extent);  // recreate at the next acquire
    void setVsync(bool vsync);       // FIFO or MAILBOX/IMMEDIATE from the next acquire (recreates)
    bool vsync() const noexcept { return desc_.vsync; }
    VkPresentModeKHR presentMode() const noexcept { return presentMode_; }

    VkFormat format() const noexcept { return format_; }
    VkExtent2D extent() const noexcept { return extent_; }
    uint32_t imageCount() const noexcept { return static_cast<uint32_t>(images_.size()); }
    uint32_t recreateCount() const noexcept { return recreations_; }

private:
    void create();
    void destroyViews();

    Context& ctx_;
    SwapchainDesc desc_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkSemaphore> acquireSemaphores_;  // one more than images: the next acquire's is always free
    std::vector<VkSemaphore> finishedSemaphores_; // per image
    std::vector<uint64_t> acquireSemaphoreFreeAt_; // timeline value after which an acquire semaphore is reusable
    uint32_t nextAcquire_ = 0;
    bool outOfDate_ = false;
    uint32_t recreations_ = 0;
};

}  // namespace idk::vk
