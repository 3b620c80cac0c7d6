// texture_streamer.cpp: the worker pool (decode + image creation + dedicated staging for big textures), the
// per-frame upload (staging ring in kRingSegments slices recycled on the context's timeline, sync2 barriers,
// buffer -> image copies of every mip) and the synchronous finish. Port of IDKEngine's AsyncTextureLoader.
#include "render/texture_streamer.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <tuple>

#include "core/log.hpp"
#include "render/gpu_scene.hpp"
#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::render {
namespace {

constexpr uint32_t kRingSegments = 3;        // frames in flight (2) + the one being recorded
constexpr VkDeviceSize kStagingAlign = 16;   // >= texel size 4 and a common optimalBufferCopyOffsetAlignment

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

void flushIfNeeded(vk::Context& ctx, const vk::Buffer& buffer) {
    if (buffer.allocation.hostCoherent) return;
    const VkDeviceSize atom = ctx.info().limits.nonCoherentAtomSize;
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = buffer.allocation.memory;
    range.offset = buffer.allocation.offset / atom * atom;
    range.size = VK_WHOLE_SIZE;
    vk::check(vkFlushMappedMemoryRanges(ctx.device(), 1, &range));
}

vk::Buffer makeStaging(vk::Context& ctx, VkDeviceSize size, const std::string& name) {
    vk::BufferDesc desc;
    desc.size = size;
    desc.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    desc.memory = vk::MemoryUsage::Upload;
    desc.name = name;
    desc.category = "staging";
    return ctx.createBuffer(desc);
}

VkImageMemoryBarrier2 imageBarrier(const vk::Image& image, VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
    return b;
}

bool sameSampler(const vk::SamplerDesc& a, const vk::SamplerDesc& b) {
    return std::tie(a.filter, a.mipmap, a.address, a.maxAnisotropy, a.reduction) ==
           std::tie(b.filter, b.mipmap, b.address, b.maxAnisotropy, b.reduction);
}

}  // namespace

TextureStreamer::TextureStreamer(vk::Context& ctx, const scene::Scene& scene, ReadyCallback onReady,
                                 const TextureStreamerOptions& options)
    : ctx_(ctx), scene_(scene), onReady_(std::move(onReady)), options_(options), segments_(kRingSegments) {
    spaces_ = scene::textureColorSpaces(scene);
    jobOfTexture_.assign(scene.textures.size(), UINT32_MAX);
    samplerOfTexture_.resize(scene.textures.size());
    warnedImages_.assign(scene.images.size(), false);

    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(ctx.physicalDevice(), &features);  // the context enables what is supported
    std::vector<vk::SamplerDesc> uniqueDescs;
    std::map<std::pair<uint32_t, bool>, uint32_t> jobByKey;  // (image or UINT32_MAX, srgb) -> job
    for (uint32_t t = 0; t < scene.textures.size(); ++t) {
        const scene::TextureColorSpace space = spaces_[t];
        if (space == scene::TextureColorSpace::Unused) continue;
        if (space == scene::TextureColorSpace::Both) {
            warnings_.push_back(core::concat(scene.sourcePath.string(), ": texture ", t,
                                             " is used both as colour and as data; it is loaded once, as sRGB"));
            core::logWarning(warnings_.back());
        }
        const scene::Texture& texture = scene.textures[t];
        const bool srgb = space != scene::TextureColorSpace::Linear;
        std::optional<uint32_t> image = texture.image;
        if (image && *image >= scene.images.size()) image.reset();
        const auto key = std::make_pair(image.value_or(UINT32_MAX), srgb);
        auto [it, inserted] = jobByKey.try_emplace(key, uint32_t(jobs_.size()));
        if (inserted) {
            Job job;
            job.image = image;
            job.srgb = srgb;
            job.label = image ? scene::imageLabel(scene, *image)
                              : "texture " + std::to_string(t) + " of " + scene.sourcePath.filename().string();
            jobs_.push_back(std::move(job));
        }
        jobs_[it->second].textures.push_back(t);
        jobOfTexture_[t] = it->second;
        ++streamedTextures_;

        vk::SamplerDesc desc = samplerDesc(texture.sampler);
        if (!features.samplerAnisotropy) desc.maxAnisotropy = 1.0f;
        auto same = std::find_if(uniqueDescs.begin(), uniqueDescs.end(),
                                 [&](const vk::SamplerDesc& d) { return sameSampler(d, desc); });
        if (same == uniqueDescs.end()) {
            uniqueDescs.push_back(desc);
            samplers_.push_back(ctx.bindless().addSampler(desc));
            same = uniqueDescs.end() - 1;
        }
        samplerOfTexture_[t] = samplers_[size_t(same - uniqueDescs.begin())];
    }
    stats_.textures = streamedTextures_;
    stats_.images = uint32_t(jobs_.size());
    if (options_.maxWaiting == 0) options_.maxWaiting = 1;

    uint32_t threads = options_.workerThreads;
    if (threads == 0) threads = std::max(2u, std::thread::hardware_concurrency()) - 1;
    threads = std::min(threads, uint32_t(jobs_.size()));  // nothing to decode: no threads
    for (uint32_t i = 0; i < threads; ++i) workers_.emplace_back([this] { workerLoop(); });
}

