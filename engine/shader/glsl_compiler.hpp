// glsl_compiler.hpp: runtime GLSL -> SPIR-V (Vulkan 1.3, SPIR-V 1.6) through glslang, for hot reload.
// Same rules as the build step (glslangValidator -V --target-env vulkan1.3 -I...): #include needs
// GL_GOOGLE_include_directive; "x.h" is searched next to the including file first, then in includeDirs.
#pragma once

#include "shader/shader_stage.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace idk::shader {

struct CompileRequest {
    std::filesystem::path path;           // file to compile; with `source` set, only its name (virtual file)
    std::optional<std::string> source;    // compile this text instead of reading `path`
    std::optional<ShaderStage> stage;     // default: from the extension of `path` (.comp, .vert.glsl, ...)
    std::vector<std::filesystem::path> includeDirs;
    std::vector<std::pair<std::string, std::string>> defines;  // {NAME, VALUE}; VALUE may be empty
    bool debugInfo = false;               // OpLine/OpSource for debuggers (as glslangValidator -g)
};

struct CompileResult {
    std::vector<uint32_t> spirv;               // empty on failure
    std::string error;                         // empty on success; names the file, holds glslang's log
    std::vector<std::filesystem::path> includedFiles;  // every file #included (for reload dependency tracking)
    bool ok() const noexcept { return error.empty() && !spirv.empty(); }
};

// Never throws for a shader problem (missing file, syntax error, missing include, link error): all of these
// come back in CompileResult::error. The glslang process is initialised on first use and finalised at exit.
// Safe to call from several threads at once.
CompileResult compileGlsl(const CompileRequest& request);

}  // namespace idk::shader
