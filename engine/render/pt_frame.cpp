// pt_frame.cpp: the path tracer's per-resolution buffers and images, and their import into render graphs.
#include "render/pt_frame.hpp"

#include "render/compute_primitives.hpp"
#include "render/vk_graph_backend.hpp"
#include "shared/pt_wavefront.h"
#include "vk/context.hpp"

namespace idk::render {
namespace {

constexpr const char* kCategory = "path tracer";

vk::Buffer makeBuffer(vk::Context& ctx, VkDeviceSize bytes, const std::string& name, VkBufferUsageFlags extra = 0) {
    vk::BufferDesc desc;
    desc.size = std::max<VkDeviceSize>(bytes, 16);
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | extra;
    desc.name = name;
    desc.category = kCategory;
    return ctx.createBuffer(desc);
}

vk::Image makeImage(vk::Context& ctx, VkFormat format, uint32_t w, uint32_t h, const std::string& name) {
    vk::ImageDesc desc;
    desc.format = format;
    desc.extent = {w, h, 1};
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = name;
    desc.category = kCategory;
    return ctx.createImage(desc);
}

}  // namespace

PtFrameResources createPtFrame(vk::Context& ctx, uint32_t width, uint32_t height, bool sorting) {
    PtFrameResources f;
    f.width = width;
    f.height = height;
    const VkDeviceSize pixels = VkDeviceSize(width) * height;
    f.paths = makeBuffer(ctx, pixels * sizeof(gpu::GpuPtPath), "pt paths");
    f.hits = makeBuffer(ctx, pixels * sizeof(gpu::GpuPtHit), "pt hits");
    f.shadowRays = makeBuffer(ctx, pixels * sizeof(gpu::GpuPtShadowRay), "pt shadow rays");
    f.guides = makeBuffer(ctx, pixels * sizeof(gpu::GpuPtGuide), "pt guides");
    const VkDeviceSize queueBytes = (pixels + gpu::kPtQueueHeaderWords) * sizeof(uint32_t);
    for (int i = 0; i < 2; ++i) {
        const std::string n = std::to_string(i);
        f.queue[i] = makeBuffer(ctx, queueBytes, "pt ray queue " + n);
        f.args[i] = makeBuffer(ctx, 3 * sizeof(uint32_t), "pt ray args " + n, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
        f.shadow[i] = makeBuffer(ctx, queueBytes, "pt shadow queue " + n);
        f.shadowArgs[i] = makeBuffer(ctx, 3 * sizeof(uint32_t), "pt shadow args " + n, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    }
    f.accumColor = makeBuffer(ctx, pixels * 16, "pt accum color");
    f.accumAlbedo = makeBuffer(ctx, pixels * 16, "pt accum albedo");
    f.accumNormal = makeBuffer(ctx, pixels * 16, "pt accum normal");
    f.accumDepth = makeBuffer(ctx, pixels * 4, "pt accum depth");
    f.accumMoment = makeBuffer(ctx, pixels * 4, "pt accum moment");
    f.colorImage = makeImage(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, width, height, "pt color");
    f.albedoImage = makeImage(ctx, VK_FORMAT_R16G16B16A16_SFLOAT, width, height, "pt albedo");
    f.normalImage = makeImage(ctx, VK_FORMAT_R16G16B16A16_SFLOAT, width, height, "pt normal");
    f.depthImage = makeImage(ctx, VK_FORMAT_R32_SFLOAT, width, height, "pt depth");
    f.varianceImage = makeImage(ctx, VK_FORMAT_R32_SFLOAT, width, height, "pt variance");
    f.denoisedImage = makeImage(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, width, height, "pt denoised");
    vk::BindlessTable& bindless = ctx.bindless();
    f.colorStorage = bindless.addStorage(f.colorImage.view);
    f.albedoStorage = bindless.addStorage(f.albedoImage.view);
    f.normalStorage = bindless.addStorage(f.normalImage.view);
    f.depthStorage = bindless.addStorage(f.depthImage.view);
    f.varianceStorage = bindless.addStorage(f.varianceImage.view);
    f.queueIndex[0] = bindless.addBuffer(f.queue[0].buffer, f.queue[0].size, f.queue[0].name);
    f.queueIndex[1] = bindless.addBuffer(f.queue[1].buffer, f.queue[1].size, f.queue[1].name);
    if (sorting) {
        f.keys = makeBuffer(ctx, pixels * sizeof(uint32_t), "pt sort keys");
        f.sortScratch = makeBuffer(ctx, VkDeviceSize(radixSortScratchElements(uint32_t(pixels), true)) * 4, "pt sort scratch");
        f.keysIndex = bindless.addBuffer(f.keys.buffer, f.keys.size, f.keys.name);
        f.scratchIndex = bindless.addBuffer(f.sortScratch.buffer, f.sortScratch.size, f.sortScratch.name);
    }
    return f;
}

void destroyPtFrame(vk::Context& ctx, PtFrameResources& f) {
    vk::BindlessTable& bindless = ctx.bindless();
    for (vk::StorageImageIndex i : {f.colorStorage, f.albedoStorage, f.normalStorage, f.depthStorage, f.varianceStorage})
        if (i.value != UINT32_MAX) bindless.release(i);
    for (vk::StorageBufferIndex i : {f.queueIndex[0], f.queueIndex[1], f.keysIndex, f.scratchIndex})
        if (i.value != UINT32_MAX) bindless.release(i);
    for (vk::Buffer* b : {&f.paths, &f.hits, &f.shadowRays, &f.guides, &f.keys, &f.sortScratch, &f.queue[0], &f.queue[1],
                          &f.args[0], &f.args[1], &f.shadow[0], &f.shadow[1], &f.shadowArgs[0], &f.shadowArgs[1],
                          &f.accumColor, &f.accumAlbedo, &f.accumNormal, &f.accumDepth, &f.accumMoment})
        if (b->buffer) ctx.destroyDeferred(*b);
    for (vk::Image* i : {&f.colorImage, &f.albedoImage, &f.normalImage, &f.depthImage, &f.varianceImage, &f.denoisedImage})
        if (i->image) ctx.destroyDeferred(*i);
    f = {};
}

graph::BufferHandle& PtGraphResources::buffer(const vk::Buffer& b) {
    auto it = buffers_.find(&b);
    if (it != buffers_.end()) return it->second;
    graph::PhysicalBuffer p;
    p.buffer = b.buffer;
    p.size = b.size;
    p.address = b.address;
    auto state = states_.find(&b);
    graph::BufferHandle h = graph_.importBuffer(std::string("pt buffer ") + std::to_string(buffers_.size()), p,
                                                state == states_.end() ? graph::ResourceState{} : state->second);
    return buffers_[&b] = h;
}

graph::TextureHandle& PtGraphResources::image(const vk::Image& i, uint32_t storageIndex) {
    auto it = images_.find(&i);
    if (it != images_.end()) return it->second;
    graph::PhysicalTexture p = physicalOf(i);
    p.storageIndex = storageIndex;
    auto state = states_.find(&i);
    graph::TextureHandle h = graph_.importTexture(std::string("pt image ") + std::to_string(images_.size()), p,
                                                  state == states_.end() ? graph::ResourceState{} : state->second,
                                                  graph::FinalUse{graph::Access::TransferSrc});
    return images_[&i] = h;
}

void PtGraphResources::saveStates() {
    for (const auto& [key, handle] : buffers_) states_[key] = graph_.finalState(handle);
    for (const auto& [key, handle] : images_) states_[key] = graph_.finalState(handle);
}

}  // namespace idk::render
