// texture_streamer_test.cpp: asynchronous texture streaming on the device. Streams DamagedHelmet and BoxTextured
// while empty frames are pumped and compares every mip read back with the CPU decode, byte for byte; likewise
// through the staging ring only, with a tiny budget (several frames; a frame recorded before all arrived uses
// valid placeholder indices), with forced staging, synchronously, with hostile images and torn down mid-stream.
// Validation must stay clean. The read-back, the frame pump and the oracle of a finished stream are shared with the
// registered check "textures/streaming" (engine/conformance/texture_stream_support.hpp), which streams a scene made
// in memory so that `idk conformance` needs no asset.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <thread>

#include "conformance/texture_stream_support.hpp"
#include "core/log.hpp"
#include "render/texture_streamer.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/texture_decode.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/frames.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

using render::TextureStreamer;
using render::TextureStreamerOptions;

using namespace idk::conformance;  // ReadyLog, readMips and the stream oracle, shared with the registry check

const scene::Scene& sharedSceneFile(const std::string& relative) {
    static std::map<std::string, std::unique_ptr<scene::Scene>> cache;
    auto& s = cache[relative];
    if (!s) s = std::make_unique<scene::Scene>(scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + relative));
    return *s;
}
const scene::Scene& helmet() { return sharedSceneFile("DamagedHelmet/glTF-Binary/DamagedHelmet.glb"); }
const scene::Scene& box() { return sharedSceneFile("BoxTextured/glTF-Binary/BoxTextured.glb"); }

// The CPU decodes of a shared scene, kept for the whole run (decoding DamagedHelmet takes a while).
ReferenceDecodes& decodesOf(const scene::Scene& scene) {
    static std::map<const scene::Scene*, std::unique_ptr<ReferenceDecodes>> decodes;
    auto& d = decodes[&scene];
    if (!d) d = std::make_unique<ReferenceDecodes>(scene);
    return *d;
}
const scene::DecodedTexture& reference(const scene::Scene& scene, uint32_t texture, bool srgb) {
    return decodesOf(scene).get(texture, srgb);
}

// The registry's oracle of a finished stream (texture_stream_support.hpp) as a gtest expectation.
void expectExact(vk::Context& ctx, const scene::Scene& scene, ReferenceDecodes& decodes, const TextureStreamer& streamer,
                 const ReadyLog& log) {
    Verdict v;
    expectStreamedExactly(v, ctx, scene, decodes, streamer, log);
    EXPECT_TRUE(v.passed()) << v.messages() << " (" << v.failures() << " failures)";
}
void expectExact(vk::Context& ctx, const scene::Scene& scene, const TextureStreamer& streamer, const ReadyLog& log) {
    expectExact(ctx, scene, decodesOf(scene), streamer, log);
}

StreamResult pumpFrames(vk::Context& ctx, const std::vector<TextureStreamer*>& streamers, const std::vector<ReadyLog*>& logs) {
    const StreamResult r = pumpUntilReady(ctx, streamers, logs);
    EXPECT_FALSE(r.timedOut) << "textures not ready after 120 s";
    return r;
}

class TextureStreamerTest : public GpuTest {};

