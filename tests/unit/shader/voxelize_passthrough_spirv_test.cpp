// voxelize_passthrough_spirv_test.cpp: the SPIR-V of the single-draw voxelization's native rung
// (vxgi/voxelize_passthrough.geom, GL_NV_geometry_shader_passthrough), as the build compiled it (glslang, then
// spirv-val: the build fails on an invalid module). No device here runs it (lavapipe lacks the extension), so the
// module is checked for what a passthrough geometry shader must be: the GeometryShaderPassthroughNV capability,
// every input decorated PassthroughNV (an undecorated one would not reach the rasterizer), the inputs' locations
// exactly voxelize.vert's outputs (the fragment shaders read them unchanged), and gl_ViewportIndex its only output.
#include "shader/spirv_file.hpp"

#include <glslang/SPIRV/spirv.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Variable {
    uint32_t storage = 0;
    std::set<uint32_t> decorations;  // spv::Decoration values
    std::optional<uint32_t> location, builtIn;
};

// The module's global variables with their decorations (a minimal walk: OpCapability, OpDecorate, OpVariable).
struct Module {
    std::vector<uint32_t> capabilities;
    std::map<uint32_t, Variable> variables;  // by result id
};

Module parse(const std::vector<uint32_t>& words) {
    Module m;
    std::map<uint32_t, Variable> decorated;
    for (size_t i = 5; i < words.size();) {
        const uint32_t count = words[i] >> 16, op = words[i] & 0xffffu;
        if (count == 0 || i + count > words.size()) throw std::runtime_error("truncated SPIR-V");
        if (op == spv::OpCapability) m.capabilities.push_back(words[i + 1]);
        if (op == spv::OpDecorate) {
            Variable& v = decorated[words[i + 1]];
            v.decorations.insert(words[i + 2]);
            if (words[i + 2] == spv::DecorationLocation) v.location = words[i + 3];
            if (words[i + 2] == spv::DecorationBuiltIn) v.builtIn = words[i + 3];
        }
        if (op == spv::OpVariable && words[i + 3] != spv::StorageClassFunction) {
            Variable v = decorated[words[i + 2]];
            v.storage = words[i + 3];
            m.variables[words[i + 2]] = v;
        }
        i += count;
    }
    return m;
}

Module load(const char* relative) {
    const fs::path path = fs::path(IDK_BINARY_DIR) / "spirv" / relative;
    if (!fs::exists(path)) throw std::runtime_error(path.string() + " is missing: build the idk_shaders target");
    return parse(idk::shader::readSpirvFile(path));
}

TEST(VoxelizePassthroughSpirv, PassesEveryVertexOutputThroughAndWritesOnlyTheViewport) {
    const Module gs = load("vxgi/voxelize_passthrough.geom.spv");
    const Module vs = load("vxgi/voxelize.vert.spv");
    EXPECT_NE(std::find(gs.capabilities.begin(), gs.capabilities.end(), uint32_t(spv::CapabilityGeometryShaderPassthroughNV)),
              gs.capabilities.end());
    std::set<uint32_t> inputs, outputs;
    uint32_t inputCount = 0;
    for (const auto& [id, v] : gs.variables) {
        if (v.storage == spv::StorageClassInput) {
            ++inputCount;
            EXPECT_TRUE(v.decorations.count(spv::DecorationPassthroughNV)) << "input %" << id << " not passthrough";
            if (v.location) inputs.insert(*v.location);
        }
        if (v.storage == spv::StorageClassOutput) {
            EXPECT_EQ(v.builtIn, std::optional<uint32_t>(spv::BuiltInViewportIndex)) << "output %" << id;
            outputs.insert(id);
        }
    }
    EXPECT_EQ(outputs.size(), 1u);
    EXPECT_EQ(inputCount, inputs.size() + 1) << "expected the located inputs and gl_in";
    std::set<uint32_t> vertexOutputs;
    for (const auto& [id, v] : vs.variables)
        if (v.storage == spv::StorageClassOutput && v.location) vertexOutputs.insert(*v.location);
    EXPECT_EQ(inputs, vertexOutputs);
    EXPECT_EQ(inputs.size(), 7u);  // world position, normal, tangent, uv, instance, colour, uv1
}

TEST(VoxelizePassthroughSpirv, TheWalkSeesAMissingPassthroughDecoration) {
    // The general geometry shader of the fallback rung re-emits: no passthrough inputs, vertex outputs of its own.
    const Module gs = load("vxgi/voxelize_axis.geom.spv");
    uint32_t passthrough = 0, located = 0;
    for (const auto& [id, v] : gs.variables) {
        passthrough += v.decorations.count(spv::DecorationPassthroughNV) ? 1u : 0u;
        located += v.storage == spv::StorageClassOutput && v.location ? 1u : 0u;
    }
    EXPECT_EQ(passthrough, 0u);
    EXPECT_EQ(located, 7u);
}

}  // namespace
