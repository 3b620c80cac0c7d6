// glsl_compiler_test.cpp: checks idk::shader::compileGlsl on files written to a scratch folder: valid shaders,
// errors that name the file and line, include resolution (next to the includer, then include dirs), defines,
// debug info, stage detection, and concurrent compiles. Also readSpirvFile's error messages.
#include "shader/glsl_compiler.hpp"
#include "shader/spirv_file.hpp"
#include "shader/spirv_reflect.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <thread>

using namespace idk::shader;
namespace fs = std::filesystem;

namespace {

// A scratch folder per test, removed afterwards.
class ScratchDir {
public:
    ScratchDir() {
        const auto* test = testing::UnitTest::GetInstance()->current_test_info();
        std::random_device rd;
        path_ = fs::temp_directory_path() /
                ("idk_shader_" + std::string(test->name()) + "_" + std::to_string(rd()));
        fs::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    fs::path write(const fs::path& relative, const std::string& text) const {
        const fs::path p = path_ / relative;
        fs::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

const char* kValidCompute = R"(#version 460
layout(local_size_x = 16, local_size_y = 4) in;
layout(push_constant) uniform Push { uint count; float scale; } pc;
layout(set = 0, binding = 3) buffer Data { float values[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < pc.count) values[i] *= pc.scale;
}
)";

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

}  // namespace

TEST(GlslCompiler, CompilesFileAndReflectionMatches) {
    ScratchDir dir;
    const fs::path file = dir.write("scale.comp.glsl", kValidCompute);
    CompileRequest request;
    request.path = file;  // stage from the ".comp.glsl" extension
    const CompileResult result = compileGlsl(request);
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(result.spirv[0], 0x07230203u);
    EXPECT_TRUE(result.includedFiles.empty());

    const ShaderInfo info = reflectSpirv(result.spirv);
    EXPECT_EQ(info.stage, ShaderStage::Compute);
    EXPECT_EQ(info.localSize, (std::array<uint32_t, 3>{16, 4, 1}));
    EXPECT_EQ(info.pushConstantBytes, 8u);
    EXPECT_EQ(info.descriptorSetMask, 1u);
    ASSERT_EQ(info.bindings.size(), 1u);
    EXPECT_EQ(info.bindings[0].binding, 3u);
    EXPECT_EQ(info.spirvVersion, 0x00010600u);
}

TEST(GlslCompiler, SyntaxErrorNamesFileAndLine) {
    ScratchDir dir;
    const fs::path file = dir.write("broken.comp", "#version 460\n"
                                                   "layout(local_size_x = 1) in;\n"
                                                   "void main() {\n"
                                                   "    uint x = undefinedThing + 1u;\n"
                                                   "}\n");
    CompileRequest request;
    request.path = file;
    CompileResult result;
    ASSERT_NO_THROW(result = compileGlsl(request));
    EXPECT_FALSE(result.ok());
    EXPECT_TRUE(result.spirv.empty());
    EXPECT_TRUE(contains(result.error, file.string())) << result.error;
    EXPECT_TRUE(contains(result.error, file.string() + ":4:")) << result.error;
    EXPECT_TRUE(contains(result.error, "undefinedThing")) << result.error;
}

TEST(GlslCompiler, ErrorInsideIncludeNamesTheHeader) {
    ScratchDir dir;
    dir.write("include/bad.h", "// line 1\nfloat broken( {\n");
    const fs::path file = dir.write("main.comp", "#version 460\n"
                                                 "#extension GL_GOOGLE_include_directive : require\n"
                                                 "#include \"bad.h\"\n"
                                                 "layout(local_size_x = 1) in;\n"
                                                 "void main() {}\n");
    CompileRequest request;
    request.path = file;
    request.includeDirs = {dir.path() / "include"};
    const CompileResult result = compileGlsl(request);
    EXPECT_FALSE(result.ok());
    EXPECT_TRUE(contains(result.error, "bad.h:2:")) << result.error;
}

TEST(GlslCompiler, MissingIncludeIsNamed) {
    ScratchDir dir;
    const fs::path file = dir.write("needs.frag", "#version 460\n"
                                                  "#extension GL_GOOGLE_include_directive : require\n"
                                                  "#include \"does_not_exist.h\"\n"
                                                  "layout(location = 0) out vec4 color;\n"
                                                  "void main() { color = vec4(1.0); }\n");
    CompileRequest request;
    request.path = file;
    request.includeDirs = {dir.path() / "nowhere"};
    const CompileResult result = compileGlsl(request);
    EXPECT_FALSE(result.ok());
    EXPECT_TRUE(contains(result.error, "does_not_exist.h")) << result.error;
    EXPECT_TRUE(contains(result.error, file.string() + ":3:")) << result.error;
    EXPECT_TRUE(contains(result.error, (dir.path() / "nowhere").string())) << result.error;
}

TEST(GlslCompiler, IncludesResolveNextToIncluderFirstThenIncludeDirs) {
    ScratchDir dir;
    // "common.h" exists both next to the shader and in the include dir: the local one must win.
    dir.write("shaders/common.h", "#include \"sub/nested.h\"\nconst uint kLocal = 5u;\n");
    dir.write("shaders/sub/nested.h", "#include \"sibling.h\"\n");          // relative to sub/
    dir.write("shaders/sub/sibling.h", "const uint kSibling = 7u;\n");
    dir.write("include/common.h", "#error wrong common.h\n");
    dir.write("include/shared.h", "const uint kShared = 11u;\n");
    const fs::path file = dir.write("shaders/use.comp", "#version 460\n"
                                                        "#extension GL_GOOGLE_include_directive : require\n"
                                                        "#include \"common.h\"\n"
                                                        "#include <shared.h>\n"
                                                        "layout(local_size_x = kLocal + kSibling + kShared) in;\n"
                                                        "void main() {}\n");
    CompileRequest request;
    request.path = file;
    request.includeDirs = {dir.path() / "include"};
    const CompileResult result = compileGlsl(request);
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(reflectSpirv(result.spirv).localSize[0], 23u);
    ASSERT_EQ(result.includedFiles.size(), 4u);
    EXPECT_EQ(result.includedFiles[0], (dir.path() / "shaders/common.h").lexically_normal());
    EXPECT_EQ(result.includedFiles[3], (dir.path() / "include/shared.h").lexically_normal());
}

TEST(GlslCompiler, DefinesChangeTheOutput) {
    const std::string source = "#version 460\n"
                               "layout(local_size_x = GROUP) in;\n"
                               "#ifdef WITH_PUSH\n"
                               "layout(push_constant) uniform Push { vec4 v; } pc;\n"
                               "layout(set = 0, binding = 0) buffer Out { float r[]; };\n"
                               "#endif\n"
                               "void main() {\n"
                               "#ifdef WITH_PUSH\n"
                               "    r[0] = pc.v.x;\n"
                               "#endif\n"
                               "}\n";
    CompileRequest request;
    request.path = "virtual/defines.comp";
    request.source = source;
    request.defines = {{"GROUP", "32"}};
    const CompileResult small = compileGlsl(request);
    ASSERT_TRUE(small.ok()) << small.error;
    request.defines = {{"GROUP", "128"}, {"WITH_PUSH", ""}};
    const CompileResult large = compileGlsl(request);
    ASSERT_TRUE(large.ok()) << large.error;
    const ShaderInfo a = reflectSpirv(small.spirv);
    const ShaderInfo b = reflectSpirv(large.spirv);
    EXPECT_EQ(a.localSize[0], 32u);
    EXPECT_EQ(a.pushConstantBytes, 0u);
    EXPECT_EQ(b.localSize[0], 128u);
    EXPECT_EQ(b.pushConstantBytes, 16u);

    request.defines = {};
    const CompileResult missing = compileGlsl(request);
    EXPECT_FALSE(missing.ok());
    EXPECT_TRUE(contains(missing.error, "virtual/defines.comp:2:")) << missing.error;
}

TEST(GlslCompiler, DebugInfoAddsLineInformation) {
    CompileRequest request;
    request.path = "virtual/debug.comp";
    request.source = kValidCompute;
    const CompileResult plain = compileGlsl(request);
    request.debugInfo = true;
    const CompileResult debug = compileGlsl(request);
    ASSERT_TRUE(plain.ok()) << plain.error;
    ASSERT_TRUE(debug.ok()) << debug.error;
    auto countOpcode = [](const std::vector<uint32_t>& words, uint32_t opcode) {
        int n = 0;
        for (size_t at = 5; at < words.size(); at += words[at] >> 16) {
            n += (words[at] & 0xffffu) == opcode;
        }
        return n;
    };
    constexpr uint32_t kOpLine = 8;
    EXPECT_EQ(countOpcode(plain.spirv, kOpLine), 0);
    EXPECT_GT(countOpcode(debug.spirv, kOpLine), 0);
    EXPECT_EQ(reflectSpirv(debug.spirv).localSize, reflectSpirv(plain.spirv).localSize);
}

TEST(GlslCompiler, ReportsProblemsWithoutThrowing) {
    CompileRequest missingFile;
    missingFile.path = "/nonexistent/idk/shader.comp";
    CompileResult r;
    ASSERT_NO_THROW(r = compileGlsl(missingFile));
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error, "/nonexistent/idk/shader.comp")) << r.error;
    EXPECT_TRUE(contains(r.error, "no such file")) << r.error;

