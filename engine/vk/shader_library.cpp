// shader_library.cpp: SPIR-V loading, per-description pipeline cache, and hot reload with rollback.
#include "vk/shader_library.hpp"

#include <fstream>
#include <sstream>

#include "core/log.hpp"
#include "shader/glsl_compiler.hpp"
#include "vk/check.hpp"

namespace idk::vk {
namespace {

std::vector<uint32_t> readSpirv(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) throw PipelineError("cannot open SPIR-V file " + path.string() + " (was the idk_shaders target built?)");
    std::streamsize size = file.tellg();
    if (size <= 0 || size % 4 != 0) {
        throw PipelineError(core::concat("SPIR-V file ", path.string(), " has ", size, " bytes, not a multiple of 4"));
    }
    std::vector<uint32_t> words(static_cast<size_t>(size) / 4);
    file.seekg(0);
    file.read(reinterpret_cast<char*>(words.data()), size);
    return words;
}

VkShaderStageFlagBits vkStage(shader::ShaderStage s) {
    switch (s) {
        case shader::ShaderStage::Compute: return VK_SHADER_STAGE_COMPUTE_BIT;
        case shader::ShaderStage::Vertex: return VK_SHADER_STAGE_VERTEX_BIT;
        case shader::ShaderStage::Fragment: return VK_SHADER_STAGE_FRAGMENT_BIT;
        case shader::ShaderStage::Geometry: return VK_SHADER_STAGE_GEOMETRY_BIT;
        case shader::ShaderStage::TessControl: return VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
        case shader::ShaderStage::TessEvaluation: return VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
        case shader::ShaderStage::Mesh: return VK_SHADER_STAGE_MESH_BIT_EXT;
        case shader::ShaderStage::Task: return VK_SHADER_STAGE_TASK_BIT_EXT;
    }
    return VK_SHADER_STAGE_ALL;
}

std::string specKey(const std::vector<SpecConstant>& spec) {
    std::ostringstream out;
    for (const SpecConstant& s : spec) out << s.id << '=' << s.value << ',';
    return out.str();
}

std::string keyOf(const ComputePipelineDesc& d) {
    std::string local = d.localSize ? core::concat((*d.localSize)[0], "x", (*d.localSize)[1], "x", (*d.localSize)[2]) : "";
    return core::concat("C", static_cast<uint32_t>(d.shader), "|", specKey(d.spec), "|", d.pushBytes, "|", local);
}

std::string keyOf(const GraphicsPipelineDesc& d) {
    std::ostringstream out;
    out << "G" << static_cast<uint32_t>(d.vertex) << '|' << (d.task ? int(*d.task) : -1) << '|'
        << (d.fragment ? int(*d.fragment) : -1) << '|';
    for (VkFormat f : d.colorFormats) out << f << ',';
    out << '|';
    for (BlendMode b : d.blend) out << int(b) << ',';
    out << '|' << d.depthFormat << '|' << d.depthCompare << '|' << d.depthWrite << d.depthTest << '|' << d.cull << '|'
        << d.frontFace << '|' << d.topology << '|' << d.polygonMode << '|' << d.viewMask << '|' << specKey(d.spec)
        << '|' << (d.geometry ? int(*d.geometry) : -1) << '|' << d.conservative << '|' << int(d.shadingRate)
        << '|' << d.pushBytes << '|' << d.fragmentPushBytes << '|';
    for (const VkViewportSwizzleNV& v : d.viewportSwizzles) out << v.x << v.y << v.z << v.w << ',';
    return out.str();
}

}  // namespace

ShaderLibrary::ShaderLibrary(Context& ctx, std::filesystem::path spirvDir, std::filesystem::path sourceDir)
    : ctx_(ctx), spirvDir_(std::move(spirvDir)), sourceDir_(std::move(sourceDir)) {}

ShaderLibrary::~ShaderLibrary() {
    ctx_.waitIdle();
    for (auto& [key, entry] : pipelines_) vkDestroyPipeline(ctx_.device(), entry.pipeline->handle, nullptr);
}

ShaderLibrary::Module& ShaderLibrary::module(ShaderId id) {
    Module& m = modules_[id];
    if (m.loaded) return m;
    const shaders::ShaderEntry& entry = shaders::shaderEntry(id);
    m.words = readSpirv(spirvDir_ / entry.spirvPath);
    try {
        m.info = shader::reflectSpirv(m.words);
    } catch (const shader::ReflectError& e) {
        throw PipelineError(std::string(entry.spirvPath) + ": " + e.what());
    }
    std::error_code ec;
    m.sourceTime = std::filesystem::last_write_time(sourceDir_ / entry.sourcePath, ec);
    m.loaded = true;
    return m;
}

const std::vector<uint32_t>& ShaderLibrary::spirv(ShaderId id) { return module(id).words; }
const shader::ShaderInfo& ShaderLibrary::info(ShaderId id) { return module(id).info; }

bool ShaderLibrary::uses(const Entry& e, ShaderId id) {
    if (e.computeDesc) return e.computeDesc->shader == id;
    const GraphicsPipelineDesc& g = *e.graphicsDesc;
    return g.vertex == id || g.task == id || g.fragment == id || g.geometry == id;
}

