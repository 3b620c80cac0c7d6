// spirv_reflect_test.cpp: checks idk::shader::reflectSpirv on GLSL compiled at test time by the runtime compiler
// (stages, workgroup sizes incl. spec constants, push-constant sizes under std430 and scalar layout, descriptor
// sets) and on small hand-assembled modules (LocalSize literals, the WorkgroupSize built-in, malformed input).
#include "shader/glsl_compiler.hpp"
#include "shader/spirv_reflect.hpp"

#include <glslang/SPIRV/spirv.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <initializer_list>
#include <random>
#include <string>

using namespace idk::shader;

namespace {

std::vector<uint32_t> compile(const std::string& source, ShaderStage stage) {
    CompileRequest request;
    request.path = std::string("inline.") + std::string(toString(stage)) + ".glsl";
    request.source = source;
    request.stage = stage;
    const CompileResult result = compileGlsl(request);
    EXPECT_TRUE(result.ok()) << result.error;
    return result.spirv;
}

ShaderInfo reflectGlsl(const std::string& source, ShaderStage stage = ShaderStage::Compute) {
    const auto spirv = compile(source, stage);
    if (spirv.empty()) {
        ADD_FAILURE() << "no SPIR-V to reflect";
        return {};
    }
    return reflectSpirv(spirv);
}

// Push-constant block size of a compute shader whose block body is `members` (every member read in main).
uint32_t pushBytes(const std::string& declarations, const std::string& layout, const std::string& members,
                   const std::string& use) {
    const std::string source = "#version 460\n"
                               "#extension GL_EXT_scalar_block_layout : require\n"
                               "layout(local_size_x = 1) in;\n" +
                               declarations + "layout(push_constant" + layout + ") uniform Push {\n" + members +
                               "} pc;\n"
                               "layout(set = 0, binding = 0) buffer Out { float result[]; };\n"
                               "void main() { result[0] = float(" +
                               use + "); }\n";
    return reflectGlsl(source).pushConstantBytes;
}

// Tiny SPIR-V assembler for hand-made modules.
struct Assembler {
    std::vector<uint32_t> words{0x07230203u, 0x00010600u, 0u, 64u, 0u};
    void op(uint32_t opcode, std::initializer_list<uint32_t> operands) {
        words.push_back(uint32_t(operands.size() + 1) << 16 | opcode);
        words.insert(words.end(), operands);
    }
    void entryPoint(uint32_t model, uint32_t function, const std::string& name) {
        std::vector<uint32_t> packed((name.size() + 4) / 4, 0u);
        for (size_t i = 0; i < name.size(); ++i) {
            packed[i / 4] |= uint32_t(uint8_t(name[i])) << (8 * (i % 4));
        }
        words.push_back(uint32_t(3 + packed.size()) << 16 | spv::OpEntryPoint);
        words.push_back(model);
        words.push_back(function);
        words.insert(words.end(), packed.begin(), packed.end());
    }
    void emptyFunction(uint32_t function) {
        op(spv::OpFunction, {2, function, 0, 3});
        op(spv::OpLabel, {5});
        op(spv::OpReturn, {});
        op(spv::OpFunctionEnd, {});
    }
};

// What glslang emits for `layout(local_size_x_id = 4, local_size_y = 2) in;` with --target-env vulkan1.0:
// LocalSize literals plus a WorkgroupSize built-in composite whose x is spec constant 4 (default 8 here).
Assembler workgroupBuiltInModule(bool withBuiltIn) {
    Assembler a;
    a.op(spv::OpCapability, {spv::CapabilityShader});
    a.op(spv::OpMemoryModel, {spv::AddressingModelLogical, spv::MemoryModelGLSL450});
    a.entryPoint(spv::ExecutionModelGLCompute, 4, "main");
    a.op(spv::OpExecutionMode, {4, spv::ExecutionModeLocalSize, 3, 5, 7});
    a.op(spv::OpDecorate, {16, spv::DecorationSpecId, 4});
    if (withBuiltIn) {
        a.op(spv::OpDecorate, {20, spv::DecorationBuiltIn, spv::BuiltInWorkgroupSize});
    }
    a.op(spv::OpTypeVoid, {2});
    a.op(spv::OpTypeFunction, {3, 2});
    a.op(spv::OpTypeInt, {6, 32, 0});
    a.op(spv::OpSpecConstant, {6, 16, 8});
    a.op(spv::OpConstant, {6, 17, 2});
    a.op(spv::OpConstant, {6, 18, 1});
    a.op(spv::OpTypeVector, {19, 6, 3});
    a.op(spv::OpSpecConstantComposite, {19, 20, 16, 17, 18});
    a.emptyFunction(4);
    return a;
}

std::string reflectErrorOf(std::span<const uint32_t> words) {
    try {
        (void)reflectSpirv(words);
    } catch (const ReflectError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST(SpirvReflect, ComputeLocalSizeFromLocalSizeId) {
    const ShaderInfo info = reflectGlsl(R"(#version 460
layout(local_size_x = 64, local_size_y = 2, local_size_z = 3) in;
layout(set = 0, binding = 0) buffer Out { uint data[]; };
void main() { data[gl_LocalInvocationIndex] = 1u; }
)");
    EXPECT_EQ(info.stage, ShaderStage::Compute);
    EXPECT_EQ(info.entryPoint, "main");
    EXPECT_EQ(info.spirvVersion, 0x00010600u);
    EXPECT_EQ(info.localSize, (std::array<uint32_t, 3>{64, 2, 3}));
    EXPECT_FALSE(info.localSizeSpecIds[0] || info.localSizeSpecIds[1] || info.localSizeSpecIds[2]);
    EXPECT_EQ(info.pushConstantBytes, 0u);
    EXPECT_EQ(info.descriptorSetMask, 0b1u);
    ASSERT_EQ(info.bindings.size(), 1u);
    EXPECT_EQ(info.bindings[0].kind, DescriptorKind::StorageBuffer);
    EXPECT_EQ(info.bindings[0].count, 1u);
    EXPECT_TRUE(info.specConstantIds.empty());
    EXPECT_FALSE(info.uses64BitPointers);
    EXPECT_NE(std::find(info.capabilities.begin(), info.capabilities.end(), uint32_t(spv::CapabilityShader)),
              info.capabilities.end());
}

TEST(SpirvReflect, LocalSizeSpecConstants) {
    const ShaderInfo info = reflectGlsl(R"(#version 460
layout(local_size_x_id = 4, local_size_x = 16, local_size_y = 2, local_size_z_id = 9) in;
layout(constant_id = 7) const int kIterations = 3;
layout(set = 0, binding = 0) buffer Out { uint data[]; };
void main() { data[gl_LocalInvocationIndex] = gl_WorkGroupSize.x + uint(kIterations); }
)");
    EXPECT_EQ(info.localSize, (std::array<uint32_t, 3>{16, 2, 1}));  // spec defaults: 16 given, 1 implied
    EXPECT_EQ(info.localSizeSpecIds[0], 4u);
    EXPECT_EQ(info.localSizeSpecIds[1], std::nullopt);
    EXPECT_EQ(info.localSizeSpecIds[2], 9u);
    EXPECT_EQ(info.specConstantIds, (std::vector<uint32_t>{4, 7, 9}));
}

TEST(SpirvReflect, LocalSizeLiteralExecutionMode) {
    const Assembler a = workgroupBuiltInModule(false);
    const ShaderInfo info = reflectSpirv(a.words);
    EXPECT_EQ(info.localSize, (std::array<uint32_t, 3>{3, 5, 7}));
    EXPECT_EQ(info.localSizeSpecIds[0], std::nullopt);
    EXPECT_EQ(info.specConstantIds, (std::vector<uint32_t>{4}));
}

TEST(SpirvReflect, WorkgroupSizeBuiltInTakesPrecedence) {
    const Assembler a = workgroupBuiltInModule(true);
    const ShaderInfo info = reflectSpirv(a.words);
    EXPECT_EQ(info.localSize, (std::array<uint32_t, 3>{8, 2, 1}));
    EXPECT_EQ(info.localSizeSpecIds[0], 4u);
    EXPECT_EQ(info.localSizeSpecIds[1], std::nullopt);
}

TEST(SpirvReflect, PushConstantScalarVec3) {
    EXPECT_EQ(pushBytes("", ", scalar", "vec3 a; vec3 b; float c;\n", "pc.a.x + pc.b.y + pc.c"), 28u);
    // std430 puts a float into the tail of a vec3 and the next vec3 at 16.
    EXPECT_EQ(pushBytes("", "", "vec3 a; float b; vec3 c;\n", "pc.a.x + pc.b + pc.c.z"), 28u);
    EXPECT_EQ(pushBytes("", "", "vec3 a; vec3 c;\n", "pc.a.x + pc.c.z"), 28u);
    EXPECT_EQ(pushBytes("", ", scalar", "vec3 a; vec3 c;\n", "pc.a.x + pc.c.z"), 24u);
}

TEST(SpirvReflect, PushConstantArrays) {
    EXPECT_EQ(pushBytes("", "", "uint x; vec4 arr[3];\n", "pc.x + pc.arr[2].w"), 64u);
    EXPECT_EQ(pushBytes("", ", scalar", "float x; vec3 arr[2];\n", "pc.x + pc.arr[1].z"), 28u);
    EXPECT_EQ(pushBytes("", "", "float f[5];\n", "pc.f[4]"), 20u);
}

TEST(SpirvReflect, PushConstantNestedStructs) {
    const std::string inner = "struct Inner { vec2 a; float b; };\n";
    // std430: Inner aligns to 8 and has stride 16; the last member ends at its own last byte.
    EXPECT_EQ(pushBytes(inner, "", "uint x; Inner one; Inner two[2];\n", "pc.x + pc.one.b + pc.two[1].a.y"), 56u);
    EXPECT_EQ(pushBytes(inner, ", scalar", "uint x; Inner one; Inner two[2];\n", "pc.x + pc.one.b + pc.two[1].b"),
              40u);
    EXPECT_EQ(pushBytes(inner, "", "uint x; Inner one;\n", "pc.x + pc.one.b"), 20u);
}

TEST(SpirvReflect, PushConstantMatrices) {
    EXPECT_EQ(pushBytes("", "", "mat4 m; mat3 n;\n", "pc.m[0][0] + pc.n[2][2]"), 112u);
    EXPECT_EQ(pushBytes("", ", scalar", "mat4 m; mat3 n;\n", "pc.m[0][0] + pc.n[2][2]"), 100u);
    EXPECT_EQ(pushBytes("", "", "mat2x3 c;\n", "pc.c[1][2]"), 32u);                       // 2 columns, stride 16
    EXPECT_EQ(pushBytes("", "", "layout(row_major) mat2x3 r;\n", "pc.r[1][2]"), 24u);      // 3 rows, stride 8
    EXPECT_EQ(pushBytes("", ", scalar", "uint i; mat4x3 ms[2];\n", "pc.i + pc.ms[1][3][2]"), 100u);  // 4 + 2*48
}

TEST(SpirvReflect, PushConstantDeviceAddresses) {
    const std::string source = R"(#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
layout(local_size_x = 32) in;
layout(buffer_reference, scalar) buffer Values { uint v[]; };
layout(push_constant, scalar) uniform Push { Values values; uint count; uint64_t raw; uint tail; } pc;
void main() { if (gl_GlobalInvocationID.x < pc.count + uint(pc.raw) + pc.tail) pc.values.v[0] = 1u; }
)";
    const ShaderInfo info = reflectGlsl(source);
    EXPECT_EQ(info.pushConstantBytes, 28u);  // pointer 0..8, count 8..12, raw 16..24 (8-aligned), tail 24..28
    EXPECT_TRUE(info.uses64BitPointers);
    EXPECT_EQ(info.descriptorSetMask, 0u);
    EXPECT_TRUE(info.bindings.empty());
}

TEST(SpirvReflect, DescriptorSetsAndKinds) {
    const ShaderInfo info = reflectGlsl(R"(#version 460
#extension GL_EXT_nonuniform_qualifier : require
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform texture2D textures2D[];
layout(set = 0, binding = 0) uniform texture3D textures3D[];
layout(set = 0, binding = 1, r32ui) uniform uimage2D storageImages[];
layout(set = 0, binding = 2) uniform sampler samplers[4];
layout(set = 0, binding = 3) buffer Floats { float f[]; } floatBuffers[];
layout(set = 0, binding = 3) buffer Uints { uint u[]; } uintBuffers[];
layout(set = 2, binding = 5) uniform Globals { mat4 viewProjection; } globals;
layout(set = 3, binding = 1) uniform sampler2D combined;
layout(set = 3, binding = 2) uniform samplerBuffer texels;
layout(set = 3, binding = 3, r32f) uniform imageBuffer storageTexels;
void main() {
    vec4 c = texture(sampler2D(textures2D[nonuniformEXT(1)], samplers[0]), vec2(0.5));
    c += texture(sampler3D(textures3D[2], samplers[1]), vec3(0.5));
    c += texture(combined, vec2(0.5)) + texelFetch(texels, 0) + imageLoad(storageTexels, 0);
    imageStore(storageImages[0], ivec2(gl_GlobalInvocationID.xy), uvec4(globals.viewProjection[0][0] + c.x));
    floatBuffers[nonuniformEXT(gl_WorkGroupID.x)].f[0] = c.y;  // dynamic indices keep the arrays unsized
    uintBuffers[gl_WorkGroupID.y].u[0] = 3u;
}
)");
    EXPECT_EQ(info.localSize, (std::array<uint32_t, 3>{8, 8, 1}));
    EXPECT_EQ(info.descriptorSetMask, 0b1101u);
    const auto set0 = bindingsInSet(info, 0);
    ASSERT_EQ(set0.size(), 4u);  // aliases of bindings 0 and 3 merged
    EXPECT_EQ(set0[0].binding, 0u);
    EXPECT_EQ(set0[0].kind, DescriptorKind::SampledImage);
    EXPECT_EQ(set0[0].count, 0u);
    EXPECT_EQ(set0[1].kind, DescriptorKind::StorageImage);
    EXPECT_EQ(set0[2].kind, DescriptorKind::Sampler);
    EXPECT_EQ(set0[2].count, 4u);
    EXPECT_EQ(set0[3].kind, DescriptorKind::StorageBuffer);
    EXPECT_EQ(set0[3].count, 0u);
    const auto set2 = bindingsInSet(info, 2);
    ASSERT_EQ(set2.size(), 1u);
    EXPECT_EQ(set2[0].binding, 5u);
    EXPECT_EQ(set2[0].kind, DescriptorKind::UniformBuffer);
    const auto set3 = bindingsInSet(info, 3);
    ASSERT_EQ(set3.size(), 3u);
    EXPECT_EQ(set3[0].kind, DescriptorKind::CombinedImageSampler);
    EXPECT_EQ(set3[1].kind, DescriptorKind::UniformTexelBuffer);
    EXPECT_EQ(set3[2].kind, DescriptorKind::StorageTexelBuffer);
    EXPECT_TRUE(bindingsInSet(info, 1).empty());
}

TEST(SpirvReflect, VertexAndFragmentStages) {
    const ShaderInfo vert = reflectGlsl(R"(#version 460
layout(push_constant) uniform Push { mat4 transform; } pc;
layout(location = 0) in vec3 position;
void main() { gl_Position = pc.transform * vec4(position, 1.0); }
)",
                                        ShaderStage::Vertex);
    EXPECT_EQ(vert.stage, ShaderStage::Vertex);
    EXPECT_EQ(vert.localSize, (std::array<uint32_t, 3>{0, 0, 0}));
    EXPECT_EQ(vert.pushConstantBytes, 64u);
    EXPECT_EQ(vert.descriptorSetMask, 0u);

    const ShaderInfo frag = reflectGlsl(R"(#version 460
layout(set = 1, binding = 0) uniform sampler2D albedo;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
void main() { color = texture(albedo, uv); }
)",
                                        ShaderStage::Fragment);
    EXPECT_EQ(frag.stage, ShaderStage::Fragment);
    EXPECT_EQ(frag.descriptorSetMask, 0b10u);
    EXPECT_EQ(frag.pushConstantBytes, 0u);
}

