// swapchain.cpp: surface format/present-mode choice, creation and recreation, acquire and present.
#include "vk/swapchain.hpp"

#include <algorithm>

#include "core/log.hpp"
#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::vk {

Swapchain::Swapchain(Context& ctx, const SwapchainDesc& desc) : ctx_(ctx), desc_(desc) { create(); }

Swapchain::~Swapchain() {
    ctx_.waitIdle();
    destroyViews();
    for (VkSemaphore s : acquireSemaphores_) vkDestroySemaphore(ctx_.device(), s, nullptr);
    for (VkSemaphore s : finishedSemaphores_) vkDestroySemaphore(ctx_.device(), s, nullptr);
    if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
}

void Swapchain::destroyViews() {
    for (VkImageView v : views_) vkDestroyImageView(ctx_.device(), v, nullptr);
    views_.clear();
}

void Swapchain::create() {
    VkPhysicalDevice physical = ctx_.physicalDevice();
    VkBool32 supported = VK_FALSE;
    check(vkGetPhysicalDeviceSurfaceSupportKHR(physical, ctx_.queueFamily(), desc_.surface, &supported));
    if (!supported) throw Error(VK_ERROR_INITIALIZATION_FAILED, "the graphics queue cannot present to this surface");

    VkSurfaceCapabilitiesKHR caps;
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, desc_.surface, &caps));
    uint32_t count = 0;
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, desc_.surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, desc_.surface, &count, formats.data()));
    // UNORM, not SRGB: the tonemapping pass writes display-encoded values itself.
    VkSurfaceFormatKHR chosen = formats.at(0);
    for (const VkSurfaceFormatKHR& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
            chosen = f;
    format_ = chosen.format;

    check(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, desc_.surface, &count, nullptr));
    std::vector<VkPresentModeKHR> modes(count);
    check(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, desc_.surface, &count, modes.data()));
    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
    if (!desc_.vsync) {
        for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
            if (std::find(modes.begin(), modes.end(), m) != modes.end()) {
                mode = m;
                break;
            }
    }

    presentMode_ = mode;

    // SPEC: currentExtent 0xFFFFFFFF means the surface takes the swapchain's size.
    extent_ = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : desc_.preferredExtent;
    extent_.width = std::clamp(extent_.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height = std::clamp(extent_.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    if (extent_.width == 0 || extent_.height == 0) return;  // minimised: create when it has a size again

    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount) imageCount = std::min(imageCount, caps.maxImageCount);
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = desc_.surface;
    info.minImageCount = imageCount;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;  // blit + UI pass
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    check(vkCreateSwapchainKHR(ctx_.device(), &info, nullptr, &created));
    if (swapchain_) {
        ctx_.waitIdle();  // the old images may still be in use by submitted frames
        destroyViews();
        vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
        ++recreations_;
    }
    swapchain_ = created;

    check(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &count, nullptr));
    images_.resize(count);
    check(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &count, images_.data()));
    for (uint32_t i = 0; i < count; ++i) {
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = images_[i];
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format_;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView v;
        check(vkCreateImageView(ctx_.device(), &view, nullptr, &v));
        views_.push_back(v);
        ctx_.setName(images_[i], VK_OBJECT_TYPE_IMAGE, "swapchain image " + std::to_string(i));
    }
    VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    while (acquireSemaphores_.size() < count + 1) {
        VkSemaphore s;
        check(vkCreateSemaphore(ctx_.device(), &sem, nullptr, &s));
        acquireSemaphores_.push_back(s);
        acquireSemaphoreFreeAt_.push_back(0);
    }
    while (finishedSemaphores_.size() < count) {
        VkSemaphore s;
        check(vkCreateSemaphore(ctx_.device(), &sem, nullptr, &s));
        finishedSemaphores_.push_back(s);
    }
    outOfDate_ = false;
}

void Swapchain::resize(VkExtent2D extent) {
    desc_.preferredExtent = extent;
    outOfDate_ = true;
}

void Swapchain::setVsync(bool vsync) {
    if (desc_.vsync == vsync) return;
    desc_.vsync = vsync;
    outOfDate_ = true;
}

std::optional<AcquiredImage> Swapchain::acquire() {
    if (outOfDate_ || !swapchain_) create();
    if (!swapchain_ || extent_.width == 0 || extent_.height == 0) return std::nullopt;
    for (int attempt = 0; attempt < 2; ++attempt) {
        uint32_t slot = nextAcquire_;
        // SYNC: a binary semaphore may be waited on again only after the submission that waited on it ran.
        ctx_.waitFor(acquireSemaphoreFreeAt_[slot]);
        VkSemaphore semaphore = acquireSemaphores_[slot];
        uint32_t index = 0;
        VkResult result = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, semaphore, VK_NULL_HANDLE, &index);
        if (result == VK_ERROR_OUT_OF_DATE_KHR) {
            create();
            if (!swapchain_) return std::nullopt;
            continue;
        }
        if (result == VK_SUBOPTIMAL_KHR) outOfDate_ = true;  // still usable this frame
        else check(result);
        nextAcquire_ = (slot + 1) % static_cast<uint32_t>(acquireSemaphores_.size());
        // The frame that waits on this semaphore is the next submission.
        acquireSemaphoreFreeAt_[slot] = ctx_.lastSubmittedValue() + 1;
        return AcquiredImage{index, images_[index], views_[index], semaphore, finishedSemaphores_[index]};
    }
    return std::nullopt;
}

void Swapchain::present(const AcquiredImage& image) {
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &image.renderFinished;
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &image.index;
    VkResult result = vkQueuePresentKHR(ctx_.queue(), &info);
    if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) {
        outOfDate_ = true;
        return;
    }
    check(result);
}

}  // namespace idk::vk
