// shader_reload.cpp: recompiles through vk::ShaderLibrary::reload / reloadChanged and reports each result.
#include "viewer/shader_reload.hpp"

#include <chrono>
#include <cstdio>

namespace idk::viewer {

void ShaderReloader::report(shaders::ShaderId id, const vk::ReloadResult& result) {
    ReloadLogEntry e{result.ok, shaders::shaderEntry(id).sourcePath, result.message};
    if (!result.ok) {
        ++failures_;
        std::printf("idk-viewer: shader reload failed: %s: %s\n", e.shader.c_str(), e.message.c_str());
        std::fflush(stdout);
        errors_.push_back(e);
    } else if (result.rebuiltPipelines > 0) {
        std::printf("idk-viewer: %s\n", e.message.c_str());
    }
    if (!result.ok || result.rebuiltPipelines > 0) log_.push_back(std::move(e));
    if (log_.size() > 64) log_.erase(log_.begin(), log_.begin() + long(log_.size() - 64));
}

void ShaderReloader::reloadAll() {
    errors_.clear();
    auto start = std::chrono::steady_clock::now();
    uint32_t count = 0;
    for (uint32_t i = 0; i < shaders::allShaders().size(); ++i) {
        auto id = static_cast<shaders::ShaderId>(i);
        report(id, shaders_.reload(id));
        ++count;
    }
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("idk-viewer: recompiled %u shaders in %.0f ms, %zu failed\n", count, ms, errors_.size());
    std::fflush(stdout);
}

void ShaderReloader::reloadChanged() {
    auto results = shaders_.reloadChanged();
    if (results.empty()) return;
    errors_.clear();
    for (const auto& [id, result] : results) report(id, result);
    std::fflush(stdout);
}

}  // namespace idk::viewer
