// depth_pyramid_test.cpp: the Hi-Z pyramid (culling/hiz_build.comp.glsl) against a direct CPU reduction
// (render::buildDepthPyramid), exactly, for odd, non-power-of-two, thin and tiny depth images, on both rungs of
// the ladder "hiz-reduction" (compute; MAX-reduction sampler); and the screen
// footprint of a box (shared/depth_pyramid.h) is conservative on 100k random boxes: every point of the box
// projects inside the rectangle, no nearer than its nearest depth, and the chosen level's at most
// 2 x 2 texels cover every pixel of the rectangle.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "passes/culling.hpp"
#include "render/depth_pyramid.hpp"
#include "scene/camera.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

// Depth of a few random planes seen from above, with background (1.0) holes: realistic structure, exact floats.
std::vector<float> randomDepth(glm::uvec2 size, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> d(size_t(size.x) * size.y);
    const float a = u(rng), b = u(rng) * 0.01f, c = u(rng) * 0.01f;
    for (uint32_t y = 0; y < size.y; ++y)
        for (uint32_t x = 0; x < size.x; ++x) {
            float v = u(rng) < 0.1f ? 1.0f : std::fmod(a + b * float(x) + c * float(y), 1.0f);
            d[size_t(y) * size.x + x] = u(rng) < 0.05f ? u(rng) : v;
        }
    return d;
}

class DepthPyramidTest : public GpuTest {
protected:
    std::vector<float> gpuPyramid(const std::vector<float>& depth, glm::uvec2 size) {
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
            passes::recordDepthPyramid(cmd, ctx(), shaders(), storage.value, size, pyramid.address);
        });
        std::vector<float> out = vk::downloadBuffer<float>(ctx(), pyramid, count);
        ctx().bindless().release(storage);
        ctx().destroyDeferred(pyramid);
        ctx().destroyDeferred(image);
        return out;
    }
};

TEST_F(DepthPyramidTest, EqualsCpuReductionForAnySize) {
    const glm::uvec2 sizes[] = {{1, 1}, {2, 1}, {1, 7}, {7, 5}, {97, 61}, {128, 128}, {300, 17}, {255, 256}, {640, 360}};
    uint32_t seed = 1;
    for (glm::uvec2 size : sizes) {
        const std::vector<float> depth = randomDepth(size, seed++);
        const std::vector<float> expected = render::buildDepthPyramid(depth, size);
        const std::vector<float> got = gpuPyramid(depth, size);
        ASSERT_EQ(got.size(), expected.size());
        size_t wrong = 0;
        for (size_t i = 0; i < got.size(); ++i) wrong += got[i] != expected[i];
        EXPECT_EQ(wrong, 0u) << size.x << "x" << size.y << ": texels differing from the CPU reduction";
        // The last level is one texel holding the image's maximum.
        EXPECT_EQ(expected.back(), *std::max_element(depth.begin(), depth.end()));
    }
}