TextureStreamer::~TextureStreamer() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    workCv_.notify_all();
    for (std::thread& w : workers_) w.join();
    // Results never uploaded were never referenced by a command buffer.
    for (Prepared& p : ready_) discard(p);
    ready_.clear();
    // Everything else may be read by submitted frames: release after they complete.
    for (vk::Buffer& b : lastPumpStagings_) ctx_.destroyDeferred(b);
    for (Job& job : jobs_) {
        if (job.sampled.value != UINT32_MAX) ctx_.bindless().release(job.sampled);
        ctx_.destroyDeferred(job.gpuImage);
    }
    for (vk::SamplerIndex s : samplers_) ctx_.bindless().release(s);
    ctx_.destroyDeferred(ring_);
}

void TextureStreamer::discard(Prepared& p) {
    ctx_.destroy(p.image);
    ctx_.destroy(p.staging);
}

void TextureStreamer::workerLoop() {
    for (;;) {
        uint32_t job = 0;
        {
            std::unique_lock lock(mutex_);
            // Bounded queue: at most maxWaiting decoded images exist (decoding or waiting for upload).
            workCv_.wait(lock, [&] { return stop_ || nextJob_ >= jobs_.size() || waiting_ < options_.maxWaiting; });
            if (stop_ || nextJob_ >= jobs_.size()) return;
            job = nextJob_++;
            ++waiting_;
        }
        Prepared p = prepare(job);
        {
            std::lock_guard lock(mutex_);
            ++stats_.decoded;
            ready_.push_back(std::move(p));
        }
        readyCv_.notify_all();
    }
}

TextureStreamer::Prepared TextureStreamer::prepare(uint32_t jobIndex) {
    Prepared p;
    p.job = jobIndex;
    const Job& job = jobs_[jobIndex];  // immutable fields only (label, image, srgb)
    try {
        // The device's image size limit is checked against the declared size, before anything is decoded.
        scene::ImageLimits limits;
        if (ctx_.info().limits.maxImageDimension2D < limits.maxDimension) {
            limits.maxDimension = ctx_.info().limits.maxImageDimension2D;
            limits.dimensionLimit = "texel device limit (maxImageDimension2D)";
        }
        p.texture = job.image ? scene::decodeImage(scene_.images[*job.image], job.srgb, job.label, limits)
                              : scene::decodeImage(scene::Image{}, job.srgb, job.label, limits);
        vk::ImageDesc desc;
        desc.format = job.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
        desc.extent = {p.texture.width, p.texture.height, 1};
        desc.mipLevels = uint32_t(p.texture.mips.size());
        desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
        desc.name = "texture: " + job.label;
        desc.category = "textures";
        p.image = ctx_.createImage(desc);
        // Too big for the frame budget: like IDKEngine, the worker writes the texels into a persistently mapped
        // staging buffer, so the render thread only records the copy.
        if (p.texture.byteSize() > options_.frameBudget) {
            p.staging = makeStaging(ctx_, p.texture.byteSize(), "texture staging: " + job.label);
            std::memcpy(p.staging.mapped(), p.texture.texels.data(), p.texture.byteSize());
            flushIfNeeded(ctx_, p.staging);
            p.texture.texels = {};
        }
    } catch (...) {
        p.error = std::current_exception();
    }
    return p;
}

void TextureStreamer::retireLastPump() {
    // The previous pump's command buffer has been submitted by now, so lastSubmittedValue() covers it.
    for (vk::Buffer& b : lastPumpStagings_) ctx_.destroyDeferred(b);
    lastPumpStagings_.clear();
    if (lastPumpSegment_ >= 0) segments_[size_t(lastPumpSegment_)].freeAfter = ctx_.lastSubmittedValue();
    lastPumpSegment_ = -1;
}

