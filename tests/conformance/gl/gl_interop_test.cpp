// gl_interop_test.cpp: the GL-interop rung's memory sharing. An RGBA8 image and a uint buffer are written by
// Vulkan, read and modified by a GL compute shader, and read back by Vulkan: exact against the CPU oracle, with
// no validation message (the ownership transfers and CPU-side waits of shared_memory.hpp are the ordering). And
// the "no GL" path: with EGL disabled the rung is absent with the reason, and the other rungs are unaffected.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include "gl_probed_context.hpp"
#include "gl/gl_compute.hpp"
#include "gl/interop_probe.hpp"
#include "gl/shared_memory.hpp"
#include "render/float_splat.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

#include "gl_modify_kernel.hpp"

namespace idk::test {
namespace {

void expectNoValidationErrors(const vk::Context& ctx) {
    EXPECT_EQ(ctx.validationErrors(), 0u);
    for (const std::string& m : ctx.validationMessages()) ADD_FAILURE() << m;
}


TEST(GlInteropTest, ImageAndBufferRoundTripThroughGlComputeAreExact) {
    auto ctx = glProbedContext();
    const gl::GlContext* gl = ctx->glContext();
    ASSERT_NE(gl, nullptr) << ctx->capabilities().glInteropNote;
    const uint32_t width = 24, height = 16, count = width * height;

    gl::SharedImage image(*ctx, *gl, VK_FORMAT_R8G8B8A8_UNORM, width, height, VK_IMAGE_USAGE_STORAGE_BIT, "rt image");
    gl::SharedBuffer buffer(*ctx, *gl, count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "rt buffer");
    std::vector<uint8_t> texels(size_t(count) * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t(i * 37 + 11);
    std::vector<uint32_t> values(count);
    for (uint32_t i = 0; i < count; ++i) values[i] = i * 1000003u + 7;

    vk::uploadImage(*ctx, image.vk(), texels.data(), texels.size(), VK_IMAGE_LAYOUT_GENERAL);
    vk::uploadBuffer(*ctx, buffer.vk(), std::span<const uint32_t>(values));
    ctx->runImmediate([&](VkCommandBuffer cmd) {
        gl::releaseToGl(cmd, *ctx, image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                        VK_ACCESS_2_TRANSFER_WRITE_BIT);
        gl::releaseToGl(cmd, *ctx, buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });
    {
        gl::GlContext::Current current(*gl);
        gl::ComputeProgram program(*gl, "round trip", kModify);
        program.setUint("count", count);
        gl->api().glBindImageTexture(0, image.gl(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
        gl->api().glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffer.gl());
        program.dispatch(width / 8, height / 8);
        gl::finishGl(*gl);
    }
    ctx->runImmediate([&](VkCommandBuffer cmd) {
        gl::acquireFromGl(cmd, *ctx, image, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        gl::acquireFromGl(cmd, *ctx, buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    });
    std::vector<uint8_t> gotTexels = vk::readbackImage(*ctx, image.vk(), VK_IMAGE_LAYOUT_GENERAL);
    std::vector<uint32_t> gotValues = vk::downloadBuffer<uint32_t>(*ctx, buffer.vk(), count);
    ASSERT_EQ(gotTexels.size(), texels.size());
    for (size_t i = 0; i < texels.size(); ++i) ASSERT_EQ(gotTexels[i], 255 - texels[i]) << "texel byte " << i;
    for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(gotValues[i], values[i] * 3u + i) << "value " << i;
    expectNoValidationErrors(*ctx);
}

TEST(GlInteropTest, ProbeRoundTripPassesAndTheRungIsOffered) {
    auto ctx = glProbedContext();
    ASSERT_NE(ctx->glContext(), nullptr) << ctx->capabilities().glInteropNote;
    EXPECT_EQ(gl::roundTrip(*ctx, *ctx->glContext(), 13, 7), "");  // odd sizes: no row padding assumption
    EXPECT_NE(ctx->capabilities().glInteropNote.find("sync:"), std::string::npos);
    // llvmpipe has GL_NV_shader_atomic_float: the float-atomics ladder offers its GL rung exactly when GL has it.
    if (ctx->glContext()->renderer().find("llvmpipe") != std::string::npos) {
        EXPECT_TRUE(ctx->capabilities().glAtomicFloat);
    }
    for (const vk::RungOption& o : ctx->ladder("float-atomics").options) {
        if (o.rung != vk::Rung::GlInterop) continue;
        EXPECT_EQ(o.available, ctx->capabilities().glAtomicFloat) << o.note;
    }
    expectNoValidationErrors(*ctx);
}

// --rung float-atomics=gl-interop makes the ladder's own choice the GL pass even though the device has native
// float atomics: the graph's splat pass runs in GL and its Vulkan consumer (the sum) reads the result.
TEST(GlInteropTest, ForcedGlRungRunsTheGlPassWhoseOutputVulkanConsumes) {
    auto ctx = glProbedContext({vk::RungForce{"float-atomics", vk::Rung::GlInterop}});
    ASSERT_TRUE(ctx->forcedRungError().empty()) << ctx->forcedRungError();
    vk::ShaderLibrary shaders(*ctx);
    render::SplatInput input;
    input.binCount = 16;
    for (uint32_t i = 0; i < 4000; ++i) {
        input.bins.push_back(i % 3 == 0 ? 5u : (i * 7) % 17);  // bin 16 is out of range: dropped
        input.values.push_back(float(i % 13) * 0.25f);
    }
    const render::SplatResult got = render::runSplatGraph(*ctx, shaders, input);
    const render::SplatResult want = render::splatOracle(input);
    EXPECT_EQ(got.rung, vk::Rung::GlInterop);
    EXPECT_EQ(got.bins, want.bins);
    EXPECT_EQ(got.total, want.total);
    const std::vector<vk::Ladder> ran = ctx->consultedLadders();
    ASSERT_EQ(ran.size(), 1u);
    EXPECT_EQ(ran[0].chosen, vk::Rung::GlInterop);
    // Without the forcing the device takes its own best rung (native float atomics on lavapipe), with the same bits.
    auto native = glProbedContext();
    vk::ShaderLibrary nativeShaders(*native);
    const render::SplatResult nat = render::runSplatGraph(*native, nativeShaders, input);
    EXPECT_NE(nat.rung, vk::Rung::GlInterop);
    EXPECT_EQ(nat.rung, native->ladder("float-atomics").chosen);
    EXPECT_EQ(nat.bins, got.bins);
    expectNoValidationErrors(*ctx);
    expectNoValidationErrors(*native);
}

TEST(GlInteropTest, WithoutEglTheRungIsAbsentWithTheReasonAndOtherRungsRun) {
    ::setenv("IDK_GL_INTEROP", "off", 1);
    auto ctx = glProbedContext({vk::RungForce{"float-atomics", vk::Rung::GlInterop}});
    ::unsetenv("IDK_GL_INTEROP");
    EXPECT_EQ(ctx->glContext(), nullptr);
    EXPECT_FALSE(ctx->capabilities().glInterop);
    EXPECT_NE(ctx->capabilities().glInteropNote.find("IDK_GL_INTEROP=off"), std::string::npos);
    const vk::Ladder& ladder = ctx->ladder("float-atomics");
    for (const vk::RungOption& o : ladder.options) {
        if (o.rung != vk::Rung::GlInterop) continue;
        EXPECT_FALSE(o.available);
        EXPECT_NE(o.note.find("IDK_GL_INTEROP=off"), std::string::npos) << o.note;
    }
    EXPECT_NE(ladder.chosen, vk::Rung::GlInterop);
    // The forced GL rung is refused, naming why and what the device can run instead.
    EXPECT_NE(ctx->forcedRungError().find("IDK_GL_INTEROP=off"), std::string::npos) << ctx->forcedRungError();
    EXPECT_NE(ctx->forcedRungError().find("float-atomics=native|fallback"), std::string::npos) << ctx->forcedRungError();
    expectNoValidationErrors(*ctx);
}

}  // namespace
}  // namespace idk::test