TEST(SpirvReflect, MeshAndTaskStages) {
    const ShaderInfo mesh = reflectGlsl(R"(#version 460
#extension GL_EXT_mesh_shader : require
layout(local_size_x = 32) in;
layout(triangles, max_vertices = 64, max_primitives = 124) out;
layout(push_constant) uniform Push { uint meshletCount; } pc;
void main() {
    SetMeshOutputsEXT(3, 1);
    if (gl_LocalInvocationIndex < 3) gl_MeshVerticesEXT[gl_LocalInvocationIndex].gl_Position = vec4(pc.meshletCount);
    if (gl_LocalInvocationIndex == 0) gl_PrimitiveTriangleIndicesEXT[0] = uvec3(0, 1, 2);
}
)",
                                        ShaderStage::Mesh);
    EXPECT_EQ(mesh.stage, ShaderStage::Mesh);
    EXPECT_EQ(mesh.localSize, (std::array<uint32_t, 3>{32, 1, 1}));
    EXPECT_EQ(mesh.pushConstantBytes, 4u);

    const ShaderInfo task = reflectGlsl(R"(#version 460
#extension GL_EXT_mesh_shader : require
layout(local_size_x = 64) in;
void main() { EmitMeshTasksEXT(1, 1, 1); }
)",
                                        ShaderStage::Task);
    EXPECT_EQ(task.stage, ShaderStage::Task);
    EXPECT_EQ(task.localSize, (std::array<uint32_t, 3>{64, 1, 1}));
}

