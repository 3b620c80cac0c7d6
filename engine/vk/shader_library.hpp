// shader_library.hpp: loads the build's SPIR-V by ShaderId (see the generated shader_manifest.hpp), reflects
// and checks it, and owns every pipeline, cached per description. Hot reload recompiles a shader's GLSL
// source through glslang at run time; if compiling, checking or rebuilding any dependent pipeline fails, the
// old pipelines stay in place and the compiler's message is returned.
#pragma once
#include <volk.h>

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shader/spirv_reflect.hpp"
#include "vk/pipeline.hpp"

namespace idk::vk {

struct Pipeline {
    VkPipeline handle = VK_NULL_HANDLE;  // replaced in place by a successful reload
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    std::array<uint32_t, 3> localSize{};  // compute only
    std::string name;
};

struct ReloadResult {
    bool ok = false;
    std::string message;          // compiler or pipeline error, or a short success note
    uint32_t rebuiltPipelines = 0;
};

class ShaderLibrary {
public:
    explicit ShaderLibrary(Context& ctx, std::filesystem::path spirvDir = shaders::kSpirvDir,
                           std::filesystem::path sourceDir = shaders::kShaderSourceDir);
    ~ShaderLibrary();
    ShaderLibrary(const ShaderLibrary&) = delete;
    ShaderLibrary& operator=(const ShaderLibrary&) = delete;

    const std::vector<uint32_t>& spirv(ShaderId id);  // throws naming the file if missing or malformed
    const shader::ShaderInfo& info(ShaderId id);

    const Pipeline& compute(const ComputePipelineDesc& desc);
    const Pipeline& graphics(const GraphicsPipelineDesc& desc);

    // Recompiles the shader from its GLSL file (or from sourceText, for tests and editors).
    ReloadResult reload(ShaderId id, const std::optional<std::string>& sourceText = std::nullopt);
    // Reloads every shader whose source file changed since it was last loaded.
    std::vector<std::pair<ShaderId, ReloadResult>> reloadChanged();

    uint32_t pipelineCount() const { return static_cast<uint32_t>(pipelines_.size()); }

private:
    struct Module {
        std::vector<uint32_t> words;
        shader::ShaderInfo info;
        std::filesystem::file_time_type sourceTime{};
        bool loaded = false;
    };
    struct Entry {
        std::unique_ptr<Pipeline> pipeline;
        std::optional<ComputePipelineDesc> computeDesc;
        std::optional<GraphicsPipelineDesc> graphicsDesc;
    };
    Module& module(ShaderId id);
    VkPipeline build(const Entry& entry, const std::map<ShaderId, const Module*>& override);
    static bool uses(const Entry& entry, ShaderId id);

    Context& ctx_;
    std::filesystem::path spirvDir_;
    std::filesystem::path sourceDir_;
    std::map<ShaderId, Module> modules_;
    std::map<std::string, Entry> pipelines_;
};

// Small recording helpers for passes.
template <class Push>
void pushConstants(VkCommandBuffer cmd, const Context& ctx, const Push& push);
void bindPipeline(VkCommandBuffer cmd, const Pipeline& pipeline);
inline uint32_t groupCount(uint32_t items, uint32_t groupSize) { return (items + groupSize - 1) / groupSize; }

}  // namespace idk::vk

#include "vk/context.hpp"

template <class Push>
void idk::vk::pushConstants(VkCommandBuffer cmd, const Context& ctx, const Push& push) {
    static_assert(sizeof(Push) <= 128, "push constants are limited to 128 bytes");
    vkCmdPushConstants(cmd, ctx.pipelineLayout(), VK_SHADER_STAGE_ALL, 0, sizeof(Push), &push);
}
