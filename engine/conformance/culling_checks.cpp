// culling_checks.cpp: the Hi-Z depth pyramid the GPU culling reads (culling/hiz_build.comp.glsl through
// passes::recordDepthPyramid) against a direct CPU max-reduction (render::buildDepthPyramid), exactly, for odd,
// non-power-of-two, thin and tiny depth images (1x1 to 640x360). Moved from tests/conformance/culling/, which keeps
// the CPU-only layout and footprint tests. The cull kernel and meshlet tests are not registered yet.
#include <algorithm>
#include <cmath>
#include <random>

#include "conformance/conformance.hpp"
#include "passes/culling.hpp"
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

std::vector<float> gpuPyramid(CheckEnv& env, const std::vector<float>& depth, glm::uvec2 size) {
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R32_SFLOAT;
    desc.extent = {size.x, size.y, 1};
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    desc.name = "check depth";
    desc.category = "test";
    vk::Image image = env.ctx.createImage(desc);
    vk::uploadImage(env.ctx, image, depth.data(), depth.size() * sizeof(float), VK_IMAGE_LAYOUT_GENERAL);
    vk::StorageImageIndex storage = env.ctx.bindless().addStorage(image.view);
    const uint32_t count = gpu::hizLevelOffset(size, gpu::hizLevelCount(size));
    vk::Buffer pyramid = env.ctx.createBuffer(
        {count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "check pyramid", "test"});
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        passes::recordDepthPyramid(cmd, env.ctx, env.shaders, storage.value, size, pyramid.address);
    });
    std::vector<float> out = vk::downloadBuffer<float>(env.ctx, pyramid, count);
    env.ctx.bindless().release(storage);
    env.ctx.destroyDeferred(pyramid);
    env.ctx.destroyDeferred(image);
    return out;
}

void hizPyramid(CheckEnv& env, Verdict& v) {
    const glm::uvec2 sizes[] = {{1, 1}, {2, 1}, {1, 7}, {7, 5}, {97, 61}, {128, 128}, {300, 17}, {255, 256}, {640, 360}};
    uint32_t seed = 1;
    for (glm::uvec2 size : sizes) {
        const std::string what = std::to_string(size.x) + "x" + std::to_string(size.y);
        const std::vector<float> depth = randomDepth(size, seed++);
        const std::vector<float> expected = render::buildDepthPyramid(depth, size);
        const std::vector<float> got = gpuPyramid(env, depth, size);
        if (!v.expectEq(got.size(), expected.size(), what + ": texel count")) continue;
        size_t wrong = 0;
        for (size_t i = 0; i < got.size(); ++i) {
            wrong += got[i] != expected[i];
            v.recordError(std::abs(double(got[i]) - expected[i]));
        }
        v.expectEq(wrong, size_t(0), what + ": texels differing from the CPU reduction");
        // The last level is one texel holding the image's maximum (the oracle itself is right).
        v.expectEq(expected.back(), *std::max_element(depth.begin(), depth.end()), what + ": the oracle's top texel");
    }
}

}  // namespace

std::vector<Check> cullingChecks() {
    return {{"culling/hi-z pyramid", "", "exact", hizPyramid}};
}

}  // namespace idk::conformance
