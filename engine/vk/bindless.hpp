// bindless.hpp: the one global descriptor set (set 0, see shaders_glsl/shared/bindings.h). Resources are
// addressed in shaders by typed integer indices; freed indices are reused only after every submission that
// could still read them has completed (deferred release on the context's timeline).
#pragma once
#include <volk.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace idk::vk {

class Context;

// Distinct types so a storage-image index cannot be passed where a texture index is expected.
struct SampledIndex { uint32_t value = UINT32_MAX; };
struct StorageImageIndex { uint32_t value = UINT32_MAX; };
struct SamplerIndex { uint32_t value = UINT32_MAX; };
struct StorageBufferIndex { uint32_t value = UINT32_MAX; };

struct SamplerDesc {
    VkFilter filter = VK_FILTER_LINEAR;
    VkSamplerMipmapMode mipmap = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    float maxAnisotropy = 1.0f;  // > 1 enables anisotropic filtering when the device supports it
    VkSamplerReductionMode reduction = VK_SAMPLER_REDUCTION_MODE_WEIGHTED_AVERAGE;  // MIN/MAX for Hi-Z
    bool compare = false;  // depth comparison (shadow samplers): returns reference `compareOp` texel, filtered
    VkCompareOp compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
};

class BindlessTable {
public:
    explicit BindlessTable(Context& context);
    ~BindlessTable();
    BindlessTable(const BindlessTable&) = delete;
    BindlessTable& operator=(const BindlessTable&) = delete;

    // Sampled images are read in SHADER_READ_ONLY_OPTIMAL, storage images in GENERAL (the render graph puts
    // them there before each pass).
    SampledIndex addSampled(VkImageView view);
    StorageImageIndex addStorage(VkImageView view);
    SamplerIndex addSampler(const SamplerDesc& desc);  // the sampler object is owned by the table
    StorageBufferIndex addBuffer(VkBuffer buffer, VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
    // The whole buffer as one storage-buffer descriptor: `size` above the device's maxStorageBufferRange throws
    // DeviceLimitError naming `name` (a descriptor range over the limit is a validation error; buffer device
    // address access has no such limit).
    StorageBufferIndex addBuffer(VkBuffer buffer, VkDeviceSize size, const std::string& name);

    void release(SampledIndex index);
    void release(StorageImageIndex index);
    void release(StorageBufferIndex index);
    void release(SamplerIndex index);

    VkDescriptorSetLayout layout() const noexcept { return layout_; }
    VkDescriptorSet set() const noexcept { return set_; }
    uint32_t capacity(uint32_t binding) const { return slots_[binding].capacity; }
    uint32_t liveCount(uint32_t binding) const;

    // Binds the global set for the graphics and compute bind points.
    void bind(VkCommandBuffer cmd) const;

private:
    struct Slots {
        uint32_t capacity = 0;
        uint32_t next = 0;               // never-used slots start here
        std::vector<uint32_t> freeList;  // released and retired
        uint32_t live = 0;
    };
    uint32_t acquire(uint32_t binding);
    void retire(uint32_t binding, uint32_t index);

    Context& context_;
    VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    mutable std::mutex mutex_;
    Slots slots_[4];
    std::vector<VkSampler> samplers_;  // by sampler index
};

}  // namespace idk::vk
