// texture_streamer.hpp: asynchronous texture loading. Worker threads decode every texture a material uses
// (scene/texture_decode) and create its image; once per frame the render thread records the copies of what
// finished within a staging budget, registers image and sampler in the bindless table and hands the indices to
// the renderer; no frame waits for a decode. Ports IDKEngine's AsyncTextureLoader / TextureLoading (reference
// 2.9): persistently mapped staging (workers fill it for big textures), copies recorded on the render thread.
#pragma once
#include <volk.h>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "scene/scene.hpp"
#include "scene/texture_decode.hpp"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::vk { class Context; }

namespace idk::render {

struct TextureStreamerOptions {
    // Staging-ring bytes one pump() may upload. A texture larger than this (all mips) gets its own staging
    // buffer, written by the worker, and is uploaded alone in a frame (one such texture per frame).
    VkDeviceSize frameBudget = 16ull << 20;
    uint32_t workerThreads = 0;   // 0: max(1, hardware_concurrency - 1)
    uint32_t maxWaiting = 4;      // decoded images held (decoding or waiting for upload); workers block beyond
};

struct TextureStreamerStats {
    uint32_t textures = 0;           // scene textures streamed (those a material references)
    uint32_t images = 0;             // GPU images: one per (scene image, colour space) the textures need
    uint32_t decoded = 0;            // images the workers finished (placeholders included)
    uint32_t uploaded = 0;           // images whose copies were recorded
    uint32_t readyTextures = 0;      // onReady calls so far
    uint32_t placeholders = 0;       // images replaced by the magenta checker (missing, undecodable, too big)
    uint64_t bytes = 0;              // texel bytes uploaded, all mips
    uint32_t pumps = 0;              // pump() calls
    uint32_t uploadFrames = 0;       // pumps (and synchronous batches) that uploaded something
    uint32_t dedicatedStagings = 0;  // uploads through their own staging buffer instead of the ring
};

class TextureStreamer {
public:
    // Called on the thread that runs pump() / finishSynchronously(), exactly once per streamed texture, in the
    // frame whose command buffer made it ready: the renderer repoints the texture's material slots (which use a
    // placeholder until then). The sampled index views the image as sRGB for colour textures (base colour,
    // emissive) and UNORM for data; the sampler follows the texture's glTF sampler (equal ones shared).
    using ReadyCallback = std::function<void(uint32_t textureIndex, vk::SampledIndex, vk::SamplerIndex)>;

    // Starts decoding at once. `scene` must outlive the streamer (workers read Scene::images). Textures no
    // material references are not loaded. A texture used both as colour and as data is loaded once as sRGB
    // (one warning). Failed images become the decoder's placeholder with one warning per image (none again
    // for images the loader already reported).
    TextureStreamer(vk::Context& ctx, const scene::Scene& scene, ReadyCallback onReady,
                    const TextureStreamerOptions& options = {});
    ~TextureStreamer();  // stops and joins the workers; GPU objects are released deferred (after submitted work)
    TextureStreamer(const TextureStreamer&) = delete;
    TextureStreamer& operator=(const TextureStreamer&) = delete;

    // Once per frame, on the render thread, inside the frame's command buffer BEFORE the render graph records:
    // uploads what finished decoding (never waits for a decode or for the GPU) and calls onReady for each
    // texture it made ready. The command buffer must be submitted before the next pump() or the destructor
    // (staging space is recycled on the timeline value of that submission). Rethrows a worker's Vulkan error.
    void pump(VkCommandBuffer cmd);
    // Waits for every decode and uploads the rest with immediate submissions (for `idk render`, which wants the
    // final image); calls onReady for each. Afterwards allReady() is true.
    void finishSynchronously();

    bool allReady() const;
    bool isReady(uint32_t textureIndex) const;
    // The image a ready texture samples (tests read its mips back); nullptr before ready or when not streamed.
    const vk::Image* image(uint32_t textureIndex) const;
    // How texture i is loaded (Unused: not streamed; Both: loaded as sRGB).
    const std::vector<scene::TextureColorSpace>& colorSpaces() const noexcept { return spaces_; }
    TextureStreamerStats stats() const;
    std::vector<std::string> warnings() const;  // the warnings this streamer logged

private:
    struct Job {
        std::optional<uint32_t> image;  // Scene::images index; empty: the texture has no source
        bool srgb = false;
        std::string label;
        std::vector<uint32_t> textures;
        vk::Image gpuImage;  // owned once uploaded
        vk::SampledIndex sampled;
        bool ready = false;
    };
    struct Prepared {  // a worker's result, waiting for upload
        uint32_t job = 0;
        scene::DecodedTexture texture;  // texels emptied when `staging` holds them
        vk::Image image;
        vk::Buffer staging;  // dedicated staging buffer (texture larger than the frame budget)
        std::exception_ptr error;
    };
    struct Segment {
        uint64_t freeAfter = 0;  // timeline value after which the GPU no longer reads it
    };

    void workerLoop();
    Prepared prepare(uint32_t job);
    void retireLastPump();
    bool acquireSegment();
    void recordUploads(VkCommandBuffer cmd, std::vector<Prepared>& uploads, const std::vector<VkDeviceSize>& offsets,
                       const std::vector<VkBuffer>& sources);
    void finishUploads(std::vector<Prepared>& uploads);
    void discard(Prepared& p);

    vk::Context& ctx_;
    const scene::Scene& scene_;
    ReadyCallback onReady_;
    TextureStreamerOptions options_;
    std::vector<scene::TextureColorSpace> spaces_;
    std::vector<Job> jobs_;
    std::vector<uint32_t> jobOfTexture_;  // UINT32_MAX: not streamed
    std::vector<vk::SamplerIndex> samplerOfTexture_;
    std::vector<vk::SamplerIndex> samplers_;  // unique, owned
    std::vector<bool> warnedImages_;
    uint32_t streamedTextures_ = 0;

    // Shared with the workers (mutex_).
    mutable std::mutex mutex_;
    std::condition_variable workCv_;   // workers: a slot freed or stop
    std::condition_variable readyCv_;  // finishSynchronously: a result arrived
    uint32_t nextJob_ = 0;
    uint32_t waiting_ = 0;  // results held (decoding or queued)
    bool stop_ = false;
    std::deque<Prepared> ready_;
    TextureStreamerStats stats_;
    std::vector<std::string> warnings_;
    std::vector<std::thread> workers_;

    // Render thread only.
    vk::Buffer ring_;  // kRingSegments * frameBudget, persistently mapped, created on first use
    std::vector<Segment> segments_;
    uint32_t nextSegment_ = 0;
    int lastPumpSegment_ = -1;
    int currentSegment_ = -1;
    std::vector<vk::Buffer> lastPumpStagings_;  // dedicated buffers of the last pump, released after its submit
};

}  // namespace idk::render