TEST(SpirvReflect, RejectsBadMagic) {
    Assembler a = workgroupBuiltInModule(false);
    a.words[0] = 0xdeadbeefu;
    const std::string error = reflectErrorOf(a.words);
    EXPECT_NE(error.find("bad magic"), std::string::npos) << error;
    EXPECT_NE(error.find("word 0"), std::string::npos) << error;
    a.words[0] = 0x03022307u;
    EXPECT_NE(reflectErrorOf(a.words).find("byte-swapped"), std::string::npos);
}

TEST(SpirvReflect, RejectsTruncatedInput) {
    const std::vector<uint32_t> header{0x07230203u, 0x00010600u, 0u};
    EXPECT_NE(reflectErrorOf(header).find("truncated header"), std::string::npos);
    EXPECT_NE(reflectErrorOf({}).find("truncated header"), std::string::npos);

    Assembler a = workgroupBuiltInModule(false);
    const size_t at = a.words.size();
    a.words.push_back(uint32_t(5) << 16 | spv::OpConstant);  // claims 5 words, only 2 follow
    a.words.push_back(6);
    a.words.push_back(30);
    try {
        (void)reflectSpirv(a.words);
        ADD_FAILURE() << "no error";
    } catch (const ReflectError& e) {
        EXPECT_EQ(e.word(), at);
        EXPECT_NE(std::string(e.what()).find("truncated instruction"), std::string::npos) << e.what();
    }

    // A real module cut in the middle of an instruction.
    auto spirv = compile("#version 460\nlayout(local_size_x = 1) in;\nvoid main() {}\n", ShaderStage::Compute);
    ASSERT_GT(spirv.size(), 20u);
    size_t cut = 5;
    while (cut < spirv.size() && (spirv[cut] >> 16) < 3) {
        cut += spirv[cut] >> 16;
    }
    ASSERT_LT(cut, spirv.size());
    spirv.resize(cut + 1);
    EXPECT_NE(reflectErrorOf(spirv).find("truncated instruction"), std::string::npos);
}

