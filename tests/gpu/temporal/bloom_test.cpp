// bloom_test.cpp: the bloom passes (passes/bloom.cpp) on CPU-made HDR images, run through a render graph on the
// device and read back:
//  * energy: the image's total radiance (sum over pixels, per channel) is kept within 1%, for a scattered HDR image
//    with bright spots and for a single bright texel (without the Karis average, which deliberately takes energy
//    from fireflies; with it, the loss is reported and bounded);
//  * symmetry: a bright 2x2 spot centred on a corner of every level's grid (the half-resolution chain cannot see a
//    single texel symmetrically) spreads into an image symmetric about the spot under x and y mirroring and
//    transposition, falling off monotonically with distance;
// IDKEngine has no bloom tests.
#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "graph/render_graph.hpp"
#include "passes/bloom.hpp"
#include "render/vk_graph_backend.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 128;

// Runs the bloom over `image` (kSize x kSize RGB, stored as RGBA16F) and returns the result's RGB.
std::vector<glm::vec3> bloomOnGpu(vk::Context& ctx, vk::ShaderLibrary& shaders, const std::vector<glm::vec3>& image,
                                  const passes::BloomParams& params) {
    const VkExtent3D extent{kSize, kSize, 1};
    const size_t count = size_t(kSize) * kSize;
    std::vector<uint16_t> halves(count * 4);
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 4; ++c) halves[i * 4 + c] = glm::packHalf1x16(c < 3 ? image[i][c] : 1.0f);
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.extent = extent;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    desc.name = "bloom test image";
    vk::Image target = ctx.createImage(desc);
    vk::uploadImage(ctx, target, halves.data(), halves.size() * sizeof(uint16_t), VK_IMAGE_LAYOUT_GENERAL);
    vk::StorageImageIndex slot = ctx.bindless().addStorage(target.view);
    vk::BufferDesc bufferDesc;
    bufferDesc.size = count * 4 * sizeof(uint16_t);
    bufferDesc.memory = vk::MemoryUsage::Readback;
    bufferDesc.name = "bloom test readback";
    vk::Buffer readback = ctx.createBuffer(bufferDesc);
    {
        render::VkGraphBackend backend(ctx);
        graph::ResourcePool pool(backend);
        graph::RenderGraph graph(pool, {kSize, kSize});
        graph::ResourceState general;
        general.layout = VK_IMAGE_LAYOUT_GENERAL;
        graph::PhysicalTexture p;
        p.image = target.image;
        p.view = target.view;
        p.format = target.format;
        p.extent = extent;
        p.storageIndex = slot.value;
        const graph::TextureHandle hdr = graph.importTexture("hdr", p, general);
        const graph::TextureHandle bloomed = passes::addBloomPasses(graph, ctx, shaders, hdr, kSize, kSize, params);
        graph::PhysicalBuffer pb;
        pb.buffer = readback.buffer;
        pb.size = readback.size;
        pb.address = readback.address;
        const graph::BufferHandle out = graph.importBuffer("readback", pb, graph::ResourceState{});
        auto copied = std::make_shared<graph::BufferHandle>();
        graph.addPass(
            "readback",
            [&](graph::PassBuilder& b) {
                b.read(bloomed, graph::Access::TransferSrc);
                *copied = b.write(out, graph::Access::TransferDst);
            },
            [bloomed, copied, extent](graph::PassContext& pc) {
                VkBufferImageCopy region{};
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.imageExtent = extent;
                vkCmdCopyImageToBuffer(pc.commandBuffer(), pc.image(bloomed), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                       pc.vkBuffer(*copied), 1, &region);
            });
        graph.markOutput(*copied);
        ctx.runImmediate([&](VkCommandBuffer cmd) { graph.execute(cmd); });
        ctx.waitIdle();
    }
    const std::vector<uint16_t> bits = vk::downloadBuffer<uint16_t>(ctx, readback, count * 4);
    ctx.destroy(readback);
    ctx.bindless().release(slot);
    ctx.destroy(target);
    std::vector<glm::vec3> result(count);
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c) result[i][c] = glm::unpackHalf1x16(bits[i * 4 + c]);
    return result;
}

glm::dvec3 total(const std::vector<glm::vec3>& image) {
    glm::dvec3 sum(0.0);
    for (const glm::vec3& v : image) sum += glm::dvec3(v);
    return sum;
}

