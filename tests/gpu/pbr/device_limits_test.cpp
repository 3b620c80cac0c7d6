// device_limits_test.cpp: a scene or a resource too large for the device is a DeviceLimitError naming the resource
// and the limit (maxBufferSize, maxStorageBufferRange, maxImageDimension2D), never a validation error or a crash.
// The device pretends to have small limits (ContextDesc::limitOverrides) so the test needs no 128 MiB scene; the
// same calls within the limits succeed, and the validation layer reports nothing.
#include <gtest/gtest.h>

#include <string>

#include "render/gpu_scene.hpp"
#include "scene/gltf_loader.hpp"
#include "vk/bindless.hpp"
#include "vk/context.hpp"

namespace idk {
namespace {

template <class F>
void expectLimitError(F call, const std::string& resource, const std::string& limit) {
    try {
        call();
        ADD_FAILURE() << "no DeviceLimitError for " << resource;
    } catch (const vk::DeviceLimitError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(resource), std::string::npos) << what;
        EXPECT_NE(what.find("the device's " + limit), std::string::npos) << what;
    }
}

TEST(DeviceLimits, TooLargeForTheDeviceIsAnErrorNamingTheLimit) {
    vk::ContextDesc desc;
    desc.validation = true;
    desc.limitOverrides.maxBufferSize = 1024;
    desc.limitOverrides.maxStorageBufferRange = 512;
    desc.limitOverrides.maxImageDimension2D = 64;
    vk::Context ctx(desc);
    EXPECT_EQ(ctx.info().maxBufferSize, 1024u);

    vk::BufferDesc big{.size = 4096, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "test big"};
    expectLimitError([&] { (void)ctx.createBuffer(big); }, "buffer 'test big' needs 4096 bytes", "maxBufferSize (1024)");

    vk::BufferDesc fits{.size = 1024, .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, .name = "test fits"};
    vk::Buffer buffer = ctx.createBuffer(fits);
    expectLimitError([&] { (void)ctx.bindless().addBuffer(buffer.buffer, buffer.size, buffer.name); },
                     "storage buffer 'test fits' needs 1024 bytes", "maxStorageBufferRange (512)");
    ctx.destroy(buffer);

    vk::ImageDesc wide{.extent = {128, 16, 1}, .usage = VK_IMAGE_USAGE_SAMPLED_BIT, .name = "test wide"};
    expectLimitError([&] { (void)ctx.createImage(wide); }, "image 'test wide' (128x16)", "maxImageDimension2D (64)");
    vk::ImageDesc small{.extent = {64, 16, 1}, .usage = VK_IMAGE_USAGE_SAMPLED_BIT, .name = "test small"};
    vk::Image image = ctx.createImage(small);
    ctx.destroy(image);

    // A whole scene: the Cornell box's GPU buffers are larger than 1 KiB.
    const scene::Scene cornell = scene::loadGltf(std::filesystem::path(IDK_SOURCE_DIR) / "scenes/cornell_box.gltf");
    expectLimitError([&] { render::GpuScene gpu(ctx, cornell); }, "buffer 'scene ", "maxBufferSize (1024)");
    // The failed constructor released what it had created (its placeholder textures): nothing is left.
    ctx.waitIdle();
    ctx.collectGarbage();
    for (const auto& [category, bytes] : ctx.allocator().stats().bytesByCategory)
        EXPECT_EQ(bytes, 0u) << category << " still allocated after the failed upload";
    EXPECT_EQ(ctx.validationErrors(), 0u);
}

}  // namespace
}  // namespace idk
