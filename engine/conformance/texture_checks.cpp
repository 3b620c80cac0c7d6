// texture_checks.cpp: the asynchronous texture streamer (engine/render/texture_streamer.*) on the device, on a
// scene made here so that `idk conformance` needs no asset: three PNG images encoded in memory (301x203 and 7x1,
// odd sizes with odd mip chains, and 128x128), used as base colour (sRGB), normal map (linear) and both by two
// materials, plus a texture no material uses. Streamed while empty frames are pumped, every mip read back must equal
// the CPU decode byte for byte (texture_stream_support.hpp), onReady comes once per used texture with valid
// bindless indices and never for the unused one; with the default budget and with a 16 KiB budget (the large
// image then gets its own staging buffer and the textures arrive over several frames). The DamagedHelmet and
// BoxTextured runs, placeholders, hostile images and teardown stay in tests/conformance/textures/.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <random>

#include "conformance/conformance.hpp"
#include "conformance/texture_stream_support.hpp"

namespace idk::conformance {
namespace {

// A width x height RGBA8 PNG, encoded in memory: a gradient with seeded noise and varying alpha.
std::vector<uint8_t> pngImage(uint32_t width, uint32_t height, uint32_t seed) {
    std::vector<uint8_t> rgba(size_t(width) * height * 4);
    std::mt19937 rng(seed);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            uint8_t* p = &rgba[(size_t(y) * width + x) * 4];
            p[0] = uint8_t(255 * x / std::max(1u, width - 1));
            p[1] = uint8_t(255 * y / std::max(1u, height - 1));
            p[2] = uint8_t(rng());
            p[3] = uint8_t(128 + (rng() % 128));
        }
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create("texture.png");
    if (!out || !out->set_ioproxy(&memory)) throw std::runtime_error("cannot encode a PNG in memory");
    const OIIO::ImageSpec spec(int(width), int(height), 4, OIIO::TypeDesc::UINT8);
    bool ok = out->open("texture.png", spec) && out->write_image(OIIO::TypeDesc::UINT8, rgba.data());
    ok = out->close() && ok;
    if (!ok) throw std::runtime_error("PNG encoding failed: " + out->geterror());
    return encoded;
}

scene::Scene texturedScene() {
    scene::Scene s;
    const uint32_t sizes[3][2] = {{301, 203}, {128, 128}, {7, 1}};
    for (uint32_t i = 0; i < 3; ++i) {
        scene::Image image;
        image.name = "check image " + std::to_string(i);
        image.mimeType = "image/png";
        image.encoded = pngImage(sizes[i][0], sizes[i][1], 100 + i);
        s.images.push_back(std::move(image));
    }
    for (uint32_t i : {0u, 1u, 2u, 1u}) s.textures.push_back({i, {}});  // texture 3: image 1 again, unused
    scene::Material a, b;
    a.baseColorTexture = scene::TextureRef{0};
    a.normalTexture = scene::TextureRef{1};
    b.baseColorTexture = scene::TextureRef{2};
    b.metallicRoughnessTexture = scene::TextureRef{1};
    s.materials = {a, b};
    return s;
}

void streamOnce(CheckEnv& env, Verdict& v, const render::TextureStreamerOptions& options, const std::string& what,
                uint64_t* frames, uint32_t* dedicated, uint64_t* spread) {
    const scene::Scene scene = texturedScene();
    ReferenceDecodes reference(scene);
    ReadyLog log(scene.textures.size());
    render::TextureStreamer stream(env.ctx, scene, log.callback(), options);
    const StreamResult r = pumpUntilReady(env.ctx, {&stream}, {&log});
    if (!v.expect(!r.timedOut, what + ": textures not ready after 120 s")) return;
    Verdict inner;
    expectStreamedExactly(inner, env.ctx, scene, reference, stream, log);
    v.expect(inner.passed(), what + ": " + inner.messages());
    const render::TextureStreamerStats stats = stream.stats();
    v.expectEq(stats.textures, 3u, what + ": textures streamed");
    v.expectEq(stats.placeholders, 0u, what + ": placeholders");
    v.expect(stream.warnings().empty(), what + ": warnings");
    *frames = r.frames;
    *dedicated = stats.dedicatedStagings;
    uint64_t first = UINT64_MAX, last = 0;
    for (uint32_t t = 0; t < 3; ++t) first = std::min(first, log.frameOfCall[t]), last = std::max(last, log.frameOfCall[t]);
    *spread = last - first;
}

void streamsExactly(CheckEnv& env, Verdict& v) {
    uint64_t frames = 0, spread = 0;
    uint32_t dedicated = 0;
    streamOnce(env, v, {}, "default budget", &frames, &dedicated, &spread);
    v.expectEq(dedicated, 0u, "default budget: every image fits the staging ring");
    render::TextureStreamerOptions tiny;
    tiny.frameBudget = 16 << 10;  // below the 301x203 image with its mips (about 320 KiB)
    streamOnce(env, v, tiny, "16 KiB budget", &frames, &dedicated, &spread);
    v.expect(dedicated >= 1, "16 KiB budget: the large image did not get its own staging buffer");
    v.expect(spread > 0, "16 KiB budget: the textures should arrive over more than one frame");
}

}  // namespace

std::vector<Check> textureChecks() {
    return {{"textures/streaming", "", "every mip byte-identical to the CPU decode", streamsExactly}};
}

}  // namespace idk::conformance
