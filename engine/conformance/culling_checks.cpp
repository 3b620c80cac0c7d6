// culling_checks.cpp: the depth pyramids against direct CPU reductions, exactly, for odd, non-power-of-two, thin and
// tiny depth images (1x1 to 641x361, 2049x3, 1280x720):
// * "culling/hi-z pyramid" (the farthest-depth pyramid the GPU culling reads) on each rung of the "hiz-reduction"
//   ladder: fallback = culling/hiz_build.comp.glsl through passes::recordDepthPyramid (compute max of 2x2 loads,
//   six levels per dispatch from shared-memory tiles; also one and four levels per dispatch, the same texels),
//   native = passes::recordDepthPyramidMinmax (one MAX-reduction sample per 2x2 block), which must also equal the
//   compute rung bit for bit and, with a plain sampler in its place, must NOT reproduce the maximum (so the rung
//   cannot pass by sampling one texel); oracle render::buildDepthPyramid.
// * "ssr/closest-depth pyramid" (the SSR march's min pyramid, recordDepthPyramid with HizReduction::Closest) against
//   render::buildDepthPyramid with DepthReduction::Closest.
// Moved from tests/conformance/culling/{depth_pyramid,ssr_pyramid}_test.cpp, which keep the CPU-only layout and
// footprint tests. The culling kernel itself: cull_kernel_checks.cpp.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "conformance/conformance.hpp"
#include "passes/culling.hpp"
#include "passes/depth_pyramid_levels.hpp"
#include "render/depth_pyramid.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {
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

vk::Image floatImage(CheckEnv& env, glm::uvec2 size, VkImageUsageFlags usage, const char* name) {
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R32_SFLOAT;
    desc.extent = {size.x, size.y, 1};
    desc.usage = usage;
    desc.name = name;
    desc.category = "test";
    return env.ctx.createImage(desc);
}

// The compute rung (max or min) on a storage image.
std::vector<float> computePyramid(CheckEnv& env, const std::vector<float>& depth, glm::uvec2 size,
                                  passes::HizReduction reduction, uint32_t levelsPerDispatch = gpu::kHizTileLevels) {
    vk::Image image = floatImage(env, size, VK_IMAGE_USAGE_STORAGE_BIT, "check depth");
    vk::uploadImage(env.ctx, image, depth.data(), depth.size() * sizeof(float), VK_IMAGE_LAYOUT_GENERAL);
    vk::StorageImageIndex storage = env.ctx.bindless().addStorage(image.view);
    const uint32_t count = gpu::hizLevelOffset(size, gpu::hizLevelCount(size));
    vk::Buffer pyramid = env.ctx.createBuffer(
        {count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "check pyramid", "test"});
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        passes::recordDepthPyramidLevels(cmd, env.ctx, env.shaders, storage.value, size, pyramid.address, reduction,
                                         levelsPerDispatch);
    });
    std::vector<float> out = vk::downloadBuffer<float>(env.ctx, pyramid, count);
    env.ctx.bindless().release(storage);
    env.ctx.destroyDeferred(pyramid);
    env.ctx.destroyDeferred(image);
    return out;
}

// The sampler rung: the depth sampled through `sampler` (bindless index), one image per level.
std::vector<float> samplerPyramid(CheckEnv& env, const std::vector<float>& depth, glm::uvec2 size, uint32_t sampler) {
    constexpr VkImageUsageFlags kUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    vk::Image depthImage = floatImage(env, size, kUsage, "check depth");
    vk::uploadImage(env.ctx, depthImage, depth.data(), depth.size() * sizeof(float),
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const vk::SampledIndex depthSampled = env.ctx.bindless().addSampled(depthImage.view);
    std::vector<vk::Image> levels;
    std::vector<vk::SampledIndex> sampled;
    passes::HizMinmaxResources records;
    records.sampler = sampler;
    for (uint32_t level = 0; level < gpu::hizLevelCount(size); ++level) {
        levels.push_back(floatImage(env, gpu::hizLevelSize(size, level), kUsage, "check hiz level"));
        sampled.push_back(env.ctx.bindless().addSampled(levels.back().view));
        records.levels.push_back({levels.back().image, sampled.back().value});
    }
    const uint32_t count = gpu::hizLevelOffset(size, gpu::hizLevelCount(size));
    vk::Buffer pyramid = env.ctx.createBuffer({count * sizeof(float),
                                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                               vk::MemoryUsage::GpuOnly, "check pyramid", "test"});
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        passes::recordDepthPyramidMinmax(cmd, env.ctx, env.shaders, depthSampled.value, records, size, pyramid.buffer,
                                         pyramid.address);
    });
    std::vector<float> out = vk::downloadBuffer<float>(env.ctx, pyramid, count);
    env.ctx.bindless().release(depthSampled);
    for (size_t i = 0; i < levels.size(); ++i) {
        env.ctx.bindless().release(sampled[i]);
        env.ctx.destroyDeferred(levels[i]);
    }
    env.ctx.destroyDeferred(pyramid);
    env.ctx.destroyDeferred(depthImage);
    return out;
}

