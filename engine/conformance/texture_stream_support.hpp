// texture_stream_support.hpp: what the texture-streaming check (texture_checks.cpp) and the asset-based streaming
// tests (tests/conformance/textures/) share: the CPU decode a streamed texture must equal, the read-back of every
// mip of an image, the log of the streamer's onReady calls, the frame pump, and the oracle of a finished stream
// (onReady once per used texture with valid indices, none for unused ones, every mip byte-identical to the CPU
// decode, in the format of its colour space).
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "conformance/conformance.hpp"
#include "render/texture_streamer.hpp"
#include "scene/scene.hpp"
#include "scene/texture_decode.hpp"

namespace idk::conformance {

// The CPU decodes of one scene's textures, made on first use (decoding 2048^2 textures takes a while).
class ReferenceDecodes {
public:
    explicit ReferenceDecodes(const scene::Scene& scene) : scene_(scene) {}
    const scene::DecodedTexture& get(uint32_t texture, bool srgb);

private:
    const scene::Scene& scene_;
    std::map<std::pair<uint32_t, bool>, scene::DecodedTexture> cache_;
};

// Every mip of an image in SHADER_READ_ONLY_OPTIMAL, tightly packed level after level (RGBA8).
std::vector<uint8_t> readMips(vk::Context& ctx, const vk::Image& image);

// What the renderer does with onReady, recorded: calls per texture and the indices handed over.
struct ReadyLog {
    std::vector<uint32_t> calls;
    std::vector<vk::SampledIndex> sampled;
    std::vector<vk::SamplerIndex> samplers;
    std::vector<uint64_t> frameOfCall;
    uint64_t frame = 0;
    uint32_t outOfRange = 0;  // calls naming a texture the scene does not have
    explicit ReadyLog(size_t n) : calls(n, 0), sampled(n), samplers(n), frameOfCall(n, 0) {}
    render::TextureStreamer::ReadyCallback callback();
};

struct StreamResult {
    uint64_t frames = 0;   // frames pumped until every streamer was ready
    bool timedOut = false;  // not ready after 120 s
};

// Pumps empty frames (a FrameRing of two) until every streamer is ready; `perFrame` runs after the pumps, inside
// the frame's command buffer. Gives up after 120 s.
StreamResult pumpUntilReady(vk::Context& ctx, const std::vector<render::TextureStreamer*>& streamers,
                            const std::vector<ReadyLog*>& logs,
                            const std::function<void(VkCommandBuffer, uint64_t frame)>& perFrame = {});

// A finished stream: onReady once per used texture with valid indices, every mip equal to the CPU decode.
void expectStreamedExactly(Verdict& v, vk::Context& ctx, const scene::Scene& scene, ReferenceDecodes& reference,
                           const render::TextureStreamer& streamer, const ReadyLog& log);

}  // namespace idk::conformance
