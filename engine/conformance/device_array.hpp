// device_array.hpp: a helper owning a GPU buffer of 32-bit elements registered in the bindless table, with
// typed upload/download, and the input generators shared by the compute-primitive conformance checks (and tests).
#pragma once
#include <algorithm>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "render/compute_primitives.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {

class DeviceArray {
public:
    DeviceArray(vk::Context& ctx, uint32_t elements, const std::string& name) : ctx_(ctx) {
        // At least one element: a zero-sized buffer is invalid and a zero-count dispatch may still be bound to it.
        buffer_ = ctx.createBuffer({VkDeviceSize(std::max(elements, 1u)) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    vk::MemoryUsage::GpuOnly, name, "test"});
        index_ = ctx.bindless().addBuffer(buffer_.buffer);
    }
    ~DeviceArray() {
        ctx_.bindless().release(index_);
        ctx_.destroyDeferred(buffer_);
    }
    DeviceArray(const DeviceArray&) = delete;
    DeviceArray& operator=(const DeviceArray&) = delete;

    render::GpuArray array(uint32_t offset = 0) const { return {index_, offset}; }
    template <class T>
    void upload(const std::vector<T>& values, uint32_t offsetElements = 0) {
        static_assert(sizeof(T) == 4);
        vk::uploadBuffer(ctx_, buffer_, std::span<const T>(values), VkDeviceSize(offsetElements) * 4);
    }
    template <class T>
    std::vector<T> download(uint32_t count, uint32_t offsetElements = 0) {
        static_assert(sizeof(T) == 4);
        if (count == 0) return {};
        return vk::downloadBuffer<T>(ctx_, buffer_, count, VkDeviceSize(offsetElements) * 4);
    }

private:
    vk::Context& ctx_;
    vk::Buffer buffer_;
    vk::StorageBufferIndex index_;
};

// Uniform uint32 in [0, bound) (bound 0 = the full range), from a fixed seed so failures reproduce.
inline std::vector<uint32_t> randomUints(size_t count, uint32_t bound, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint32_t> v(count);
    for (uint32_t& x : v) x = bound ? uint32_t(rng() % bound) : uint32_t(rng());
    return v;
}

}  // namespace idk::conformance
