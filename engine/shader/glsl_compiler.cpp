// glsl_compiler.cpp: drives glslang (parse, link, GlslangToSpv) for one shader with a file-system includer and
// -D style defines in the preamble. Every failure becomes an error string that names the file; the glslang
// process is initialised once (thread-safe static) and finalised at exit.
#include "shader/glsl_compiler.hpp"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

namespace idk::shader {

namespace fs = std::filesystem;

namespace {

constexpr size_t kMaxIncludeDepth = 64;

struct GlslangProcess {
    GlslangProcess() { glslang::InitializeProcess(); }
    ~GlslangProcess() { glslang::FinalizeProcess(); }
    GlslangProcess(const GlslangProcess&) = delete;
    GlslangProcess& operator=(const GlslangProcess&) = delete;
};

void ensureGlslangProcess() {
    static GlslangProcess process;  // initialised once, even with concurrent first calls; finalised at exit
}

EShLanguage toGlslang(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Compute: return EShLangCompute;
        case ShaderStage::Vertex: return EShLangVertex;
        case ShaderStage::Fragment: return EShLangFragment;
        case ShaderStage::Geometry: return EShLangGeometry;
        case ShaderStage::TessControl: return EShLangTessControl;
        case ShaderStage::TessEvaluation: return EShLangTessEvaluation;
        case ShaderStage::Mesh: return EShLangMesh;
        case ShaderStage::Task: return EShLangTask;
    }
    return EShLangCompute;
}

// Reads a whole file; nullopt and `why` on failure.
std::optional<std::string> readText(const fs::path& path, std::string& why) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        why = fs::exists(path, ec) ? "not a regular file" : "no such file";
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        why = std::strerror(errno);
        return std::nullopt;
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) {
        why = "read error";
        return std::nullopt;
    }
    return std::move(text).str();
}

// Resolves #include "x" next to the including file, then (and for #include <x>) in the include directories.
class FileIncluder final : public glslang::TShader::Includer {
public:
    FileIncluder(const std::vector<fs::path>& dirs, fs::path rootDir) : dirs_(dirs), rootDir_(std::move(rootDir)) {}

    IncludeResult* includeLocal(const char* header, const char* includer, size_t depth) override {
        if (depth > kMaxIncludeDepth) {
            return failure("#include nested deeper than " + std::to_string(kMaxIncludeDepth) + " levels");
        }
        const fs::path includerPath(includer != nullptr ? includer : "");
        const fs::path base = includerPath.has_parent_path() ? includerPath.parent_path() : rootDir_;
        return tryOpen(base / header);  // nullptr: glslang then calls includeSystem
    }

    IncludeResult* includeSystem(const char* header, const char* /*includer*/, size_t depth) override {
        if (depth > kMaxIncludeDepth) {
            return failure("#include nested deeper than " + std::to_string(kMaxIncludeDepth) + " levels");
        }
        for (const fs::path& dir : dirs_) {
            if (IncludeResult* found = tryOpen(dir / header)) {
                return found;
            }
        }
        std::string message = std::string("cannot find include file \"") + header + "\" (searched ";
        message += rootDir_.empty() ? std::string("the including file's folder") : rootDir_.string();
        for (const fs::path& dir : dirs_) {
            message += ", " + dir.string();
        }
        message += ")";
        return failure(std::move(message));
    }

    void releaseInclude(IncludeResult* result) override {
        if (result != nullptr) {
            delete static_cast<std::string*>(result->userData);
            delete result;
        }
    }

    std::vector<fs::path> included;

private:
    IncludeResult* tryOpen(const fs::path& candidate) {
        std::string why;
        auto text = readText(candidate, why);
        if (!text) {
            return nullptr;
        }
        const fs::path resolved = candidate.lexically_normal();
        if (std::find(included.begin(), included.end(), resolved) == included.end()) {
            included.push_back(resolved);
        }
        auto* owned = new std::string(std::move(*text));
        return new IncludeResult(resolved.string(), owned->data(), owned->size(), owned);
    }

    // glslang reports headerData as the message when headerName is empty.
    static IncludeResult* failure(std::string message) {
        auto* owned = new std::string(std::move(message));
        return new IncludeResult(std::string(), owned->data(), owned->size(), owned);
    }

    const std::vector<fs::path>& dirs_;
    fs::path rootDir_;
};

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) {
        s.pop_back();
    }
    return s;
}

CompileResult compileImpl(const CompileRequest& request) {
    CompileResult result;
    const std::string name = request.path.string();
    auto failWith = [&](std::string message) {
        result.spirv.clear();
        result.error = name + ": " + trimmed(std::move(message));
        return result;
    };

    const std::optional<ShaderStage> stage = request.stage ? request.stage : stageFromPath(request.path);
    if (!stage) {
        return failWith("cannot tell the shader stage from the file name; set CompileRequest::stage");
    }
    std::string text;
    if (request.source) {
        text = *request.source;
    } else {
        std::string why;
        auto read = readText(request.path, why);
        if (!read) {
            return failWith("cannot read shader source: " + why);
        }
        text = std::move(*read);
    }
    if (text.size() > size_t(INT32_MAX)) {
        return failWith("source larger than 2 GiB");
    }

    std::string preamble;
    for (const auto& [define, value] : request.defines) {
        preamble += "#define " + define + (value.empty() ? "" : " " + value) + "\n";
    }

    ensureGlslangProcess();
    const EShLanguage language = toGlslang(*stage);
    auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
    if (request.debugInfo) {
        messages = static_cast<EShMessages>(messages | EShMsgDebugInfo);
    }

    glslang::TShader shader(language);
    const char* strings[] = {text.c_str()};
    const int lengths[] = {static_cast<int>(text.size())};
    const char* names[] = {name.c_str()};
    shader.setStringsWithLengthsAndNames(strings, lengths, names, 1);
    shader.setPreamble(preamble.c_str());
    shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
    if (request.debugInfo) {
        shader.setDebugInfo(true);
    }

    FileIncluder includer(request.includeDirs, request.path.parent_path());
    const bool parsed = shader.parse(GetDefaultResources(), 100, false, messages, includer);
    result.includedFiles = includer.included;
    if (!parsed) {
        return failWith(std::string("GLSL compile failed\n") + shader.getInfoLog() + shader.getInfoDebugLog());
    }

    glslang::TProgram program;  // destroyed before `shader`, as glslang requires
    program.addShader(&shader);
    if (!program.link(messages)) {
        return failWith(std::string("GLSL link failed\n") + program.getInfoLog() + program.getInfoDebugLog());
    }
    const glslang::TIntermediate* intermediate = program.getIntermediate(language);
    if (intermediate == nullptr) {
        return failWith("glslang produced no intermediate code");
    }

    glslang::SpvOptions options;
    options.generateDebugInfo = request.debugInfo;
    options.disableOptimizer = true;
    options.validate = false;
    spv::SpvBuildLogger logger;
    glslang::GlslangToSpv(*intermediate, result.spirv, &logger, &options);
    if (result.spirv.empty()) {
        return failWith("SPIR-V generation failed\n" + logger.getAllMessages());
    }
    return result;
}

}  // namespace

CompileResult compileGlsl(const CompileRequest& request) {
    try {
        return compileImpl(request);
    } catch (const std::exception& e) {
        CompileResult result;
        result.error = request.path.string() + ": " + e.what();
        return result;
    }
}

}  // namespace idk::shader
