// bindless.cpp: creates the update-after-bind set and hands out indices from free lists.
#include "vk/bindless.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/log.hpp"
#include "shared/bindings.h"
#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::vk {

BindlessTable::BindlessTable(Context& context) : context_(context) {
    const DeviceInfo& info = context.info();
    // Generous but bounded: the whole array must fit in one descriptor pool on every driver.
    slots_[gpu::kBindingSampledImages].capacity = std::min(info.maxSampledImagesUpdateAfterBind, 16384u);
    slots_[gpu::kBindingStorageImages].capacity = std::min(info.maxStorageImagesUpdateAfterBind, 4096u);
    slots_[gpu::kBindingSamplers].capacity = std::min(info.maxSamplersUpdateAfterBind, 128u);
    slots_[gpu::kBindingStorageBuffers].capacity = std::min(info.maxStorageBuffersUpdateAfterBind, 4096u);

    const VkDescriptorType types[4] = {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                       VK_DESCRIPTOR_TYPE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    VkDescriptorSetLayoutBinding bindings[4];
    VkDescriptorBindingFlags flags[4];
    VkDescriptorPoolSize sizes[4];
    for (uint32_t i = 0; i < 4; ++i) {
        bindings[i] = {i, types[i], slots_[i].capacity, VK_SHADER_STAGE_ALL, nullptr};
        // SPEC: PARTIALLY_BOUND lets unused slots stay empty; UPDATE_AFTER_BIND lets new textures be written
        // while earlier frames using the set are still in flight; UNUSED_WHILE_PENDING covers slot reuse.
        flags[i] = VK_DESCRIPTOR_BINDING_PARTIALLY_BOUND_BIT | VK_DESCRIPTOR_BINDING_UPDATE_AFTER_BIND_BIT |
                   VK_DESCRIPTOR_BINDING_UPDATE_UNUSED_WHILE_PENDING_BIT;
        sizes[i] = {types[i], slots_[i].capacity};
    }
    VkDescriptorSetLayoutBindingFlagsCreateInfo flagInfo{
        VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_BINDING_FLAGS_CREATE_INFO};
    flagInfo.bindingCount = 4;
    flagInfo.pBindingFlags = flags;
    VkDescriptorSetLayoutCreateInfo layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, &flagInfo};
    layout.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_UPDATE_AFTER_BIND_POOL_BIT;
    layout.bindingCount = 4;
    layout.pBindings = bindings;
    VkDevice device = context.device();
    check(vkCreateDescriptorSetLayout(device, &layout, nullptr, &layout_));

    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_UPDATE_AFTER_BIND_BIT;
    pool.maxSets = 1;
    pool.poolSizeCount = 4;
    pool.pPoolSizes = sizes;
    check(vkCreateDescriptorPool(device, &pool, nullptr, &pool_));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout_;
    check(vkAllocateDescriptorSets(device, &alloc, &set_));
    context.setName(set_, VK_OBJECT_TYPE_DESCRIPTOR_SET, "global bindless set");
}

BindlessTable::~BindlessTable() {
    VkDevice device = context_.device();
    for (VkSampler s : samplers_)
        if (s) vkDestroySampler(device, s, nullptr);
    vkDestroyDescriptorPool(device, pool_, nullptr);
    vkDestroyDescriptorSetLayout(device, layout_, nullptr);
}

uint32_t BindlessTable::acquire(uint32_t binding) {
    std::lock_guard lock(mutex_);
    Slots& s = slots_[binding];
    uint32_t index;
    if (!s.freeList.empty()) {
        index = s.freeList.back();
        s.freeList.pop_back();
    } else if (s.next < s.capacity) {
        index = s.next++;
    } else {
        throw std::runtime_error(core::concat("bindless binding ", binding, " is full (", s.capacity, " slots)"));
    }
    ++s.live;
    return index;
}

void BindlessTable::retire(uint32_t binding, uint32_t index) {
    if (index == UINT32_MAX) return;
    {
        std::lock_guard lock(mutex_);
        --slots_[binding].live;
    }
    // The slot may still be read by submitted work: hand it out again only after that work completes.
    context_.destroyDeferred([this, binding, index] {
        std::lock_guard lock(mutex_);
        slots_[binding].freeList.push_back(index);
    });
}

uint32_t BindlessTable::liveCount(uint32_t binding) const {
    std::lock_guard lock(mutex_);
    return slots_[binding].live;
}

