// spirv_capabilities_test.cpp: no shader the build compiled (<build>/spirv/**/*.spv) declares the Float64
// capability, so none needs shaderFloat64 and the BVH traversal rung runs on any Vulkan 1.3 device (issue 19). The
// scanner is first shown to find Float64 in a module that does use double precision.
#include "shader/glsl_compiler.hpp"
#include "shader/spirv_file.hpp"
#include "shader/spirv_reflect.hpp"

#include <glslang/SPIRV/spirv.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

using namespace idk::shader;
namespace fs = std::filesystem;

namespace {

bool declaresFloat64(const std::vector<uint32_t>& words) {
    const ShaderInfo info = reflectSpirv(words);
    return std::find(info.capabilities.begin(), info.capabilities.end(), uint32_t(spv::CapabilityFloat64)) !=
           info.capabilities.end();
}

TEST(SpirvCapabilities, ScannerFindsFloat64InADoubleShader) {
    CompileRequest request;
    request.path = "fp64.comp.glsl";
    request.source = "#version 460\nlayout(local_size_x = 1) in;\n"
                     "layout(set = 0, binding = 0) buffer B { float f[]; };\n"
                     "void main() { double d = double(f[0]); f[1] = float(d * d); }\n";
    request.stage = ShaderStage::Compute;
    const CompileResult fp64 = compileGlsl(request);
    ASSERT_TRUE(fp64.ok()) << fp64.error;
    EXPECT_TRUE(declaresFloat64(fp64.spirv));
    request.source = "#version 460\nlayout(local_size_x = 1) in;\n"
                     "layout(set = 0, binding = 0) buffer B { float f[]; };\n"
                     "void main() { f[1] = f[0] * f[0]; }\n";
    const CompileResult fp32 = compileGlsl(request);
    ASSERT_TRUE(fp32.ok()) << fp32.error;
    EXPECT_FALSE(declaresFloat64(fp32.spirv));
}

TEST(SpirvCapabilities, NoBuiltShaderDeclaresFloat64) {
    const fs::path dir = fs::path(IDK_BINARY_DIR) / "spirv";
    ASSERT_TRUE(fs::is_directory(dir)) << dir << " is missing: build the idk_shaders target first";
    std::vector<std::string> offenders;
    uint32_t modules = 0;
    bool sawBvhTraversal = false;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file() || entry.path().extension() != ".spv") continue;
        ++modules;
        const std::string name = fs::relative(entry.path(), dir).generic_string();
        sawBvhTraversal = sawBvhTraversal || name == "bvh/trace_rays.comp.spv";
        if (declaresFloat64(readSpirvFile(entry.path()))) offenders.push_back(name);
    }
    EXPECT_GT(modules, 20u) << "expected every shader of shaders_glsl/ under " << dir;
    EXPECT_TRUE(sawBvhTraversal) << "bvh/trace_rays.comp.spv (the GLSL BVH traversal) not found under " << dir;
    std::string list;
    for (const std::string& name : offenders) list += " " + name;
    EXPECT_TRUE(offenders.empty()) << "shaders declaring Float64:" << list;
}

}  // namespace
