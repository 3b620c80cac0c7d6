// frames.hpp: frames in flight. Each frame slot has its own command pool and command buffer; begin() waits on
// the timeline value of the slot's previous submission (so at most framesInFlight frames are queued), recycles
// the pool and runs deferred destruction that has become safe.
#pragma once
#include <volk.h>

#include <span>
#include <vector>

namespace idk::vk {

class Context;

struct FrameSlot {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    uint64_t submittedValue = 0;  // timeline value signalled when this slot's last submission finished
};

class FrameRing {
public:
    explicit FrameRing(Context& ctx, uint32_t framesInFlight = 2);
    ~FrameRing();
    FrameRing(const FrameRing&) = delete;
    FrameRing& operator=(const FrameRing&) = delete;

    VkCommandBuffer begin();  // returns the frame's command buffer, recording
    uint64_t end(std::span<const VkSemaphoreSubmitInfo> waits = {},
                 std::span<const VkSemaphoreSubmitInfo> signals = {});  // submits; returns the timeline value
    uint32_t slotIndex() const noexcept { return current_; }
    uint64_t frameNumber() const noexcept { return frameNumber_; }
    uint32_t framesInFlight() const noexcept { return static_cast<uint32_t>(slots_.size()); }

private:
    Context& ctx_;
    std::vector<FrameSlot> slots_;
    uint32_t current_ = 0;
    uint64_t frameNumber_ = 0;
    bool recording_ = false;
};

}  // namespace idk::vk
