// shader_stage.cpp: names of shader stages and the mapping from file extensions (.comp, .vert, ...) to stages.
#include "shader/shader_stage.hpp"

#include <array>
#include <utility>

namespace idk::shader {

std::string_view toString(ShaderStage stage) noexcept {
    switch (stage) {
        case ShaderStage::Compute: return "compute";
        case ShaderStage::Vertex: return "vertex";
        case ShaderStage::Fragment: return "fragment";
        case ShaderStage::Geometry: return "geometry";
        case ShaderStage::TessControl: return "tess_control";
        case ShaderStage::TessEvaluation: return "tess_evaluation";
        case ShaderStage::Mesh: return "mesh";
        case ShaderStage::Task: return "task";
    }
    return "unknown";
}

std::optional<ShaderStage> stageFromPath(const std::filesystem::path& path) {
    static constexpr std::array<std::pair<std::string_view, ShaderStage>, 8> kExtensions = {{
        {".comp", ShaderStage::Compute},
        {".vert", ShaderStage::Vertex},
        {".frag", ShaderStage::Fragment},
        {".geom", ShaderStage::Geometry},
        {".tesc", ShaderStage::TessControl},
        {".tese", ShaderStage::TessEvaluation},
        {".mesh", ShaderStage::Mesh},
        {".task", ShaderStage::Task},
    }};
    std::filesystem::path name = path.filename();
    if (name.extension() == ".glsl") {
        name = name.stem();
    }
    const std::string extension = name.extension().string();
    for (const auto& [ext, stage] : kExtensions) {
        if (extension == ext) {
            return stage;
        }
    }
    return std::nullopt;
}

}  // namespace idk::shader