bool TextureStreamer::acquireSegment() {
    if (currentSegment_ >= 0) return true;
    if (segments_[nextSegment_].freeAfter > ctx_.completedValue()) return false;  // still read: skip, never wait
    if (!ring_) {
        ring_ = makeStaging(ctx_, options_.frameBudget * kRingSegments, "texture staging ring");
    }
    currentSegment_ = int(nextSegment_);
    nextSegment_ = (nextSegment_ + 1) % kRingSegments;
    return true;
}

void TextureStreamer::pump(VkCommandBuffer cmd) {
    retireLastPump();
    std::vector<Prepared> uploads;
    std::vector<VkDeviceSize> offsets;
    std::vector<VkBuffer> sources;
    std::exception_ptr error;
    VkDeviceSize used = 0;
    {
        std::lock_guard lock(mutex_);
        ++stats_.pumps;
        while (!ready_.empty()) {
            Prepared& p = ready_.front();
            if (p.error) {
                error = p.error;
                discard(p);
                ready_.pop_front();
                --waiting_;
                break;
            }
            if (p.staging) {  // a texture above the budget goes alone
                if (!uploads.empty()) break;
                offsets.push_back(0);
                sources.push_back(p.staging.buffer);
            } else {
                const VkDeviceSize size = alignUp(p.texture.byteSize(), kStagingAlign);
                if (used + size > options_.frameBudget || !acquireSegment()) break;
                offsets.push_back(VkDeviceSize(currentSegment_) * options_.frameBudget + used);
                sources.push_back(ring_.buffer);
                used += size;
            }
            uploads.push_back(std::move(p));
            ready_.pop_front();
            --waiting_;
            if (uploads.back().staging) break;
        }
    }
    if (!uploads.empty() || error) workCv_.notify_all();
    if (currentSegment_ >= 0) {
        for (size_t i = 0; i < uploads.size(); ++i)
            if (!uploads[i].staging)
                std::memcpy(static_cast<uint8_t*>(ring_.mapped()) + offsets[i], uploads[i].texture.texels.data(),
                            uploads[i].texture.byteSize());
        flushIfNeeded(ctx_, ring_);
        lastPumpSegment_ = currentSegment_;
        currentSegment_ = -1;
    }
    if (!uploads.empty()) {
        recordUploads(cmd, uploads, offsets, sources);
        for (Prepared& p : uploads)
            if (p.staging) lastPumpStagings_.push_back(p.staging);
        finishUploads(uploads);
    }
    if (error) std::rethrow_exception(error);
}

