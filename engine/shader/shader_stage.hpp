// shader_stage.hpp: the pipeline stage a shader module is written for, shared by reflection and the runtime
// compiler and the generated shader manifest (which aliases it as idk::shaders::ShaderStage).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>

namespace idk::shader {

enum class ShaderStage : uint8_t { Compute, Vertex, Fragment, Geometry, TessControl, TessEvaluation, Mesh, Task };

// "compute", "vertex", ..., "mesh", "task".
std::string_view toString(ShaderStage stage) noexcept;

// Stage named by a file's extensions: x.comp, x.comp.glsl, x.vert, x.frag, x.geom, x.tesc, x.tese, x.mesh,
// x.task (the stage part is the last extension, or the one before a final ".glsl"). nullopt when none matches.
std::optional<ShaderStage> stageFromPath(const std::filesystem::path& path);

// True for the stages that have a workgroup size (compute, mesh, task).
constexpr bool hasWorkgroup(ShaderStage stage) noexcept {
    return stage == ShaderStage::Compute || stage == ShaderStage::Mesh || stage == ShaderStage::Task;
}

}  // namespace idk::shader