namespace {
void writeImage(VkDevice device, VkDescriptorSet set, uint32_t binding, uint32_t index, VkDescriptorType type,
                VkImageView view, VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE) {
    VkDescriptorImageInfo image{sampler, view, layout};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.dstArrayElement = index;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pImageInfo = &image;
    vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}
}  // namespace

SampledIndex BindlessTable::addSampled(VkImageView view) {
    uint32_t i = acquire(gpu::kBindingSampledImages);
    writeImage(context_.device(), set_, gpu::kBindingSampledImages, i, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, view,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    return {i};
}

StorageImageIndex BindlessTable::addStorage(VkImageView view) {
    uint32_t i = acquire(gpu::kBindingStorageImages);
    writeImage(context_.device(), set_, gpu::kBindingStorageImages, i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, view,
               VK_IMAGE_LAYOUT_GENERAL);
    return {i};
}

SamplerIndex BindlessTable::addSampler(const SamplerDesc& desc) {
    VkSamplerReductionModeCreateInfo reduction{VK_STRUCTURE_TYPE_SAMPLER_REDUCTION_MODE_CREATE_INFO};
    reduction.reductionMode = desc.reduction;
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    if (desc.reduction != VK_SAMPLER_REDUCTION_MODE_WEIGHTED_AVERAGE) info.pNext = &reduction;
    info.magFilter = info.minFilter = desc.filter;
    info.mipmapMode = desc.mipmap;
    info.addressModeU = info.addressModeV = info.addressModeW = desc.address;
    info.maxLod = VK_LOD_CLAMP_NONE;
    info.anisotropyEnable = desc.maxAnisotropy > 1.0f ? VK_TRUE : VK_FALSE;
    info.maxAnisotropy = std::min(desc.maxAnisotropy, context_.info().limits.maxSamplerAnisotropy);
    info.compareEnable = desc.compare ? VK_TRUE : VK_FALSE;
    info.compareOp = desc.compareOp;
    VkSampler sampler = VK_NULL_HANDLE;
    check(vkCreateSampler(context_.device(), &info, nullptr, &sampler));
    uint32_t i = acquire(gpu::kBindingSamplers);
    {
        std::lock_guard lock(mutex_);
        if (samplers_.size() <= i) samplers_.resize(i + 1, VK_NULL_HANDLE);
        samplers_[i] = sampler;
    }
    writeImage(context_.device(), set_, gpu::kBindingSamplers, i, VK_DESCRIPTOR_TYPE_SAMPLER, VK_NULL_HANDLE,
               VK_IMAGE_LAYOUT_UNDEFINED, sampler);
    return {i};
}

StorageBufferIndex BindlessTable::addBuffer(VkBuffer buffer, VkDeviceSize size, const std::string& name) {
    const uint32_t limit = context_.info().limits.maxStorageBufferRange;
    if (size > limit)
        throw DeviceLimitError("storage buffer '" + name + "' needs " + std::to_string(size) +
                               " bytes, more than the device's maxStorageBufferRange (" + std::to_string(limit) + ")");
    return addBuffer(buffer, 0, VK_WHOLE_SIZE);
}

StorageBufferIndex BindlessTable::addBuffer(VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range) {
    uint32_t i = acquire(gpu::kBindingStorageBuffers);
    VkDescriptorBufferInfo info{buffer, offset, range};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = gpu::kBindingStorageBuffers;
    write.dstArrayElement = i;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &info;
    vkUpdateDescriptorSets(context_.device(), 1, &write, 0, nullptr);
    return {i};
}

void BindlessTable::release(SampledIndex index) { retire(gpu::kBindingSampledImages, index.value); }
void BindlessTable::release(StorageImageIndex index) { retire(gpu::kBindingStorageImages, index.value); }
void BindlessTable::release(StorageBufferIndex index) { retire(gpu::kBindingStorageBuffers, index.value); }
void BindlessTable::release(SamplerIndex index) {
    if (index.value == UINT32_MAX) return;
    VkSampler sampler;
    {
        std::lock_guard lock(mutex_);
        sampler = samplers_[index.value];
        samplers_[index.value] = VK_NULL_HANDLE;
    }
    VkDevice device = context_.device();
    context_.destroyDeferred([device, sampler] { vkDestroySampler(device, sampler, nullptr); });
    retire(gpu::kBindingSamplers, index.value);
}

void BindlessTable::bind(VkCommandBuffer cmd) const {
    VkPipelineLayout layout = context_.pipelineLayout();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set_, 0, nullptr);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set_, 0, nullptr);
}

}  // namespace idk::vk
