// vxgi_gl_fp16_test.cpp: the RGBA16F-image variant of VXGI's GL-interop rung ("vxgi-gl-accumulate" = native,
// GL_NV_shader_atomic_fp16_vector; passes/vxgi_gl_accumulate.hpp) on this machine's llvmpipe, which lacks the
// extension:
//  * the ladder does not offer it, names the missing extension, keeps the float-buffer program (fallback), and
//    refuses a forced native rung with that reason;
//  * the GL driver itself refuses the fp16 accumulation program, and the error names the extension;
//  * the resolve program (no extension needed) compiles and runs on llvmpipe's GL: RGBA16F sums and uint counts
//    written by GL clears, one voxel different from the rest, come out as the float sums layout the merge reads
//    (kVoxelSumWords per voxel, linear index x + n (y + n z)), exact (every value is an fp16 number).
// Not checked here (no driver exposes the extension): the f16vec4 imageAtomicAdd itself and the whole frame on
// this rung; tests/unit/shader/gl_sources_parse_test.cpp parses the program with glslang and stand-ins.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "gl_probed_context.hpp"
#include "gl/gl_compute.hpp"
#include "passes/vxgi_gl_accumulate.hpp"
#include "shared/vxgi_types.h"
#include "vk/context.hpp"

namespace idk::test {
namespace {

TEST(VxgiGlFp16Test, NotOfferedWithoutTheExtensionAndForcingItNamesIt) {
    auto ctx = glProbedContext();
    ASSERT_NE(ctx->glContext(), nullptr) << ctx->capabilities().glInteropNote;
    if (ctx->capabilities().glAtomicFp16Vector) GTEST_SKIP() << "this GL has GL_NV_shader_atomic_fp16_vector";
    const vk::Ladder& l = ctx->ladder("vxgi-gl-accumulate");
    ASSERT_EQ(l.options.size(), 2u);
    EXPECT_FALSE(l.options[0].available);
    EXPECT_EQ(l.options[0].note, "the OpenGL context lacks GL_NV_shader_atomic_fp16_vector");
    EXPECT_EQ(l.chosen, ctx->capabilities().glAtomicFloat ? vk::Rung::Fallback : l.options.back().rung);
    EXPECT_EQ(l.reason, "the OpenGL context lacks GL_NV_shader_atomic_fp16_vector");

    auto forced = glProbedContext({vk::RungForce{"vxgi-gl-accumulate", vk::Rung::Native}});
    EXPECT_EQ(forced->forcedRungError(),
              "--rung vxgi-gl-accumulate=native: the OpenGL context lacks GL_NV_shader_atomic_fp16_vector (rungs this "
              "device can run: vxgi-gl-accumulate=fallback)");
    EXPECT_EQ(forced->ladder("vxgi-gl-accumulate").chosen, vk::Rung::Fallback);
}

TEST(VxgiGlFp16Test, TheGlDriverRefusesTheFp16ProgramNamingTheExtension) {
    auto ctx = glProbedContext();
    ASSERT_NE(ctx->glContext(), nullptr) << ctx->capabilities().glInteropNote;
    if (ctx->capabilities().glAtomicFp16Vector) GTEST_SKIP() << "this GL has GL_NV_shader_atomic_fp16_vector";
    try {
        passes::VxgiGlAccumulator accumulator(*ctx, passes::VxgiGlProgram::Fp16Vector);
        ADD_FAILURE() << "the GL driver compiled a program requiring GL_NV_shader_atomic_fp16_vector without it";
    } catch (const gl::GlError& e) {
        const std::string what = e.what();
        std::printf("GL driver: %s\n", what.substr(0, 300).c_str());
        EXPECT_NE(what.find("vxgi_accumulate_fp16.comp.glsl"), std::string::npos) << what;
        EXPECT_NE(what.find("GL_NV_shader_atomic_fp16_vector"), std::string::npos) << what;
    }
    passes::VxgiGlAccumulator floatProgram(*ctx, passes::VxgiGlProgram::Float);  // the fallback builds
    EXPECT_EQ(floatProgram.program(), passes::VxgiGlProgram::Float);
}

std::string resolveSource() {
    std::ifstream file(std::filesystem::path(IDK_SOURCE_DIR) / "shaders_glsl/gl/vxgi_resolve_fp16.comp.glsl");
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

TEST(VxgiGlFp16Test, ResolveWritesTheSumsLayoutOnLlvmpipe) {
    auto ctx = glProbedContext();
    const gl::GlContext* gl = ctx->glContext();
    ASSERT_NE(gl, nullptr) << ctx->capabilities().glInteropNote;
    constexpr GLuint n = 6;  // not a multiple of the 4^3 group: the edge groups' bounds check runs
    const GLint special[3] = {3, 1, 5};
    // fp16 numbers: the sums read back as floats exactly.
    const GLfloat radiance[4] = {0.25f, 1.5f, 3.0f, 2.0f}, radianceSpecial[4] = {7.0f, -0.5f, 0.125f, 1.0f};
    const GLfloat facing[4] = {0.5f, -0.75f, 0.0f, 1.0f}, facingSpecial[4] = {-1.0f, 0.0f, 0.25f, 0.5f};
    const GLuint count = 2, countSpecial = 1;
    const uint32_t specialIndex = uint32_t(special[0]) + n * (uint32_t(special[1]) + n * uint32_t(special[2]));
    std::vector<float> sums(size_t(n) * n * n * gpu::kVoxelSumWords, -99.0f);
    {
        gl::GlContext::Current current(*gl);
        const gl::Api& api = gl->api();
        gl::ComputeProgram resolve(*gl, "gl/vxgi_resolve_fp16.comp.glsl", resolveSource());
        GLuint textures[2] = {0, 0}, buffers[2] = {0, 0};
        api.glCreateTextures(GL_TEXTURE_3D, 2, textures);
        api.glCreateBuffers(2, buffers);
        for (GLuint t : textures) api.glTextureStorage3D(t, 1, GL_RGBA16F, n, n, n);
        api.glClearTexImage(textures[0], 0, GL_RGBA, GL_FLOAT, radiance);
        api.glClearTexImage(textures[1], 0, GL_RGBA, GL_FLOAT, facing);
        api.glClearTexSubImage(textures[0], 0, special[0], special[1], special[2], 1, 1, 1, GL_RGBA, GL_FLOAT,
                               radianceSpecial);
        api.glClearTexSubImage(textures[1], 0, special[0], special[1], special[2], 1, 1, 1, GL_RGBA, GL_FLOAT,
                               facingSpecial);
        std::vector<GLuint> counts(size_t(n) * n * n, count);
        counts[specialIndex] = countSpecial;
        api.glNamedBufferStorage(buffers[0], GLsizeiptr(counts.size() * 4), counts.data(), 0);
        api.glNamedBufferStorage(buffers[1], GLsizeiptr(sums.size() * 4), sums.data(), GL_DYNAMIC_STORAGE_BIT);
        api.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[0]);
        api.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers[1]);
        for (GLuint i = 0; i < 2; ++i) api.glBindImageTexture(i, textures[i], 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
        resolve.setUint("gridSize", n);
        resolve.dispatch(2, 2, 2);
        api.glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(sums.size() * 4), sums.data());
        api.glDeleteTextures(2, textures);
        api.glDeleteBuffers(2, buffers);
        gl->check("resolve test");
    }
    size_t wrong = 0;
    for (uint32_t v = 0; v < n * n * n; ++v) {
        const bool s = v == specialIndex;
        const float* r = s ? radianceSpecial : radiance;
        const float* f = s ? facingSpecial : facing;
        const float* got = &sums[size_t(v) * gpu::kVoxelSumWords];
        for (int c = 0; c < 4; ++c) wrong += got[c] != r[c] ? 1 : 0;
        for (int c = 0; c < 4; ++c) wrong += got[4 + c] != f[c] ? 1 : 0;
        wrong += got[gpu::kVoxelSumCount] != float(s ? countSpecial : count) ? 1 : 0;
        if (wrong && wrong < 4) ADD_FAILURE() << "voxel " << v << " resolved wrongly";
    }
    EXPECT_EQ(wrong, 0u);
}

}  // namespace
}  // namespace idk::test