VkPipeline ShaderLibrary::build(const Entry& e, const std::map<ShaderId, const Module*>& override) {
    auto get = [&](ShaderId id) -> const Module& {
        auto it = override.find(id);
        return it != override.end() ? *it->second : module(id);
    };
    if (e.computeDesc) {
        const ComputePipelineDesc& d = *e.computeDesc;
        const Module& m = get(d.shader);
        std::string name = shaders::shaderEntry(d.shader).name;
        if (m.info.stage != shader::ShaderStage::Compute) throw PipelineError(name + " is not a compute shader");
        validateShader(name, m.info, d.pushBytes, d.localSize);
        return createComputePipeline(ctx_, m.words, d, name);
    }
    const GraphicsPipelineDesc& d = *e.graphicsDesc;
    std::vector<GraphicsStageCode> stages;
    std::string name;
    auto add = [&](ShaderId id) {
        const Module& m = get(id);
        std::string shaderName = shaders::shaderEntry(id).name;
        const bool prefix = m.info.stage == shader::ShaderStage::Fragment && d.fragmentPushBytes != 0;
        validateShader(shaderName, m.info, prefix ? d.fragmentPushBytes : d.pushBytes, std::nullopt);
        stages.push_back({vkStage(m.info.stage), m.words});
        name += (name.empty() ? "" : "+") + shaderName;
    };
    if (d.task) add(*d.task);
    add(d.vertex);
    if (d.geometry) add(*d.geometry);
    if (d.fragment) add(*d.fragment);
    return createGraphicsPipeline(ctx_, stages, d, name);
}

const Pipeline& ShaderLibrary::compute(const ComputePipelineDesc& desc) {
    std::string key = keyOf(desc);
    auto it = pipelines_.find(key);
    if (it != pipelines_.end()) return *it->second.pipeline;
    Entry e;
    e.computeDesc = desc;
    e.pipeline = std::make_unique<Pipeline>();
    e.pipeline->handle = build(e, {});
    e.pipeline->bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    e.pipeline->localSize = module(desc.shader).info.localSize;
    e.pipeline->name = shaders::shaderEntry(desc.shader).name;
    return *pipelines_.emplace(key, std::move(e)).first->second.pipeline;
}

const Pipeline& ShaderLibrary::graphics(const GraphicsPipelineDesc& desc) {
    std::string key = keyOf(desc);
    auto it = pipelines_.find(key);
    if (it != pipelines_.end()) return *it->second.pipeline;
    Entry e;
    e.graphicsDesc = desc;
    e.pipeline = std::make_unique<Pipeline>();
    e.pipeline->handle = build(e, {});
    e.pipeline->bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    e.pipeline->name = shaders::shaderEntry(desc.vertex).name;
    return *pipelines_.emplace(key, std::move(e)).first->second.pipeline;
}

ReloadResult ShaderLibrary::reload(ShaderId id, const std::optional<std::string>& sourceText) {
    const shaders::ShaderEntry& entry = shaders::shaderEntry(id);
    shader::CompileRequest request;
    request.path = sourceDir_ / entry.sourcePath;
    request.source = sourceText;
    request.stage = entry.stage;
    request.includeDirs = {sourceDir_ / "include", sourceDir_ / "shared"};
    shader::CompileResult compiled = shader::compileGlsl(request);
    if (!compiled.ok()) return {false, compiled.error, 0};

    Module fresh;
    fresh.words = std::move(compiled.spirv);
    fresh.loaded = true;
    std::error_code ec;
    fresh.sourceTime = std::filesystem::last_write_time(request.path, ec);
    try {
        fresh.info = shader::reflectSpirv(fresh.words);
    } catch (const shader::ReflectError& e) {
        return {false, std::string(entry.sourcePath) + ": " + e.what(), 0};
    }

    // Build every dependent pipeline first; only when all succeed do the old ones retire.
    std::vector<std::pair<Entry*, VkPipeline>> rebuilt;
    try {
        for (auto& [key, e] : pipelines_)
            if (uses(e, id)) rebuilt.emplace_back(&e, build(e, {{id, &fresh}}));
    } catch (const std::exception& error) {
        for (auto& [e, pipeline] : rebuilt) vkDestroyPipeline(ctx_.device(), pipeline, nullptr);
        return {false, error.what(), 0};
    }
    for (auto& [e, pipeline] : rebuilt) {
        VkPipeline old = e->pipeline->handle;
        VkDevice device = ctx_.device();
        ctx_.destroyDeferred([device, old] { vkDestroyPipeline(device, old, nullptr); });
        e->pipeline->handle = pipeline;
        if (e->computeDesc) e->pipeline->localSize = fresh.info.localSize;
    }
    modules_[id] = std::move(fresh);
    auto count = static_cast<uint32_t>(rebuilt.size());
    return {true, core::concat(entry.sourcePath, ": reloaded, ", count, " pipeline(s) rebuilt"), count};
}

std::vector<std::pair<ShaderId, ReloadResult>> ShaderLibrary::reloadChanged() {
    std::vector<std::pair<ShaderId, ReloadResult>> results;
    for (auto& [id, m] : modules_) {
        std::error_code ec;
        auto time = std::filesystem::last_write_time(sourceDir_ / shaders::shaderEntry(id).sourcePath, ec);
        if (ec || time == m.sourceTime) continue;
        ReloadResult r = reload(id);
        if (!r.ok) m.sourceTime = time;  // report a broken edit once, not every poll
        results.emplace_back(id, std::move(r));
    }
    return results;
}

void bindPipeline(VkCommandBuffer cmd, const Pipeline& pipeline) {
    vkCmdBindPipeline(cmd, pipeline.bindPoint, pipeline.handle);
}

}  // namespace idk::vk