// Values rounded to half precision, as the RGBA16F image holds them.
std::vector<glm::vec3> halfRounded(std::vector<glm::vec3> image) {
    for (glm::vec3& v : image)
        for (int c = 0; c < 3; ++c) v[c] = glm::unpackHalf1x16(glm::packHalf1x16(v[c]));
    return image;
}

// A scattered HDR image: smooth colours plus bright spots (up to 60), black outside a 24-texel margin (the chain
// clamps at the border, which is not energy exact).
std::vector<glm::vec3> scatteredImage() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> image(size_t(kSize) * kSize, glm::vec3(0.0f));
    for (uint32_t y = 24; y < kSize - 24; ++y)
        for (uint32_t x = 24; x < kSize - 24; ++x) {
            glm::vec3 v(0.5f + 0.4f * std::sin(0.1f * x), 0.3f + 0.2f * std::cos(0.07f * y), 0.2f * u(rng));
            if (u(rng) < 0.01f) v *= 60.0f;
            image[size_t(y) * kSize + x] = v;
        }
    return halfRounded(image);
}

class BloomTest : public GpuTest {};

TEST_F(BloomTest, TotalEnergyIsConserved) {
    const std::vector<glm::vec3> image = scatteredImage();
    std::vector<glm::vec3> spot(size_t(kSize) * kSize, glm::vec3(0.0f));
    spot[size_t(70) * kSize + 53] = glm::vec3(100.0f, 50.0f, 25.0f);
    for (const std::vector<glm::vec3>* in : {&image, static_cast<const std::vector<glm::vec3>*>(&spot)}) {
        const glm::dvec3 before = total(*in);
        const glm::dvec3 exact = total(bloomOnGpu(ctx(), shaders(), *in, {1.0f, false}));   // only the bloom
        const glm::dvec3 karis = total(bloomOnGpu(ctx(), shaders(), *in, {1.0f, true}));
        for (int c = 0; c < 3; ++c) {
            const double err = std::abs(exact[c] / before[c] - 1.0), loss = 1.0 - karis[c] / before[c];
            std::printf("%s channel %d: sum %.3f -> %.3f (%.4f%%), with the Karis average %.3f (%.2f%% lost)\n",
                        in == &spot ? "spot" : "scattered", c, before[c], exact[c], 100.0 * err, karis[c], 100.0 * loss);
            // Seen: 0.51-0.54% (scattered), 0.20% (spot): half-precision levels and the 13-tap kernel's weights
            // landing unevenly on the 2x2 phases of the source grid.
            EXPECT_LT(err, 0.01) << "channel " << c;
            // The Karis average weights each 2x2 group by 1 / (1 + luma): it takes energy from isolated bright
            // texels by design (seen: 8% of the scattered image's, 43% of a lone spot's).
            EXPECT_GT(loss, 0.0) << "channel " << c;
            EXPECT_LT(loss, in == &spot ? 0.6 : 0.15) << "channel " << c;
        }
    }
}

TEST_F(BloomTest, BrightSpotSpreadsSymmetrically) {
    std::vector<glm::vec3> image(size_t(kSize) * kSize, glm::vec3(0.0f));
    for (uint32_t y = 63; y <= 64; ++y)
        for (uint32_t x = 63; x <= 64; ++x) image[size_t(y) * kSize + x] = glm::vec3(40.0f);
    const std::vector<glm::vec3> out = bloomOnGpu(ctx(), shaders(), image, {0.5f, false});
    const auto at = [&](uint32_t x, uint32_t y) { return out[size_t(y) * kSize + x].r; };
    float worst = 0.0f;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const float v = at(x, y), tolerance = 2e-3f * std::abs(v) + 1e-6f;
            worst = std::max({worst, std::abs(v - at(kSize - 1 - x, y)) - tolerance,
                              std::abs(v - at(x, kSize - 1 - y)) - tolerance, std::abs(v - at(y, x)) - tolerance});
        }
    EXPECT_LE(worst, 0.0f) << "asymmetry beyond half-precision rounding";
    // A blur: energy reaches 12 texels away and falls off monotonically along the row through the spot.
    EXPECT_GT(at(64 + 12, 64), 0.0f);
    for (uint32_t x = 64; x < 64 + 20; ++x) EXPECT_GE(at(x, 64), at(x + 1, 64)) << "x " << x;
    std::printf("spot 40 -> centre %.3f, +4: %.4f, +12: %.5f\n", at(64, 64), at(68, 64), at(76, 64));
}

}  // namespace
}  // namespace idk::test