TEST_F(TextureStreamerTest, StreamsDamagedHelmetAndBoxTexturedExactly) {
    ReadyLog helmetLog(helmet().textures.size()), boxLog(box().textures.size());
    TextureStreamer helmetStream(ctx(), helmet(), helmetLog.callback());
    TextureStreamer boxStream(ctx(), box(), boxLog.callback());
    EXPECT_FALSE(helmetStream.allReady());
    const StreamResult r = pumpFrames(ctx(), {&helmetStream, &boxStream}, {&helmetLog, &boxLog});
    EXPECT_GT(r.frames, 1u);
    expectExact(ctx(), helmet(), helmetStream, helmetLog);
    expectExact(ctx(), box(), boxStream, boxLog);
    // DamagedHelmet: five 2048^2 textures (above the 16 MiB budget: dedicated staging); one shared glTF sampler.
    const render::TextureStreamerStats s = helmetStream.stats();
    EXPECT_EQ(s.textures, 5u);
    EXPECT_EQ(s.images, 5u);
    EXPECT_EQ(s.uploaded, 5u);
    EXPECT_EQ(s.readyTextures, 5u);
    EXPECT_EQ(s.placeholders, 0u);
    EXPECT_EQ(s.dedicatedStagings, 5u);
    EXPECT_EQ(s.uploadFrames, 5u);  // one texture above the budget per frame
    for (uint32_t t = 1; t < 5; ++t) EXPECT_EQ(helmetLog.samplers[t].value, helmetLog.samplers[0].value);
    const render::TextureStreamerStats b = boxStream.stats();
    EXPECT_EQ(b.dedicatedStagings, 0u);  // 256^2 goes through the ring
    EXPECT_EQ(b.bytes, reference(box(), 0, true).byteSize());
    EXPECT_TRUE(helmetStream.warnings().empty());
}

TEST_F(TextureStreamerTest, SameResultThroughTheStagingRingOnly) {
    TextureStreamerOptions options;
    options.frameBudget = 32ull << 20;  // every DamagedHelmet texture (22.4 MiB with mips) fits one frame's slice
    ReadyLog log(helmet().textures.size());
    TextureStreamer stream(ctx(), helmet(), log.callback(), options);
    pumpFrames(ctx(), {&stream}, {&log});
    expectExact(ctx(), helmet(), stream, log);
    EXPECT_EQ(stream.stats().dedicatedStagings, 0u);
    EXPECT_EQ(stream.stats().uploadFrames, 5u);  // 2 x 22.4 MiB exceeds the 32 MiB budget: one per frame
}

