// gl_sync_test.cpp: the GL-interop hand-off (gl/gl_sync.hpp). The mode choice on fake capability sets: semaphores
// only where GL has GL_EXT_semaphore_fd and the device VK_KHR_external_semaphore_fd, IDK_GL_SYNC=cpu forces the
// CPU-side waits, a bad value is refused with its name. On the probed context: the mode agrees with what the
// device and GL offer and `idk info`'s note states it (llvmpipe: CPU-side waits, GL lacks the extension), and a
// Vulkan -> GL -> Vulkan round trip through the four HandOff steps is exact and validation-clean in that mode.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "gl_probed_context.hpp"
#include "gl/gl_compute.hpp"
#include "gl/gl_sync.hpp"
#include "gl/shared_memory.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

#include "gl_modify_kernel.hpp"

namespace idk::test {
namespace {

using gl::SyncCapabilities;
using gl::SyncMode;

TEST(GlInteropSyncTest, SemaphoresOnlyWhereBothApisHaveThem) {
    for (const char* override : {static_cast<const char*>(nullptr), "auto"}) {
        EXPECT_EQ(gl::chooseSyncMode({true, true}, override).mode, SyncMode::Semaphores);
        const gl::SyncChoice noGl = gl::chooseSyncMode({true, false}, override);
        EXPECT_EQ(noGl.mode, SyncMode::CpuWait);
        EXPECT_EQ(noGl.why, "GL lacks GL_EXT_semaphore_fd");
        const gl::SyncChoice noVk = gl::chooseSyncMode({false, true}, override);
        EXPECT_EQ(noVk.mode, SyncMode::CpuWait);
        EXPECT_NE(noVk.why.find("VK_KHR_external_semaphore_fd"), std::string::npos) << noVk.why;
        const gl::SyncChoice neither = gl::chooseSyncMode({false, false}, override);
        EXPECT_EQ(neither.mode, SyncMode::CpuWait);
        EXPECT_NE(neither.why.find("GL_EXT_semaphore_fd"), std::string::npos) << neither.why;
        EXPECT_NE(neither.why.find("VK_KHR_external_semaphore_fd"), std::string::npos) << neither.why;
    }
    EXPECT_EQ(gl::syncText(gl::chooseSyncMode({true, true}, nullptr)),
              "semaphores (GL_EXT_semaphore_fd + VK_KHR_external_semaphore_fd)");
    EXPECT_EQ(gl::syncText(gl::chooseSyncMode({true, false}, nullptr)), "CPU-side waits (GL lacks GL_EXT_semaphore_fd)");
}

TEST(GlInteropSyncTest, EnvironmentForcesCpuWaitsAndRefusesUnknownValues) {
    for (const SyncCapabilities caps : {SyncCapabilities{true, true}, SyncCapabilities{false, false}}) {
        const gl::SyncChoice forced = gl::chooseSyncMode(caps, "cpu");
        EXPECT_EQ(forced.mode, SyncMode::CpuWait);
        EXPECT_EQ(forced.why, "forced by IDK_GL_SYNC=cpu");
    }
    const gl::SyncChoice bad = gl::chooseSyncMode({true, true}, "semaphore");
    EXPECT_EQ(bad.mode, SyncMode::CpuWait);
    EXPECT_NE(bad.why.find("IDK_GL_SYNC=semaphore"), std::string::npos) << bad.why;
}

TEST(GlInteropSyncTest, ProbedModeMatchesTheDeviceAndIsStated) {
    auto ctx = glProbedContext();
    const gl::GlContext* gl = ctx->glContext();
    ASSERT_NE(gl, nullptr) << ctx->capabilities().glInteropNote;
    const SyncCapabilities caps = gl::querySyncCapabilities(*ctx, *gl);
    const char* env = std::getenv("IDK_GL_SYNC");
    EXPECT_EQ(gl->sync().mode, gl::chooseSyncMode(caps, env).mode);
    EXPECT_NE(ctx->capabilities().glInteropNote.find("sync: " + gl::syncText(gl->sync())), std::string::npos)
        << ctx->capabilities().glInteropNote;
    if (gl->renderer().find("llvmpipe") != std::string::npos) {
        // llvmpipe has GL_EXT_memory_object_fd but not GL_EXT_semaphore_fd: the rung runs on CPU-side waits.
        EXPECT_FALSE(caps.glSemaphoreFd);
        EXPECT_EQ(gl->sync().mode, SyncMode::CpuWait);
        if (!env) {
            EXPECT_NE(gl->sync().why.find("GL lacks GL_EXT_semaphore_fd"), std::string::npos) << gl->sync().why;
        }
    }
}


TEST(GlInteropSyncTest, HandOffRoundTripIsExactInTheProbedMode) {
    auto ctx = glProbedContext();
    const gl::GlContext* gl = ctx->glContext();
    ASSERT_NE(gl, nullptr) << ctx->capabilities().glInteropNote;
    const uint32_t width = 16, height = 8, count = width * height;
    gl::SharedImage image(*ctx, *gl, VK_FORMAT_R8G8B8A8_UNORM, width, height, VK_IMAGE_USAGE_STORAGE_BIT, "sync image");
    gl::SharedBuffer buffer(*ctx, *gl, count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "sync buffer");
    std::vector<uint8_t> texels(size_t(count) * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t(i * 29 + 3);
    std::vector<uint32_t> values(count);
    for (uint32_t i = 0; i < count; ++i) values[i] = i * 2654435761u + 5;
    vk::uploadImage(*ctx, image.vk(), texels.data(), texels.size(), VK_IMAGE_LAYOUT_GENERAL);
    vk::uploadBuffer(*ctx, buffer.vk(), std::span<const uint32_t>(values));

    // Two hand-offs on one HandOff: the binary semaphores (where used) alternate signal and wait each time.
    gl::HandOff handOff(*ctx, *gl, "sync test");
    const GLuint buffers[1] = {buffer.gl()}, textures[1] = {image.gl()};
    {
        gl::GlContext::Current current(*gl);
        EXPECT_THROW(handOff.glBegin(buffers, textures), std::logic_error);  // before Vulkan handed anything over
    }
    std::unique_ptr<gl::ComputeProgram> program;
    {
        gl::GlContext::Current current(*gl);
        program = std::make_unique<gl::ComputeProgram>(*gl, "sync round trip", kModify);
    }
    for (int round = 0; round < 2; ++round) {
        handOff.submitToGl([&](VkCommandBuffer cmd) {
            gl::releaseToGl(cmd, *ctx, image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT);
            gl::releaseToGl(cmd, *ctx, buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        });
        {
            gl::GlContext::Current current(*gl);
            handOff.glBegin(buffers, textures);
            program->setUint("count", count);
            gl->api().glBindImageTexture(0, image.gl(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
            gl->api().glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffer.gl());
            program->dispatch(width / 8, height / 8);
            handOff.glEnd(buffers, textures);
        }
        ctx->runImmediate([&](VkCommandBuffer cmd) {
            handOff.resumeVulkan(cmd, [&](VkCommandBuffer c) {
                gl::acquireFromGl(c, *ctx, image, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
                gl::acquireFromGl(c, *ctx, buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
            });
        });
        for (uint8_t& t : texels) t = uint8_t(255 - t);
        for (uint32_t i = 0; i < count; ++i) values[i] = values[i] * 3u + i;
    }
    {
        gl::GlContext::Current current(*gl);
        program.reset();
    }
    EXPECT_EQ(vk::readbackImage(*ctx, image.vk(), VK_IMAGE_LAYOUT_GENERAL), texels);
    std::vector<uint32_t> back(count);
    vk::downloadBuffer(*ctx, buffer.vk(), back.data(), back.size() * 4);
    EXPECT_EQ(back, values);
    EXPECT_EQ(ctx->validationErrors(), 0u);
    for (const std::string& m : ctx->validationMessages()) ADD_FAILURE() << m;
}

}  // namespace
}  // namespace idk::test