TEST(SpirvReflect, RejectsStructuralErrors) {
    Assembler noEntry;
    noEntry.op(spv::OpCapability, {spv::CapabilityShader});
    noEntry.op(spv::OpMemoryModel, {spv::AddressingModelLogical, spv::MemoryModelGLSL450});
    EXPECT_NE(reflectErrorOf(noEntry.words).find("no OpEntryPoint"), std::string::npos);

    Assembler zero = workgroupBuiltInModule(false);
    zero.words.push_back(0u);
    EXPECT_NE(reflectErrorOf(zero.words).find("word count 0"), std::string::npos);

    Assembler outOfBound = workgroupBuiltInModule(false);
    outOfBound.op(spv::OpTypeInt, {999, 32, 0});
    EXPECT_NE(reflectErrorOf(outOfBound.words).find("outside the id bound"), std::string::npos);

    Assembler unterminated;
    unterminated.op(spv::OpEntryPoint, {spv::ExecutionModelGLCompute, 4, 0x6e69616du /* "main", no NUL */});
    EXPECT_NE(reflectErrorOf(unterminated.words).find("NUL"), std::string::npos);
}

// Corrupted modules must fail with ReflectError (or reflect something), never crash or throw anything else.
// Under IDK_SANITIZE this doubles as a memory-safety check of the parser.
TEST(SpirvReflect, SurvivesRandomCorruption) {
    const auto original = compile(R"(#version 460
#extension GL_EXT_scalar_block_layout : require
layout(local_size_x_id = 1, local_size_y = 4) in;
struct Inner { vec3 a; mat3 m; };
layout(push_constant, scalar) uniform Push { Inner inner[2]; uint count; } pc;
layout(set = 0, binding = 0) uniform sampler2D textures[];
layout(set = 1, binding = 2) buffer Out { float values[]; };
void main() { values[gl_LocalInvocationIndex] = pc.inner[1].m[2][2] + float(pc.count) + texture(textures[1], vec2(0)).x; }
)",
                                  ShaderStage::Compute);
    ASSERT_FALSE(original.empty());
    std::mt19937 rng(1234);
    int errors = 0;
    for (int round = 0; round < 3000; ++round) {
        std::vector<uint32_t> words = original;
        const int edits = 1 + int(rng() % 4);
        for (int e = 0; e < edits && words.size() > 5; ++e) {
            const size_t at = 5 + rng() % (words.size() - 5);
            switch (rng() % 4) {
                case 0: words[at] = rng(); break;                             // anything
                case 1: words[at] ^= 1u << (rng() % 32); break;               // one bit
                case 2: words[at] = rng() % 64; break;                        // small value (ids, counts)
                case 3: words.resize(std::max<size_t>(5, at)); break;         // truncation
            }
        }
        try {
            (void)reflectSpirv(words);
        } catch (const ReflectError&) {
            ++errors;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "round " << round << ": unexpected exception " << e.what();
        }
    }
    EXPECT_GT(errors, 100);
}