// This upload runs outside the render graph, and that is sound: the image is not a graph resource and no
// pass can name it until onReady hands out its bindless index (after these commands are recorded). The graph
// records after pump() in the same command buffer, so the barrier below (copy -> any shader stage, layout
// SHADER_READ_ONLY_OPTIMAL, where the image then stays for good) orders these copies before every later read.
// Host writes to the staging memory need no barrier: vkQueueSubmit makes them visible to the device.
void TextureStreamer::recordUploads(VkCommandBuffer cmd, std::vector<Prepared>& uploads,
                                    const std::vector<VkDeviceSize>& offsets, const std::vector<VkBuffer>& sources) {
    std::vector<VkImageMemoryBarrier2> barriers;
    for (const Prepared& p : uploads) {
        VkImageMemoryBarrier2 b = imageBarrier(p.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        b.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
        b.srcAccessMask = VK_ACCESS_2_NONE;
        b.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        b.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        barriers.push_back(b);
    }
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = uint32_t(barriers.size());
    dep.pImageMemoryBarriers = barriers.data();
    vkCmdPipelineBarrier2(cmd, &dep);

    std::vector<VkBufferImageCopy> regions;
    for (size_t i = 0; i < uploads.size(); ++i) {
        const scene::DecodedTexture& t = uploads[i].texture;
        regions.clear();
        for (uint32_t level = 0; level < t.mips.size(); ++level) {
            VkBufferImageCopy r{};
            r.bufferOffset = offsets[i] + t.mips[level].offset;
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
            r.imageExtent = {t.mips[level].width, t.mips[level].height, 1};
            regions.push_back(r);
        }
        vkCmdCopyBufferToImage(cmd, sources[i], uploads[i].image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
    }

    barriers.clear();
    for (const Prepared& p : uploads) {
        VkImageMemoryBarrier2 b =
            imageBarrier(p.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        b.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;  // any shader of any later pass may sample it
        b.dstAccessMask = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
        barriers.push_back(b);
    }
    dep.imageMemoryBarrierCount = uint32_t(barriers.size());
    dep.pImageMemoryBarriers = barriers.data();
    vkCmdPipelineBarrier2(cmd, &dep);
}

// Registers uploaded images, reports their warnings once per image, calls onReady.
void TextureStreamer::finishUploads(std::vector<Prepared>& uploads) {
    std::vector<std::pair<uint32_t, uint32_t>> readyCalls;  // (texture, job)
    {
        std::lock_guard lock(mutex_);
        ++stats_.uploadFrames;
        for (Prepared& p : uploads) {
            Job& job = jobs_[p.job];
            job.gpuImage = p.image;
            job.sampled = ctx_.bindless().addSampled(job.gpuImage.view);
            job.ready = true;
            ++stats_.uploaded;
            stats_.bytes += p.staging ? p.staging.size : p.texture.byteSize();
            stats_.dedicatedStagings += p.staging ? 1 : 0;
            if (p.texture.placeholder) {
                ++stats_.placeholders;
                const bool first = !job.image || !warnedImages_[*job.image];
                if (job.image) warnedImages_[*job.image] = true;
                if (first && !p.texture.reportedByLoader) {
                    core::logWarning(p.texture.warning);
                    warnings_.push_back(p.texture.warning);
                }
            }
            for (uint32_t t : job.textures) readyCalls.emplace_back(t, p.job);
            stats_.readyTextures += uint32_t(job.textures.size());
        }
    }
    for (Prepared& p : uploads) p.staging = {};  // ownership moved to lastPumpStagings_ or freed by the caller
    for (auto [t, j] : readyCalls)
        if (onReady_) onReady_(t, jobs_[j].sampled, samplerOfTexture_[t]);
}

void TextureStreamer::finishSynchronously() {
    retireLastPump();
    for (;;) {
        Prepared p;
        {
            std::unique_lock lock(mutex_);
            readyCv_.wait(lock, [&] { return !ready_.empty() || stats_.decoded == jobs_.size(); });
            if (ready_.empty()) break;
            p = std::move(ready_.front());
            ready_.pop_front();
            --waiting_;
        }
        workCv_.notify_all();
        if (p.error) {
            discard(p);
            std::rethrow_exception(p.error);
        }
        if (!p.staging) {
            p.staging = makeStaging(ctx_, p.texture.byteSize(), "texture staging (synchronous)");
            std::memcpy(p.staging.mapped(), p.texture.texels.data(), p.texture.byteSize());
            flushIfNeeded(ctx_, p.staging);
        }
        vk::Buffer staging = p.staging;
        std::vector<Prepared> one;
        one.push_back(std::move(p));
        const std::vector<VkDeviceSize> offsets{0};
        const std::vector<VkBuffer> sources{staging.buffer};
        ctx_.runImmediate([&](VkCommandBuffer cmd) { recordUploads(cmd, one, offsets, sources); });
        ctx_.destroy(staging);  // runImmediate waited for the copy
        finishUploads(one);
    }
}

bool TextureStreamer::allReady() const {
    std::lock_guard lock(mutex_);
    return stats_.readyTextures == streamedTextures_;
}

bool TextureStreamer::isReady(uint32_t textureIndex) const {
    std::lock_guard lock(mutex_);
    return textureIndex < jobOfTexture_.size() && jobOfTexture_[textureIndex] != UINT32_MAX &&
           jobs_[jobOfTexture_[textureIndex]].ready;
}

const vk::Image* TextureStreamer::image(uint32_t textureIndex) const {
    std::lock_guard lock(mutex_);
    if (textureIndex >= jobOfTexture_.size() || jobOfTexture_[textureIndex] == UINT32_MAX) return nullptr;
    const Job& job = jobs_[jobOfTexture_[textureIndex]];
    return job.ready ? &job.gpuImage : nullptr;
}

TextureStreamerStats TextureStreamer::stats() const {
    std::lock_guard lock(mutex_);
    return stats_;
}

std::vector<std::string> TextureStreamer::warnings() const {
    std::lock_guard lock(mutex_);
    return warnings_;
}

}  // namespace idk::render
