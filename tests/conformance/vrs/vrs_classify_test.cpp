// vrs_classify_test.cpp: the GPU shading-rate classifier (vrs/classify.comp.glsl) against its CPU oracle
// (frame::classifyTilesCpu) on recorded frames: the HDR frames the renderer produced for the Cornell box and
// DamagedHelmet, with a velocity field of camera-like motion, at a size that leaves partial tiles on the right and
// bottom; plus edge-case tiles patched in: zero luminance, constant colour, NaN pixels, +inf and 65504 (the
// RGBA16F image cannot hold 1e6: it stores +inf, which the classifier clamps like 1e6), velocities of 1e6 and NaN.
// Rates must be identical per tile for the subgroup and the shared-memory reductions and tile sizes 8, 16, 32.
#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>

#include "app/default_scene.hpp"
#include "frame/vrs_oracle.hpp"
#include "passes/vrs_passes.hpp"
#include "render/renderer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kWidth = 200, kHeight = 136;  // not multiples of 16 or 32: partial tiles

struct Frame {
    std::vector<glm::vec4> lit;  // as stored in RGBA16F
    std::vector<glm::vec2> velocity;
};

// An HDR frame of the scene (values exactly as the RGBA16F target held them) and a velocity field: a rotation
// about the image centre plus a zoom, up to ~0.008 UV per frame (0.5 UV/s at 60 Hz).
Frame recordFrame(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::FrameResult result = renderer.renderOffscreen(scene::defaultCamera(scene), kWidth, kHeight);
    Frame f;
    for (size_t i = 0; i < size_t(kWidth) * kHeight; ++i) {
        const float* p = &result.image.pixels[i * 4];
        f.lit.emplace_back(p[0], p[1], p[2], p[3]);
        const glm::vec2 d = glm::vec2(float(i % kWidth) / kWidth - 0.5f, float(i / kWidth) / kHeight - 0.5f);
        f.velocity.push_back(glm::vec2(-d.y, d.x) * 0.012f + d * 0.006f);
    }
    return f;
}

void fillTile(uint32_t tx, uint32_t ty, uint32_t size, const std::function<void(uint32_t, uint32_t, size_t)>& fn) {
    for (uint32_t y = ty * size; y < std::min((ty + 1) * size, kHeight); ++y)
        for (uint32_t x = tx * size; x < std::min((tx + 1) * size, kWidth); ++x) fn(x, y, size_t(y) * kWidth + x);
}

// Edge cases in tiles of 32 pixels (each covers whole tiles of every tested size), row 0 lit, row 1 velocity.
void patchEdgeCases(Frame& f) {
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

class VrsClassifyTest : public GpuTest {
protected:
    std::vector<uint32_t> classifyOnGpu(const Frame& f, const passes::VrsClassifyParams& params) {
        std::vector<uint16_t> halves;
        for (const glm::vec4& c : f.lit)
            for (int k = 0; k < 4; ++k) halves.push_back(glm::packHalf1x16(c[k]));
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        desc.extent = {kWidth, kHeight, 1};
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        desc.name = "vrs test lit";
        vk::Image lit = ctx().createImage(desc);
        vk::uploadImage(ctx(), lit, halves.data(), halves.size() * 2, VK_IMAGE_LAYOUT_GENERAL);
        vk::StorageImageIndex slot = ctx().bindless().addStorage(lit.view);
        const uint32_t tilesX = (kWidth + params.tileSize - 1) / params.tileSize;
        const uint32_t tilesY = (kHeight + params.tileSize - 1) / params.tileSize;
        std::vector<uint32_t> header(4 + tilesX * tilesY, 0xffffffffu);  // rates pre-set to an invalid index
        header[0] = params.tileSize;
        header[1] = tilesX;
        header[2] = tilesY;
        header[3] = 0;
        vk::Buffer rates = vk::createBufferWithData(
            ctx(), {header.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "vrs test rates", "test"},
            header.data(), header.size() * 4);
        vk::Buffer velocity = vk::createBufferWithData(
            ctx(), {f.velocity.size() * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "vrs test velocity", "test"},
            f.velocity.data(), f.velocity.size() * 8);
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            passes::recordVrsClassify(cmd, ctx(), shaders(), params, slot.value, kWidth, kHeight, velocity.address,
                                      rates.address);
        });
        std::vector<uint32_t> out = vk::downloadBuffer<uint32_t>(ctx(), rates, header.size());
        ctx().bindless().release(slot);
        ctx().destroy(lit);
        ctx().destroy(rates);
        ctx().destroy(velocity);
        return std::vector<uint32_t>(out.begin() + 4, out.end());
    }

    // Compares every tile; returns the histogram of oracle rates. A tile whose value lies within 1e-5 (relative)
    // of a rounding boundary may differ by one (the final sqrt/divisions may round differently on a GPU): counted.
    std::array<int, 5> compare(const Frame& f, const passes::VrsClassifyParams& params, const char* what) {
        frame::VrsTileRates cpu = frame::classifyTilesCpu(f.lit, f.velocity, kWidth, kHeight, params.tileSize,
                                                          params.frameSeconds, params.speedFactor, params.lumVarianceFactor);
        std::vector<uint32_t> gpu = classifyOnGpu(f, params);
        EXPECT_EQ(gpu.size(), cpu.rates.size());
        std::array<int, 5> histogram{};
        int borderline = 0;
        for (size_t t = 0; t < std::min(gpu.size(), cpu.rates.size()); ++t) {
            histogram[std::min(cpu.rates[t], 4u)]++;
            const float v = cpu.values[t];
            const bool nearBoundary = v < 5.0f && std::abs(v - std::floor(v) - 0.5f) <= 1e-5f * std::max(1.0f, v);
            if (nearBoundary) borderline++;
            if (nearBoundary && (gpu[t] + 1 == cpu.rates[t] || gpu[t] == cpu.rates[t] + 1)) continue;
            EXPECT_EQ(gpu[t], cpu.rates[t]) << what << " tile " << t << " (" << t % cpu.tilesX << ", " << t / cpu.tilesX
                                            << ") of size " << params.tileSize << ", value " << v;
        }
        EXPECT_LE(borderline, 1) << what;
        if (borderline) std::cout << "[ vrs ] " << what << ": " << borderline << " tile(s) at a rounding boundary\n";
        return histogram;
    }
};