TEST_F(TextureStreamerTest, TinyBudgetArrivesOverSeveralFramesWithValidPlaceholders) {
    // The renderer's view: each texture's current bindless index is a 1x1 white placeholder until onReady.
    const uint8_t white[4] = {255, 255, 255, 255};
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = "test loading placeholder";
    vk::Image placeholder = ctx().createImage(desc);
    vk::uploadImage(ctx(), placeholder, white, 4, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const vk::SampledIndex placeholderIndex = ctx().bindless().addSampled(placeholder.view);

    TextureStreamerOptions options;
    options.frameBudget = 64 << 10;
    const scene::Scene& scene = helmet();
    const uint32_t n = uint32_t(scene.textures.size());
    ReadyLog log(n);
    TextureStreamer stream(ctx(), scene, log.callback(), options);

    // In frames where some but not all textures are ready, the frame itself copies texel (0, 0) of the image
    // behind every texture's current index: validation checks the layouts, the bytes are checked afterwards.
    vk::BufferDesc rb;
    rb.size = n * 4;
    rb.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    rb.memory = vk::MemoryUsage::Readback;
    rb.name = "texel probe";
    vk::Buffer probe = ctx().createBuffer(rb);
    std::vector<std::pair<std::vector<bool>, std::vector<uint8_t>>> probes;  // (ready, texels) per probed frame
    auto perFrame = [&](VkCommandBuffer cmd) {
        uint32_t readyNow = 0;
        for (uint32_t t = 0; t < n; ++t) readyNow += stream.isReady(t);
        if (readyNow == 0 || readyNow == n || probes.size() >= 2) return;
        std::vector<bool> ready(n);
        for (uint32_t t = 0; t < n; ++t) {
            ready[t] = stream.isReady(t);
            const vk::SampledIndex index = ready[t] ? log.sampled[t] : placeholderIndex;
            EXPECT_LT(index.value, ctx().bindless().capacity(0));
            const vk::Image& img = ready[t] ? *stream.image(t) : placeholder;
            vk::transitionImage(cmd, img, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            VkBufferImageCopy r{};
            r.bufferOffset = t * 4;
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            r.imageExtent = {1, 1, 1};
            vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, probe.buffer, 1, &r);
            vk::transitionImage(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
        probes.emplace_back(ready, std::vector<uint8_t>());
    };
    // Run the probe frames one at a time so the probe buffer can be read after each.
    vk::FrameRing frames(ctx(), 2);
    uint64_t frame = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!stream.allReady() && std::chrono::steady_clock::now() < deadline) {
        VkCommandBuffer cmd = frames.begin();
        log.frame = frame;
        stream.pump(cmd);
        const size_t before = probes.size();
        perFrame(cmd);
        const uint64_t value = frames.end();
        if (probes.size() > before) {
            ctx().waitFor(value);
            probes.back().second.assign(static_cast<uint8_t*>(probe.mapped()),
                                        static_cast<uint8_t*>(probe.mapped()) + n * 4);
        }
        ++frame;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_TRUE(stream.allReady());
    expectExact(ctx(), scene, stream, log);

    // Every texture is above the 64 KiB budget: one per frame, each through its own staging buffer.
    const render::TextureStreamerStats s = stream.stats();
    EXPECT_EQ(s.dedicatedStagings, 5u);
    EXPECT_EQ(s.uploadFrames, 5u);
    uint64_t first = UINT64_MAX, last = 0;
    for (uint32_t t = 0; t < n; ++t) first = std::min(first, log.frameOfCall[t]), last = std::max(last, log.frameOfCall[t]);
    EXPECT_GT(last, first) << "textures should arrive over more than one frame";
    ASSERT_GE(probes.size(), 1u) << "no frame was recorded while only some textures were ready";
    for (const auto& [ready, texels] : probes) {
        ASSERT_EQ(texels.size(), n * 4);
        for (uint32_t t = 0; t < n; ++t) {
            const bool srgb = stream.colorSpaces()[t] != scene::TextureColorSpace::Linear;
            const uint8_t* expected = ready[t] ? reference(scene, t, srgb).texels.data() : white;
            EXPECT_EQ(0, std::memcmp(texels.data() + t * 4, expected, 4)) << "texture " << t;
        }
    }
    ctx().waitIdle();
    ctx().destroy(probe);
    ctx().bindless().release(placeholderIndex);
    ctx().destroyDeferred(placeholder);
}

TEST_F(TextureStreamerTest, SameResultOnAContextWithForcedStaging) {
    vk::ContextDesc desc;
    desc.validation = true;
    desc.forceStaging = true;
    vk::Context forced(desc);
    {
        ReadyLog helmetLog(helmet().textures.size()), boxLog(box().textures.size());
        TextureStreamer helmetStream(forced, helmet(), helmetLog.callback());
        TextureStreamer boxStream(forced, box(), boxLog.callback());
        pumpFrames(forced, {&helmetStream, &boxStream}, {&helmetLog, &boxLog});
        expectExact(forced, helmet(), helmetStream, helmetLog);
        expectExact(forced, box(), boxStream, boxLog);
    }
    forced.waitIdle();
    EXPECT_EQ(forced.validationErrors(), 0u);
    for (const std::string& m : forced.validationMessages()) ADD_FAILURE() << m;
}

TEST_F(TextureStreamerTest, FinishSynchronouslyUploadsTheRest) {
    ReadyLog log(helmet().textures.size());
    TextureStreamer stream(ctx(), helmet(), log.callback());
    {
        vk::FrameRing frames(ctx(), 2);
        stream.pump(frames.begin());  // usually nothing yet
        frames.end();
    }
    stream.finishSynchronously();
    expectExact(ctx(), helmet(), stream, log);
}

// Hostile images: each becomes the placeholder, onReady still comes once per texture, and exactly one warning
// per image names it (none for the image the loader already reported).
TEST_F(TextureStreamerTest, HostileImagesBecomePlaceholdersWithOneWarningEach) {
    const std::vector<uint8_t> png = box().images[0].encoded;
    scene::Scene scene;
    scene.sourcePath = "/virtual/hostile.gltf";
    scene::Image missing, garbage, truncated, good;
    missing.path = "/virtual/gone.png";
    missing.status = scene::ImageStatus::Missing;  // as loadGltf records it, after its own warning
    garbage.encoded.resize(4096);
    std::mt19937 rng(3);
    for (uint8_t& b : garbage.encoded) b = uint8_t(rng());
    truncated.encoded.assign(png.begin(), png.begin() + std::ptrdiff_t(png.size() / 2));
    good.encoded = png;
    scene.images = {missing, garbage, truncated, good};
    scene.textures.resize(7);
    for (uint32_t i = 0; i < 4; ++i) scene.textures[i].image = i;
    scene.textures[4].image = 3;  // the good image again, used as data
    scene.textures[6].image = 1;  // unused
    scene::Material m0, m1;
    m0.baseColorTexture = scene::TextureRef{0};
    m0.emissiveTexture = scene::TextureRef{1};
    m0.normalTexture = scene::TextureRef{2};
    m0.metallicRoughnessTexture = scene::TextureRef{4};
    m0.occlusionTexture = scene::TextureRef{5};  // texture 5 has no source
    m1.baseColorTexture = scene::TextureRef{3};
    scene.materials = {m0, m1};

    std::vector<std::string> logged;
    core::setLogSink([&](core::LogLevel level, std::string_view message) {
        if (level == core::LogLevel::Warning) logged.emplace_back(message);
    });
    ReadyLog log(scene.textures.size());
    {
        TextureStreamer stream(ctx(), scene, log.callback());
        pumpFrames(ctx(), {&stream}, {&log});
        core::setLogSink({});
        ReferenceDecodes decodes(scene);  // a local scene: not the shared cache
        expectExact(ctx(), scene, decodes, stream, log);
        const render::TextureStreamerStats s = stream.stats();
        EXPECT_EQ(s.textures, 6u);
        EXPECT_EQ(s.images, 6u);  // the good image twice (sRGB and linear)
        EXPECT_EQ(s.placeholders, 4u);
        const std::vector<uint8_t> magenta = {255, 0, 255, 255};
        const std::vector<uint8_t> mip0 = readMips(ctx(), *stream.image(1));
        EXPECT_EQ(std::vector<uint8_t>(mip0.begin(), mip0.begin() + 4), magenta);
    }
    core::setLogSink({});
    ASSERT_EQ(logged.size(), 3u);
    auto mentions = [&](const std::string& what) {
        size_t count = 0;
        for (const std::string& w : logged) count += w.find(what) != std::string::npos;
        return count;
    };
    EXPECT_EQ(mentions("embedded image 1 of hostile.gltf"), 1u);
    EXPECT_EQ(mentions("embedded image 2 of hostile.gltf"), 1u);
    EXPECT_EQ(mentions("texture 5 of hostile.gltf"), 1u);
    EXPECT_EQ(mentions("gone.png"), 0u);  // the loader's warning is the one
}

TEST_F(TextureStreamerTest, DestroyedMidStreamReleasesEverything) {
    const uint32_t deviceMemoryBefore = ctx().allocator().stats().deviceMemoryCount;
    {
        vk::FrameRing frames(ctx(), 2);
        ReadyLog log(helmet().textures.size());
        TextureStreamer stream(ctx(), helmet(), log.callback());
        for (int i = 0; i < 3; ++i) {
            stream.pump(frames.begin());
            frames.end();
        }
    }  // workers joined mid-decode; in-flight results discarded
    ctx().waitIdle();
    EXPECT_LE(ctx().allocator().stats().deviceMemoryCount, deviceMemoryBefore + 2);  // blocks may stay cached
    EXPECT_EQ(ctx().allocator().stats().bytesByCategory["textures"], 0u);
    EXPECT_EQ(ctx().allocator().stats().bytesByCategory["staging"], 0u);
}

TEST_F(TextureStreamerTest, SceneWithoutTexturesIsReadyAtOnce) {
    const scene::Scene scene = scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/Box/glTF-Binary/Box.glb");
    ReadyLog log(scene.textures.size());
    TextureStreamer stream(ctx(), scene, log.callback());
    EXPECT_TRUE(stream.allReady());
    EXPECT_EQ(stream.stats().images, 0u);
}

}  // namespace
}  // namespace idk::test
