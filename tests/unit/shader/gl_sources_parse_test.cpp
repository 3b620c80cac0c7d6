// gl_sources_parse_test.cpp: the OpenGL compute sources of the GL-interop rung (shaders_glsl/gl/, compiled by the GL
// driver at run time, so the build never compiles them) parse as OpenGL GLSL 4.50 with glslang. glslang knows
// neither GL_NV_shader_atomic_fp16_vector nor GL_NV_gpu_shader5, and no driver here exposes them (llvmpipe: see
// tests/conformance/gl/vxgi_gl_fp16_test.cpp), so vxgi_accumulate_fp16.comp is parsed with stand-ins: its f16vec4
// types from GL_EXT_shader_explicit_arithmetic_types_float16 and its imageAtomicAdd(image, coord, f16vec4) as a
// load + add + store macro. That checks everything but the atomic's own signature (image format, coordinate type
// and the vector type are still checked by imageLoad/imageStore). The resolve program needs no extension and
// parses as it is. A deliberately broken copy shows the check fails.
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

std::string readSource(const char* name) {
    const std::filesystem::path path = std::filesystem::path(IDK_SOURCE_DIR) / "shaders_glsl" / "gl" / name;
    std::ifstream file(path);
    if (!file) throw std::runtime_error(path.string() + ": cannot open");
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

void replace(std::string& text, const std::string& what, const std::string& with) {
    const size_t at = text.find(what);
    ASSERT_NE(at, std::string::npos) << "'" << what << "' not in the source";
    text.replace(at, what.size(), with);
}

// Empty when the source parses as an OpenGL 4.50 compute shader, else glslang's log.
std::string parseGl(const std::string& source) {
    static const bool initialised = glslang::InitializeProcess();
    (void)initialised;
    glslang::TShader shader(EShLangCompute);
    const char* text = source.c_str();
    shader.setStrings(&text, 1);
    // No client/target environment: plain OpenGL GLSL as a GL driver reads it (the SPIR-V-for-GL rules would ask
    // for explicit uniform locations), as `glslangValidator -S comp` checks it.
    if (shader.parse(GetDefaultResources(), 450, false, EShMsgDefault)) return "";
    return shader.getInfoLog();
}

std::string fp16WithStandIns(std::string source) {
    replace(source, "#extension GL_NV_gpu_shader5 : require",
            "#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require");
    replace(source, "#extension GL_NV_shader_atomic_fp16_vector : require",
            "#define imageAtomicAdd(image, p, value) imageStore(image, p, imageLoad(image, p) + vec4(value))");
    return source;
}

TEST(GlSourcesParse, ResolveProgramParses) {
    const std::string log = parseGl(readSource("vxgi_resolve_fp16.comp.glsl"));
    EXPECT_TRUE(log.empty()) << log;
}

TEST(GlSourcesParse, Fp16AccumulateParsesWithStandInsForTheNvExtensions) {
    const std::string source = readSource("vxgi_accumulate_fp16.comp.glsl");
    EXPECT_NE(parseGl(source).find("GL_NV"), std::string::npos) << "glslang learnt the NV extensions: drop the stand-ins";
    const std::string log = parseGl(fp16WithStandIns(source));
    EXPECT_TRUE(log.empty()) << log;
    std::string broken = fp16WithStandIns(source);
    replace(broken, "imageAtomicAdd(facingSums, p, facing);", "imageAtomicAdd(facingSums, p.xy, facing);");
    EXPECT_FALSE(parseGl(broken).empty()) << "a 2D coordinate on a 3D image must not parse";
}

}  // namespace