TEST_F(VrsClassifyTest, SubgroupAndSharedMemoryReductionsMatchTheCpuClassifierOnRecordedFrames) {
    const bool subgroups = ctx().capabilities().subgroupArithmetic;
    std::cout << "[ vrs ] subgroup size " << ctx().capabilities().subgroupSize
              << (subgroups ? "" : " (no subgroup arithmetic: shared-memory variant only)") << "\n";
    std::array<int, 5> total{};
    for (const char* name : {"cornell", "helmet"}) {
        scene::Scene scene = std::string(name) == "cornell"
                                 ? app::loadDefaultScene()
                                 : scene::loadGltf(std::string(IDK_SHARED_DIR) +
                                                   "/scenes/DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
        Frame f = recordFrame(ctx(), shaders(), scene);
        patchEdgeCases(f);
        for (uint32_t tile : {8u, 16u, 32u}) {
            for (bool subgroup : {true, false}) {
                if (subgroup && !subgroups) continue;
                // The original's factors, and stronger ones so that the speed term decides some tiles.
                std::vector<float> speedFactors{gpu::kVrsSpeedFactor};
                if (tile == 16u) speedFactors.push_back(8.0f);
                for (float speedFactor : speedFactors) {
                    passes::VrsClassifyParams params;
                    params.tileSize = tile;
                    params.subgroupReduce = subgroup;
                    params.speedFactor = speedFactor;
                    std::string what = std::string(name) + (subgroup ? " subgroup" : " shared-memory");
                    std::array<int, 5> h = compare(f, params, what.c_str());
                    for (int r = 0; r < 5; ++r) total[r] += h[r];
                }
            }
        }
    }
    std::cout << "[ vrs ] tiles per rate 1x1..4x4:";
    for (int r = 0; r < 5; ++r) std::cout << " " << total[r];
    std::cout << "\n";
    for (int r = 0; r < 5; ++r) EXPECT_GT(total[r], 0) << "no tile at rate " << r << ": the frames do not exercise it";
}

TEST_F(VrsClassifyTest, EdgeCaseTilesGetTheDocumentedRates) {
    Frame f = recordFrame(ctx(), shaders(), app::loadDefaultScene());
    for (glm::vec2& v : f.velocity) v = glm::vec2(0.0f);  // no motion but the patched tiles'
    patchEdgeCases(f);
    passes::VrsClassifyParams params;
    params.tileSize = 32;
    params.subgroupReduce = ctx().capabilities().subgroupArithmetic;
    std::vector<uint32_t> rates = classifyOnGpu(f, params);
    const uint32_t row = (kWidth + 31) / 32;
    EXPECT_EQ(rates[0], 4u) << "zero luminance: dark, 4x4";
    EXPECT_EQ(rates[1], 4u) << "constant colour: CV 0, 4x4";
    EXPECT_EQ(rates[2], 0u) << "NaN pixels count as black: CV 0.71, 0.04/CV -> 1x1";
    EXPECT_EQ(rates[3], 0u) << "+inf clamped to 65504: CV 2 -> 1x1";
    EXPECT_EQ(rates[4], 0u) << "65504 / 0.01 alternating: CV ~1 -> 1x1";
    EXPECT_EQ(rates[5], 4u) << "negative radiance counts as black: dark, 4x4";
    EXPECT_EQ(rates[row + 0], 4u) << "1e6 UV per frame: the speed term saturates, 4x4";
    EXPECT_EQ(rates[row + 1], 0u) << "NaN velocity counts as still: CV 1/3 alone -> 1x1";
    EXPECT_EQ(rates[row + 2], 4u) << "mean luminance 0.00095 <= 0.001: dark, 4x4";
    frame::VrsTileRates cpu = frame::classifyTilesCpu(f.lit, f.velocity, kWidth, kHeight, 32, params.frameSeconds,
                                                      params.speedFactor, params.lumVarianceFactor);
    EXPECT_EQ(rates, cpu.rates);
}

}  // namespace
}  // namespace idk::test
