// vk_graph_backend.cpp: Vulkan objects for the render graph.
#include "render/vk_graph_backend.hpp"

#include <optional>

#include "vk/bindless.hpp"
#include "vk/check.hpp"

namespace idk::render {

graph::PhysicalTexture physicalOf(const vk::Image& image) {
    graph::PhysicalTexture p;
    p.image = image.image;
    p.view = image.view;
    p.format = image.format;
    p.extent = image.extent;
    p.mips = image.mipLevels;
    p.layers = image.layers;
    return p;
}

namespace {

vk::ImageDesc imageDesc(const graph::TextureInfo& info) {
    vk::ImageDesc d;
    d.type = info.type;
    d.format = info.format;
    d.extent = info.extent;
    d.mipLevels = info.mips;
    d.layers = info.layers;
    d.cube = info.cube;
    d.usage = info.usage;
    return d;
}

VkBufferCreateInfo bufferInfo(const graph::BufferInfo& info) {
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = info.size;
    ci.usage = info.usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    return ci;
}

}  // namespace

VkGraphBackend::VkGraphBackend(vk::Context& ctx) : ctx_(ctx), timestamps_(ctx) {}

VkGraphBackend::~VkGraphBackend() {
    // The pool releases every object before its backend goes away; free what is left defensively.
    ctx_.waitIdle();
    for (auto& [id, a] : dedicated_) ctx_.allocator().free(a);
    for (auto& [id, a] : heaps_) ctx_.allocator().free(a);
}

graph::MemoryRequirements VkGraphBackend::textureRequirements(const graph::TextureInfo& info) {
    VkImageCreateInfo ci = vk::imageCreateInfo(imageDesc(info));
    VkDeviceImageMemoryRequirements query{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
    query.pCreateInfo = &ci;
    VkMemoryRequirements2 req{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    vkGetDeviceImageMemoryRequirements(ctx_.device(), &query, &req);
    return {req.memoryRequirements.size, req.memoryRequirements.alignment, req.memoryRequirements.memoryTypeBits};
}

graph::MemoryRequirements VkGraphBackend::bufferRequirements(const graph::BufferInfo& info) {
    VkBufferCreateInfo ci = bufferInfo(info);
    VkDeviceBufferMemoryRequirements query{VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS};
    query.pCreateInfo = &ci;
    VkMemoryRequirements2 req{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    vkGetDeviceBufferMemoryRequirements(ctx_.device(), &query, &req);
    return {req.memoryRequirements.size, req.memoryRequirements.alignment, req.memoryRequirements.memoryTypeBits};
}

graph::HeapHandle VkGraphBackend::allocateHeap(const graph::HeapDesc& desc) {
    VkMemoryRequirements req{desc.size, desc.alignment, desc.memoryTypeBits};
    auto usage = desc.hostVisible ? vk::MemoryUsage::Readback : vk::MemoryUsage::GpuOnly;
    auto tiling = desc.kind == graph::ResourceKind::Image ? vk::ResourceTiling::Optimal : vk::ResourceTiling::Linear;
    uint64_t id = nextId_++;
    heaps_[id] = ctx_.allocator().allocate(req, usage, tiling, "render graph transients", true);
    return {id};
}

graph::PhysicalTexture VkGraphBackend::createTexture(const graph::TextureInfo& info, std::string_view debugName,
                                                     const graph::MemoryPlacement* placement) {
    VkImageCreateInfo ci = vk::imageCreateInfo(imageDesc(info));
    graph::PhysicalTexture t;
    vk::check(vkCreateImage(ctx_.device(), &ci, nullptr, &t.image));
    t.backendData = nextId_++;
    if (placement) {
        const vk::MemoryAllocation& heap = heaps_.at(placement->heap.value);
        vk::check(vkBindImageMemory(ctx_.device(), t.image, heap.memory, heap.offset + placement->offset));
    } else {
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(ctx_.device(), t.image, &req);
        vk::MemoryAllocation a = ctx_.allocator().allocate(req, vk::MemoryUsage::GpuOnly, vk::ResourceTiling::Optimal,
                                                           "render targets");
        vk::check(vkBindImageMemory(ctx_.device(), t.image, a.memory, a.offset));
        dedicated_[t.backendData] = a;
    }
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = t.image;
    view.viewType = vk::viewTypeOf(imageDesc(info));
    view.format = info.format;
    view.subresourceRange = {vk::aspectOf(info.format), 0, info.mips, 0, info.layers};
    vk::check(vkCreateImageView(ctx_.device(), &view, nullptr, &t.view));
    std::string name(debugName);
    ctx_.setName(t.image, VK_OBJECT_TYPE_IMAGE, name);
    ctx_.setName(t.view, VK_OBJECT_TYPE_IMAGE_VIEW, name);
    t.format = info.format;
    t.extent = info.extent;
    t.mips = info.mips;
    t.layers = info.layers;
    if (info.usage & VK_IMAGE_USAGE_SAMPLED_BIT) t.sampledIndex = ctx_.bindless().addSampled(t.view).value;
    if (info.usage & VK_IMAGE_USAGE_STORAGE_BIT) t.storageIndex = ctx_.bindless().addStorage(t.view).value;
    return t;
}

graph::PhysicalBuffer VkGraphBackend::createBuffer(const graph::BufferInfo& info, std::string_view debugName,
                                                   const graph::MemoryPlacement* placement) {
    VkBufferCreateInfo ci = bufferInfo(info);
    graph::PhysicalBuffer b;
    vk::check(vkCreateBuffer(ctx_.device(), &ci, nullptr, &b.buffer));
    b.backendData = nextId_++;
    b.size = info.size;
    if (placement) {
        const vk::MemoryAllocation& heap = heaps_.at(placement->heap.value);
        vk::check(vkBindBufferMemory(ctx_.device(), b.buffer, heap.memory, heap.offset + placement->offset));
    } else {
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(ctx_.device(), b.buffer, &req);
        auto usage = info.hostVisible ? vk::MemoryUsage::Readback : vk::MemoryUsage::GpuOnly;
        vk::MemoryAllocation a =
            ctx_.allocator().allocate(req, usage, vk::ResourceTiling::Linear, "render graph buffers");
        vk::check(vkBindBufferMemory(ctx_.device(), b.buffer, a.memory, a.offset));
        dedicated_[b.backendData] = a;
    }
    VkBufferDeviceAddressInfo address{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    address.buffer = b.buffer;
    b.address = vkGetBufferDeviceAddress(ctx_.device(), &address);
    ctx_.setName(b.buffer, VK_OBJECT_TYPE_BUFFER, std::string(debugName));
    if (info.usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) b.storageIndex = ctx_.bindless().addBuffer(b.buffer, info.size, std::string(debugName)).value;
    return b;
}

std::optional<vk::MemoryAllocation> VkGraphBackend::takeDedicated(uint64_t backendData) {
    auto it = dedicated_.find(backendData);
    if (it == dedicated_.end()) return std::nullopt;  // placed in an aliasing heap
    vk::MemoryAllocation a = it->second;
    dedicated_.erase(it);
    return a;
}

void VkGraphBackend::destroyTexture(const graph::PhysicalTexture& t) {
    if (t.sampledIndex != graph::kNoBindlessIndex) ctx_.bindless().release(vk::SampledIndex{t.sampledIndex});
    if (t.storageIndex != graph::kNoBindlessIndex) ctx_.bindless().release(vk::StorageImageIndex{t.storageIndex});
    std::optional<vk::MemoryAllocation> memory = takeDedicated(t.backendData);
    VkDevice device = ctx_.device();
    vk::MemoryAllocator* allocator = &ctx_.allocator();
    ctx_.destroyDeferred([device, allocator, t, memory] {
        vkDestroyImageView(device, t.view, nullptr);
        vkDestroyImage(device, t.image, nullptr);
        if (memory) allocator->free(*memory);
    });
}

void VkGraphBackend::destroyBuffer(const graph::PhysicalBuffer& b) {
    if (b.storageIndex != graph::kNoBindlessIndex) ctx_.bindless().release(vk::StorageBufferIndex{b.storageIndex});
    std::optional<vk::MemoryAllocation> memory = takeDedicated(b.backendData);
    VkDevice device = ctx_.device();
    vk::MemoryAllocator* allocator = &ctx_.allocator();
    ctx_.destroyDeferred([device, allocator, b, memory] {
        vkDestroyBuffer(device, b.buffer, nullptr);
        if (memory) allocator->free(*memory);
    });
}

void VkGraphBackend::releaseHeap(graph::HeapHandle heap) {
    auto it = heaps_.find(heap.value);
    if (it == heaps_.end()) return;
    vk::MemoryAllocation a = it->second;
    heaps_.erase(it);
    vk::MemoryAllocator* allocator = &ctx_.allocator();
    // Deferred after the objects placed in it (the deferred queue runs in order).
    ctx_.destroyDeferred([allocator, a] { allocator->free(a); });
}

void VkGraphBackend::beginFrame(VkCommandBuffer cmd, uint32_t passCount) {
    timestamps_.reset(cmd);
    scopes_.assign(passCount, 0);
}

void VkGraphBackend::timestampBegin(VkCommandBuffer cmd, uint32_t passIndex, std::string_view passName) {
    if (passIndex >= scopes_.size()) scopes_.resize(passIndex + 1);
    scopes_[passIndex] = timestamps_.begin(cmd, std::string(passName));
}

void VkGraphBackend::timestampEnd(VkCommandBuffer cmd, uint32_t passIndex) {
    timestamps_.end(cmd, scopes_.at(passIndex));
}

}  // namespace idk::render