// The native rung of "hiz-reduction" (passes/depth_pyramid_minmax.cpp): one MAX-reduction sample per 2 x 2 block.
// Bit-exact against the CPU reduction and the compute rung for the same odd and non-power-of-two sizes.
class DepthPyramidMinmaxTest : public DepthPyramidTest {
protected:
    vk::Image image(glm::uvec2 size, VkImageUsageFlags usage, const char* name) {
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_R32_SFLOAT;
        desc.extent = {size.x, size.y, 1};
        desc.usage = usage;
        desc.name = name;
        desc.category = "test";
        return ctx().createImage(desc);
    }
    std::vector<float> samplerPyramid(const std::vector<float>& depth, glm::uvec2 size, uint32_t sampler) {
        vk::Image depthImage = image(size, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test depth");
        vk::uploadImage(ctx(), depthImage, depth.data(), depth.size() * sizeof(float),
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        const vk::SampledIndex depthSampled = ctx().bindless().addSampled(depthImage.view);
        std::vector<vk::Image> levels;
        passes::HizMinmaxResources records;
        records.sampler = sampler;
        std::vector<vk::SampledIndex> sampled;
        for (uint32_t level = 0; level < gpu::hizLevelCount(size); ++level) {
            levels.push_back(image(gpu::hizLevelSize(size, level),
                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test hiz level"));
            sampled.push_back(ctx().bindless().addSampled(levels.back().view));
            records.levels.push_back({levels.back().image, sampled.back().value});
        }
        const uint32_t count = gpu::hizLevelOffset(size, gpu::hizLevelCount(size));
        vk::Buffer pyramid = ctx().createBuffer({count * sizeof(float),
                                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                 vk::MemoryUsage::GpuOnly, "pyramid", "test"});
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            passes::recordDepthPyramidMinmax(cmd, ctx(), shaders(), depthSampled.value, records, size, pyramid.buffer,
                                             pyramid.address);
        });
        std::vector<float> out = vk::downloadBuffer<float>(ctx(), pyramid, count);
        ctx().bindless().release(depthSampled);
        for (size_t i = 0; i < levels.size(); ++i) {
            ctx().bindless().release(sampled[i]);
            ctx().destroyDeferred(levels[i]);
        }
        ctx().destroyDeferred(pyramid);
        ctx().destroyDeferred(depthImage);
        return out;
    }
};

TEST_F(DepthPyramidMinmaxTest, SamplerRungEqualsCpuReductionAndComputeRungForAnySize) {
    if (ctx().ladder("hiz-reduction").chosen != vk::Rung::Native)
        GTEST_SKIP() << "device lacks samplerFilterMinmax: only the compute rung runs (the test above covers it)";
    vk::SamplerDesc max;
    max.filter = VK_FILTER_LINEAR;
    max.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    max.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    max.reduction = VK_SAMPLER_REDUCTION_MODE_MAX;
    const vk::SamplerIndex sampler = ctx().bindless().addSampler(max);
    const glm::uvec2 sizes[] = {{1, 1}, {2, 1}, {1, 7}, {7, 5}, {97, 61}, {128, 128}, {300, 17}, {255, 256}, {641, 361}};
    uint32_t seed = 21;
    for (glm::uvec2 size : sizes) {
        const std::vector<float> depth = randomDepth(size, seed++);
        const std::vector<float> expected = render::buildDepthPyramid(depth, size);
        const std::vector<float> got = samplerPyramid(depth, size, sampler.value);
        const std::vector<float> compute = gpuPyramid(depth, size);
        ASSERT_EQ(got.size(), expected.size());
        size_t wrong = 0, differsFromCompute = 0;
        for (size_t i = 0; i < got.size(); ++i) {
            wrong += std::memcmp(&got[i], &expected[i], sizeof(float)) != 0;
            differsFromCompute += std::memcmp(&got[i], &compute[i], sizeof(float)) != 0;
        }
        EXPECT_EQ(wrong, 0u) << size.x << "x" << size.y << ": texels differing from the CPU reduction";
        EXPECT_EQ(differsFromCompute, 0u) << size.x << "x" << size.y << ": texels differing from the compute rung";
    }
    ctx().bindless().release(sampler);
}

// The sampler really reduces: a weighted-average sampler at the same coordinates gives the mean of the 2 x 2
// block, which differs from the maximum on random depth (so the test above cannot pass by accident).
TEST_F(DepthPyramidMinmaxTest, AveragingSamplerDoesNotGiveTheMaximum) {
    if (ctx().ladder("hiz-reduction").chosen != vk::Rung::Native) GTEST_SKIP() << "no sampler rung";
    vk::SamplerDesc average;
    average.filter = VK_FILTER_NEAREST;  // R32F linear filtering is optional; nearest picks one texel, not the max
    average.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    average.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    const vk::SamplerIndex sampler = ctx().bindless().addSampler(average);
    const glm::uvec2 size(97, 61);
    const std::vector<float> depth = randomDepth(size, 5);
    const std::vector<float> expected = render::buildDepthPyramid(depth, size);
    const std::vector<float> got = samplerPyramid(depth, size, sampler.value);
    size_t wrong = 0;
    for (size_t i = 0; i < got.size(); ++i) wrong += got[i] != expected[i];
    EXPECT_GT(wrong, got.size() / 4) << "a plain sampler must not reproduce the MAX reduction";
    ctx().bindless().release(sampler);
}

TEST(DepthPyramidLayout, LevelSizesHalveWithCeilingDownToOneTexel) {
    EXPECT_EQ(gpu::hizLevelCount({1, 1}), 1u);
    EXPECT_EQ(gpu::hizLevelCount({2, 2}), 1u);
    EXPECT_EQ(gpu::hizLevelCount({3, 1}), 2u);
    EXPECT_EQ(gpu::hizLevelCount({640, 360}), 10u);  // 320, 160, 80, 40, 20, 10, 5, 3, 2, 1 wide
    EXPECT_EQ(gpu::hizLevelSize({640, 360}, 0), glm::uvec2(320, 180));
    EXPECT_EQ(gpu::hizLevelSize({640, 360}, 7), glm::uvec2(3, 2));
    EXPECT_EQ(gpu::hizLevelSize({641, 361}, 0), glm::uvec2(321, 181));
}

// 100k random boxes, some straddling the near plane or behind the eye, seen by random perspective views.
TEST(HizFootprint, IsConservativeOnRandomBoxes) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(-30.0f, 30.0f), size(0.01f, 6.0f);
    const glm::uvec2 viewport(333, 187);
    uint32_t projected = 0, rejected = 0;
    for (int n = 0; n < 100000; ++n) {
        const glm::vec3 eye(pos(rng) * 0.2f, pos(rng) * 0.2f, pos(rng) * 0.2f);
        const glm::mat4 vp = scene::perspectiveVulkan(0.4f + 1.2f * (u(rng) * 0.5f + 0.5f), 16.0f / 9.0f, 0.1f,
                                                      n % 2 ? 0.0f : 200.0f) *
                             glm::lookAt(eye, eye + glm::vec3(u(rng), u(rng), u(rng) + 1e-3f), glm::vec3(0, 1, 0));
        const glm::vec3 center(pos(rng), pos(rng), pos(rng)), extent(size(rng), size(rng), size(rng));
        glm::vec4 rect;
        float nearest = 0.0f;
        if (!gpu::hizFootprint(vp, center, extent, glm::vec2(viewport), rect, nearest)) {
            ++rejected;
            continue;
        }
        ++projected;
        for (int k = 0; k < 16; ++k) {
            const glm::vec3 t = k < 8 ? glm::vec3((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1)
                                      : glm::vec3(u(rng), u(rng), u(rng));
            const glm::vec4 clip = vp * glm::vec4(center + t * extent, 1.0f);
            ASSERT_GT(clip.w, 0.0f) << "box " << n;
            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
            const glm::vec2 pixel = (glm::vec2(ndc) * 0.5f + 0.5f) * glm::vec2(viewport);
            // Interior points are convex combinations of the corners: inside up to float rounding.
            const float slack = 1e-4f * (1.0f + std::abs(pixel.x) + std::abs(pixel.y));
            ASSERT_GE(pixel.x, rect.x - slack) << "box " << n;
            ASSERT_GE(pixel.y, rect.y - slack) << "box " << n;
            ASSERT_LE(pixel.x, rect.z + slack) << "box " << n;
            ASSERT_LE(pixel.y, rect.w + slack) << "box " << n;
            ASSERT_GE(ndc.z, nearest - 1e-6f) << "box " << n;
        }
        // The texels cover every pixel of the (clamped) rectangle, at most 2 x 2 of them.
        glm::uvec4 texels;
        const uint32_t level = gpu::hizTexels(rect, viewport, texels);
        ASSERT_LT(level, gpu::hizLevelCount(viewport));
        const glm::uvec2 levelSize = gpu::hizLevelSize(viewport, level);
        ASSERT_LE(texels.z - texels.x, 1u);
        ASSERT_LE(texels.w - texels.y, 1u);
        ASSERT_LT(texels.z, levelSize.x);
        ASSERT_LT(texels.w, levelSize.y);
        const glm::vec2 hi = glm::vec2(viewport) - 1.0f;
        const glm::uvec2 p0(glm::clamp(glm::vec2(rect.x, rect.y), glm::vec2(0.0f), hi));
        const glm::uvec2 p1(glm::clamp(glm::vec2(rect.z, rect.w), glm::vec2(0.0f), hi));
        const uint32_t span = 2u << level;
        ASSERT_LE(texels.x * span, p0.x);
        ASSERT_LE(texels.y * span, p0.y);
        ASSERT_GE((texels.z + 1) * span, p1.x + 1);
        ASSERT_GE((texels.w + 1) * span, p1.y + 1);
    }
    std::cout << "[ footprint ] " << projected << " boxes projected, " << rejected << " cross the near plane\n";
    EXPECT_GT(projected, 20000u);
    EXPECT_GT(rejected, 5000u);
}

}  // namespace
}  // namespace idk::test
