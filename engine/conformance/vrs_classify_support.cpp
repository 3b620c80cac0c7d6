// vrs_classify_support.cpp: the frame, edge cases, GPU run and oracle comparison of vrs_classify_support.hpp (moved
// from tests/conformance/vrs/ so that the registry check and the DamagedHelmet test run the same comparison).
#include "conformance/vrs_classify_support.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "frame/vrs_oracle.hpp"
#include "render/renderer.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {
namespace {

void fillTile(uint32_t tx, uint32_t ty, uint32_t size, const std::function<void(uint32_t, uint32_t, size_t)>& fn) {
    for (uint32_t y = ty * size; y < std::min((ty + 1) * size, kVrsHeight); ++y)
        for (uint32_t x = tx * size; x < std::min((tx + 1) * size, kVrsWidth); ++x) fn(x, y, size_t(y) * kVrsWidth + x);
}

}  // namespace

VrsFrame recordVrsFrame(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::FrameResult result = renderer.renderOffscreen(scene::defaultCamera(scene), kVrsWidth, kVrsHeight);
    VrsFrame f;
    for (size_t i = 0; i < size_t(kVrsWidth) * kVrsHeight; ++i) {
        const float* p = &result.image.pixels[i * 4];
        f.lit.emplace_back(p[0], p[1], p[2], p[3]);
        const glm::vec2 d = glm::vec2(float(i % kVrsWidth) / kVrsWidth - 0.5f, float(i / kVrsWidth) / kVrsHeight - 0.5f);
        f.velocity.push_back(glm::vec2(-d.y, d.x) * 0.012f + d * 0.006f);
    }
    return f;
}

void patchVrsEdgeCases(VrsFrame& f) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const glm::vec4 one(1.0f);
    fillTile(0, 0, 32, [&](uint32_t, uint32_t, size_t i) { f.lit[i] = glm::vec4(0, 0, 0, 1); });        // zero
    fillTile(1, 0, 32, [&](uint32_t, uint32_t, size_t i) { f.lit[i] = glm::vec4(0.3f, 0.5f, 0.2f, 1); }); // constant
    fillTile(2, 0, 32, [&](uint32_t x, uint32_t, size_t i) { f.lit[i] = x % 3 == 0 ? glm::vec4(nan, 1, 1, 1) : one; });
    fillTile(3, 0, 32, [&](uint32_t x, uint32_t y, size_t i) { f.lit[i] = (x + y) % 5 == 0 ? glm::vec4(inf, 0, 0, 1) : one; });
    fillTile(4, 0, 32, [&](uint32_t x, uint32_t, size_t i) { f.lit[i] = glm::vec4(x % 2 ? 65504.0f : 0.01f); });
    fillTile(5, 0, 32, [&](uint32_t, uint32_t, size_t i) { f.lit[i] = glm::vec4(-1.0f, 0.0f, 0.0f, 1.0f); });  // negative
    fillTile(0, 1, 32, [&](uint32_t, uint32_t, size_t i) { f.velocity[i] = glm::vec2(1e6f, -1e6f); });
    fillTile(1, 1, 32, [&](uint32_t x, uint32_t, size_t i) {
        f.lit[i] = x % 2 ? glm::vec4(0.5f) : one;
        if (x % 2) f.velocity[i] = glm::vec2(nan, 0.0f);
    });
    fillTile(2, 1, 32, [&](uint32_t x, uint32_t, size_t i) { f.lit[i] = glm::vec4(x % 2 ? 5e-4f : 1.4e-3f); });  // mean < 0.001
    for (glm::vec4& c : f.lit)  // what the RGBA16F image stores
        for (int k = 0; k < 4; ++k) c[k] = glm::unpackHalf1x16(glm::packHalf1x16(c[k]));
}

std::vector<uint32_t> classifyOnGpu(vk::Context& ctx, vk::ShaderLibrary& shaders, const VrsFrame& f,
                                    const passes::VrsClassifyParams& params) {
    std::vector<uint16_t> halves;
    for (const glm::vec4& c : f.lit)
        for (int k = 0; k < 4; ++k) halves.push_back(glm::packHalf1x16(c[k]));
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.extent = {kVrsWidth, kVrsHeight, 1};
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    desc.name = "vrs check lit";
    vk::Image lit = ctx.createImage(desc);
    vk::uploadImage(ctx, lit, halves.data(), halves.size() * 2, VK_IMAGE_LAYOUT_GENERAL);
    vk::StorageImageIndex slot = ctx.bindless().addStorage(lit.view);
    const uint32_t tilesX = (kVrsWidth + params.tileSize - 1) / params.tileSize;
    const uint32_t tilesY = (kVrsHeight + params.tileSize - 1) / params.tileSize;
    std::vector<uint32_t> header(4 + tilesX * tilesY, 0xffffffffu);  // rates pre-set to an invalid index
    header[0] = params.tileSize;
    header[1] = tilesX;
    header[2] = tilesY;
    header[3] = 0;
    vk::Buffer rates = vk::createBufferWithData(
        ctx, {header.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "vrs check rates", "test"},
        header.data(), header.size() * 4);
    vk::Buffer velocity = vk::createBufferWithData(
        ctx, {f.velocity.size() * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "vrs check velocity", "test"},
        f.velocity.data(), f.velocity.size() * 8);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        passes::recordVrsClassify(cmd, ctx, shaders, params, slot.value, kVrsWidth, kVrsHeight, velocity.address,
                                  rates.address);
    });
    std::vector<uint32_t> out = vk::downloadBuffer<uint32_t>(ctx, rates, header.size());
    ctx.bindless().release(slot);
    ctx.destroy(lit);
    ctx.destroy(rates);
    ctx.destroy(velocity);
    return std::vector<uint32_t>(out.begin() + 4, out.end());
}

std::array<int, 5> expectClassifierMatches(Verdict& v, vk::Context& ctx, vk::ShaderLibrary& shaders, const VrsFrame& f,
                                           const passes::VrsClassifyParams& params, const std::string& what) {
    const frame::VrsTileRates cpu = frame::classifyTilesCpu(f.lit, f.velocity, kVrsWidth, kVrsHeight, params.tileSize,
                                                            params.frameSeconds, params.speedFactor, params.lumVarianceFactor);
    const std::vector<uint32_t> gpu = classifyOnGpu(ctx, shaders, f, params);
    v.expectEq(gpu.size(), cpu.rates.size(), what + ": tile count");
    std::array<int, 5> histogram{};
    for (size_t t = 0; t < std::min(gpu.size(), cpu.rates.size()); ++t) {
        histogram[std::min(cpu.rates[t], 4u)]++;
        v.expectEq(gpu[t], cpu.rates[t], what + " tile " + std::to_string(t % cpu.tilesX) + "," +
                                             std::to_string(t / cpu.tilesX) + " of size " + std::to_string(params.tileSize));
    }
    return histogram;
}

}  // namespace idk::conformance