    CompileRequest unknownStage;
    unknownStage.path = "virtual/shader.txt";
    unknownStage.source = kValidCompute;
    r = compileGlsl(unknownStage);
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error, "stage")) << r.error;

    CompileRequest noMain;
    noMain.path = "virtual/nomain.comp";
    noMain.source = "#version 460\nlayout(local_size_x = 1) in;\nvoid notMain() {}\n";
    r = compileGlsl(noMain);
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error, "virtual/nomain.comp")) << r.error;
    EXPECT_TRUE(contains(r.error, "entry point")) << r.error;

    CompileRequest wrongStage;
    wrongStage.path = "virtual/compute_as_vertex.vert";
    wrongStage.source = kValidCompute;
    r = compileGlsl(wrongStage);
    EXPECT_FALSE(r.ok());

    CompileRequest empty;
    empty.path = "virtual/empty.comp";
    empty.source = "";
    r = compileGlsl(empty);
    EXPECT_FALSE(r.ok());
}

TEST(GlslCompiler, StageFromPath) {
    EXPECT_EQ(stageFromPath("a/b/x.comp"), ShaderStage::Compute);
    EXPECT_EQ(stageFromPath("x.vert.glsl"), ShaderStage::Vertex);
    EXPECT_EQ(stageFromPath("x.frag"), ShaderStage::Fragment);
    EXPECT_EQ(stageFromPath("x.mesh.glsl"), ShaderStage::Mesh);
    EXPECT_EQ(stageFromPath("x.task"), ShaderStage::Task);
    EXPECT_EQ(stageFromPath("x.tesc"), ShaderStage::TessControl);
    EXPECT_EQ(stageFromPath("x.tese"), ShaderStage::TessEvaluation);
    EXPECT_EQ(stageFromPath("x.geom"), ShaderStage::Geometry);
    EXPECT_EQ(stageFromPath("x.glsl"), std::nullopt);
    EXPECT_EQ(stageFromPath("comp"), std::nullopt);
}

