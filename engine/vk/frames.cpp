// frames.cpp: frame slots on the context's timeline semaphore.
#include "vk/frames.hpp"

#include <stdexcept>

#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::vk {

FrameRing::FrameRing(Context& ctx, uint32_t framesInFlight) : ctx_(ctx), slots_(framesInFlight) {
    for (uint32_t i = 0; i < framesInFlight; ++i) {
        VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        // RESET_COMMAND_BUFFER: a pass that hands work to another API mid-frame (passes/vxgi_gl_accumulate.hpp)
        // submits the frame's command buffer, waits, and begins it again (an implicit reset).
        pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = ctx.queueFamily();
        check(vkCreateCommandPool(ctx.device(), &pool, nullptr, &slots_[i].pool));
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = slots_[i].pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        check(vkAllocateCommandBuffers(ctx.device(), &alloc, &slots_[i].cmd));
    }
}

FrameRing::~FrameRing() {
    for (FrameSlot& s : slots_) {
        if (s.submittedValue) ctx_.waitFor(s.submittedValue);
        vkDestroyCommandPool(ctx_.device(), s.pool, nullptr);
    }
}

VkCommandBuffer FrameRing::begin() {
    if (recording_) throw std::logic_error("FrameRing::begin called twice without end");
    current_ = static_cast<uint32_t>(frameNumber_ % slots_.size());
    FrameSlot& slot = slots_[current_];
    // SYNC: the slot's command buffer may still execute; wait for its timeline value before resetting it.
    if (slot.submittedValue) ctx_.waitFor(slot.submittedValue);
    ctx_.collectGarbage();
    check(vkResetCommandPool(ctx_.device(), slot.pool, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(slot.cmd, &begin));
    recording_ = true;
    return slot.cmd;
}

uint64_t FrameRing::end(std::span<const VkSemaphoreSubmitInfo> waits, std::span<const VkSemaphoreSubmitInfo> signals) {
    if (!recording_) throw std::logic_error("FrameRing::end without begin");
    FrameSlot& slot = slots_[current_];
    check(vkEndCommandBuffer(slot.cmd));
    slot.submittedValue = ctx_.submit(slot.cmd, waits, signals);
    recording_ = false;
    ++frameNumber_;
    return slot.submittedValue;
}

}  // namespace idk::vk