// Bitwise comparison (the reductions only select, never compute, so any difference is a wrong texel).
size_t differing(Verdict& v, const std::vector<float>& got, const std::vector<float>& want) {
    size_t wrong = 0;
    for (size_t i = 0; i < got.size(); ++i) {
        wrong += std::memcmp(&got[i], &want[i], sizeof(float)) != 0;
        v.recordError(std::abs(double(got[i]) - want[i]));
    }
    return wrong;
}

const glm::uvec2 kSizes[] = {{1, 1},     {2, 1},     {1, 7},     {7, 5},   {97, 61},
                             {128, 128}, {300, 17},  {255, 256}, {641, 361}, {2049, 3}, {1280, 720}};

vk::SamplerIndex addPyramidSampler(CheckEnv& env, VkFilter filter, VkSamplerReductionMode reduction) {
    vk::SamplerDesc desc;
    desc.filter = filter;
    desc.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    desc.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    desc.reduction = reduction;
    return env.ctx.bindless().addSampler(desc);
}

void hizPyramid(CheckEnv& env, Verdict& v) {
    const bool sampler = env.rung == vk::Rung::Native;
    const vk::SamplerIndex max =
        sampler ? addPyramidSampler(env, VK_FILTER_LINEAR, VK_SAMPLER_REDUCTION_MODE_MAX) : vk::SamplerIndex{};
    uint32_t seed = 1;
    for (glm::uvec2 size : kSizes) {
        const std::string what = std::to_string(size.x) + "x" + std::to_string(size.y);
        const std::vector<float> depth = randomDepth(size, seed++);
        const std::vector<float> expected = render::buildDepthPyramid(depth, size);
        const std::vector<float> compute = computePyramid(env, depth, size, passes::HizReduction::Farthest);
        const std::vector<float> got = sampler ? samplerPyramid(env, depth, size, max.value) : compute;
        // The last level is one texel holding the image's maximum (the oracle itself is right).
        v.expectEq(expected.back(), *std::max_element(depth.begin(), depth.end()), what + ": the oracle's top texel");
        if (!v.expectEq(got.size(), expected.size(), what + ": texel count")) continue;
        v.expectEq(differing(v, got, expected), size_t(0), what + ": texels differing from the CPU reduction");
        if (sampler) v.expectEq(differing(v, got, compute), size_t(0), what + ": texels differing from the compute rung");
        if (sampler) continue;
        // The compute rung reduces kHizTileLevels levels per dispatch from shared-memory tiles; one level per
        // dispatch (and any count between) must give the same texels.
        for (uint32_t perDispatch : {1u, 4u}) {
            const std::vector<float> levels = computePyramid(env, depth, size, passes::HizReduction::Farthest, perDispatch);
            v.expectEq(differing(v, levels, expected), size_t(0),
                       what + ": texels differing with " + std::to_string(perDispatch) + " level(s) per dispatch");
        }
    }
    if (!sampler) return;
    env.ctx.bindless().release(max);
    // The sampler really reduces: a plain (nearest) sampler at the same coordinates picks one texel of each 2x2
    // block, which differs from the maximum on random depth. (R32F linear filtering is optional, nearest is not.)
    const vk::SamplerIndex plain = addPyramidSampler(env, VK_FILTER_NEAREST, VK_SAMPLER_REDUCTION_MODE_WEIGHTED_AVERAGE);
    const glm::uvec2 size(97, 61);
    const std::vector<float> depth = randomDepth(size, 5);
    const std::vector<float> expected = render::buildDepthPyramid(depth, size);
    const std::vector<float> got = samplerPyramid(env, depth, size, plain.value);
    size_t wrong = 0;
    for (size_t i = 0; i < got.size(); ++i) wrong += got[i] != expected[i];
    v.expect(wrong > got.size() / 4, "a plain sampler reproduced the MAX reduction (" + std::to_string(wrong) + " of " +
                                         std::to_string(got.size()) + " texels differ): the rung test cannot fail");
    env.ctx.bindless().release(plain);
}

void closestPyramid(CheckEnv& env, Verdict& v) {
    const glm::uvec2 sizes[] = {{1, 1}, {2, 1}, {1, 7}, {7, 5}, {97, 61}, {300, 17}, {255, 256}};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (glm::uvec2 size : sizes) {
        const std::string what = std::to_string(size.x) + "x" + std::to_string(size.y);
        std::vector<float> depth(size_t(size.x) * size.y);
        for (float& d : depth) d = u(rng) < 0.2f ? 1.0f : u(rng);  // background holes
        const std::vector<float> expected = render::buildDepthPyramid(depth, size, render::DepthReduction::Closest);
        const std::vector<float> got = computePyramid(env, depth, size, passes::HizReduction::Closest);
        v.expectEq(expected.back(), *std::min_element(depth.begin(), depth.end()), what + ": the oracle's top texel");
        if (!v.expectEq(got.size(), expected.size(), what + ": texel count")) continue;
        v.expectEq(differing(v, got, expected), size_t(0), what + ": texels differing from the CPU minimum");
    }
}

}  // namespace

std::vector<Check> cullingChecks() {
    return {
        {"culling/hi-z pyramid", "hiz-reduction", "exact (sampler rung also bit-identical to the compute rung)",
         hizPyramid},
        {"ssr/closest-depth pyramid", "", "exact", closestPyramid},
    };
}

}  // namespace idk::conformance
