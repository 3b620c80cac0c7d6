// ssr_pyramid_test.cpp: the closest-depth Hi-Z pyramid of the SSR march (ssr/hiz_min.comp.glsl) against a direct
// CPU reduction (each texel the minimum over the depth pixels it covers, shared/depth_pyramid.h layout), exactly,
// for odd, non-power-of-two, thin and tiny depth images.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "passes/culling.hpp"
#include "shared/depth_pyramid.h"
#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

std::vector<float> closestDepthPyramid(const std::vector<float>& depth, glm::uvec2 size) {
    const uint32_t levels = gpu::hizLevelCount(size);
    std::vector<float> out(gpu::hizLevelOffset(size, levels));
    for (uint32_t k = 0; k < levels; ++k) {
        const glm::uvec2 s = gpu::hizLevelSize(size, k);
        const uint32_t span = 2u << k, offset = gpu::hizLevelOffset(size, k);
        for (uint32_t y = 0; y < s.y; ++y)
            for (uint32_t x = 0; x < s.x; ++x) {
                float m = 1.0f;
                for (uint32_t py = y * span; py < std::min((y + 1) * span, size.y); ++py)
                    for (uint32_t px = x * span; px < std::min((x + 1) * span, size.x); ++px)
                        m = std::min(m, depth[size_t(py) * size.x + px]);
                out[offset + y * s.x + x] = m;
            }
    }
    return out;
}

class SsrPyramidTest : public GpuTest {};

TEST_F(SsrPyramidTest, EqualsCpuMinimumReductionForAnySize) {
    const glm::uvec2 sizes[] = {{1, 1}, {2, 1}, {1, 7}, {7, 5}, {97, 61}, {300, 17}, {255, 256}};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (glm::uvec2 size : sizes) {
        std::vector<float> depth(size_t(size.x) * size.y);
        for (float& d : depth) d = u(rng) < 0.2f ? 1.0f : u(rng);  // background holes
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_R32_SFLOAT;
        desc.extent = {size.x, size.y, 1};
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        desc.name = "test depth";
        desc.category = "test";
        vk::Image image = ctx().createImage(desc);
        vk::uploadImage(ctx(), image, depth.data(), depth.size() * sizeof(float), VK_IMAGE_LAYOUT_GENERAL);
        vk::StorageImageIndex storage = ctx().bindless().addStorage(image.view);
        const uint32_t count = gpu::hizLevelOffset(size, gpu::hizLevelCount(size));
        vk::Buffer pyramid = ctx().createBuffer(
            {count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "pyramid", "test"});
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            passes::recordDepthPyramid(cmd, ctx(), shaders(), storage.value, size, pyramid.address,
                                       passes::HizReduction::Closest);
        });
        const std::vector<float> got = vk::downloadBuffer<float>(ctx(), pyramid, count);
        ctx().bindless().release(storage);
        ctx().destroyDeferred(pyramid);
        ctx().destroyDeferred(image);
        const std::vector<float> expected = closestDepthPyramid(depth, size);
        ASSERT_EQ(got.size(), expected.size());
        size_t wrong = 0;
        for (size_t i = 0; i < got.size(); ++i) wrong += got[i] != expected[i];
        EXPECT_EQ(wrong, 0u) << size.x << "x" << size.y << ": texels differing from the CPU minimum";
        EXPECT_EQ(expected.back(), *std::min_element(depth.begin(), depth.end())) << "the last level: the nearest";
    }
}

}  // namespace
}  // namespace idk::test