TEST(GlslCompiler, ConcurrentCompiles) {
    constexpr int kThreads = 4;
    std::vector<CompileResult> results(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([t, &results] {
            CompileRequest request;
            request.path = "virtual/thread.comp";
            request.source = "#version 460\nlayout(local_size_x = SIZE) in;\nvoid main() {}\n";
            request.defines = {{"SIZE", std::to_string(8 * (t + 1))}};
            results[t] = compileGlsl(request);
        });
    }
    for (auto& thread : threads) {
        thread.join();
    }
    for (int t = 0; t < kThreads; ++t) {
        ASSERT_TRUE(results[t].ok()) << results[t].error;
        EXPECT_EQ(reflectSpirv(results[t].spirv).localSize[0], uint32_t(8 * (t + 1)));
    }
}

TEST(SpirvFile, RoundTripAndErrors) {
    ScratchDir dir;
    CompileRequest request;
    request.path = "virtual/file.comp";
    request.source = kValidCompute;
    const CompileResult compiled = compileGlsl(request);
    ASSERT_TRUE(compiled.ok()) << compiled.error;
    const fs::path good = dir.path() / "good.spv";
    std::ofstream(good, std::ios::binary)
        .write(reinterpret_cast<const char*>(compiled.spirv.data()), std::streamsize(compiled.spirv.size() * 4));
    EXPECT_EQ(readSpirvFile(good), compiled.spirv);

    auto errorOf = [](const fs::path& p) -> std::string {
        try {
            (void)readSpirvFile(p);
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "(no error)";
    };
    const fs::path missing = dir.path() / "missing.spv";
    EXPECT_TRUE(contains(errorOf(missing), missing.string()));
    EXPECT_TRUE(contains(errorOf(missing), "no such file"));
    const fs::path odd = dir.write("odd.spv", "123456");
    EXPECT_TRUE(contains(errorOf(odd), odd.string()));
    EXPECT_TRUE(contains(errorOf(odd), "not a multiple of 4"));
    const fs::path text = dir.write("text.spv", "not spirv at all");
    EXPECT_TRUE(contains(errorOf(text), "magic"));
    EXPECT_TRUE(contains(errorOf(dir.write("empty.spv", "")), "empty"));
    EXPECT_TRUE(contains(errorOf(dir.path()), "not a regular file"));
}
