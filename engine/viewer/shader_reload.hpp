// shader_reload.hpp: the viewer's shader hot reload: key 1 recompiles every shader from its GLSL source, --watch
// recompiles those whose file changed (polled each frame). A failed compile keeps the old pipeline (ShaderLibrary
// guarantees it); the message goes to stdout and to the UI's log.
#pragma once
#include <string>
#include <vector>

#include "vk/shader_library.hpp"

namespace idk::viewer {

struct ReloadLogEntry {
    bool ok = false;
    std::string shader;   // source path relative to the shader folder
    std::string message;  // compiler message or success note
};

class ShaderReloader {
public:
    explicit ShaderReloader(vk::ShaderLibrary& shaders) : shaders_(shaders) {}

    void reloadAll();     // key 1
    void reloadChanged(); // --watch, each frame

    const std::vector<ReloadLogEntry>& log() const noexcept { return log_; }  // newest last, at most 64
    uint32_t failures() const noexcept { return failures_; }
    // The last reload's failures (empty when it succeeded): what the UI shows in red.
    const std::vector<ReloadLogEntry>& currentErrors() const noexcept { return errors_; }

private:
    void report(shaders::ShaderId id, const vk::ReloadResult& result);

    vk::ShaderLibrary& shaders_;
    std::vector<ReloadLogEntry> log_;
    std::vector<ReloadLogEntry> errors_;
    uint32_t failures_ = 0;
};

}  // namespace idk::viewer
