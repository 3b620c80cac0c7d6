// render_graph.cpp: declaration (passes, resources, versioned accesses and their validation), PassBuilder,
// PassContext and the inspection hooks. compile() lives in graph_compile.cpp + graph_plan.cpp, execute() in
// graph_execute.cpp, the dumps in graph_dump.cpp.
#include "graph/render_graph.hpp"

#include "graph/flags_text.hpp"
#include "graph/text_format.hpp"

#include <algorithm>

namespace idk::graph {

using detail::Origin;
using detail::PassNode;
using detail::PassUse;
using detail::ResourceNode;

namespace {
const char* kindWord(ResourceKind kind) { return kind == ResourceKind::Image ? "texture" : "buffer"; }
}  // namespace

// ---------------------------------------------------------------------------------------------------------
// PassBuilder

TextureHandle PassBuilder::create(std::string_view name, const TextureDesc& desc) {
    ResourceNode node;
    node.name = std::string(name);
    node.kind = ResourceKind::Image;
    node.origin = desc.persistent ? Origin::Persistent : Origin::Transient;
    node.textureDesc = desc;
    node.relativeTo = graph_.relativeExtent_;
    return {graph_.addResource(std::move(node), pass_), 0};
}

BufferHandle PassBuilder::create(std::string_view name, const BufferDesc& desc) {
    ResourceNode node;
    node.name = std::string(name);
    node.kind = ResourceKind::Buffer;
    node.origin = desc.persistent ? Origin::Persistent : Origin::Transient;
    node.bufferDesc = desc;
    return {graph_.addResource(std::move(node), pass_), 0};
}

TextureHandle PassBuilder::read(TextureHandle t, Access access, VkPipelineStageFlags2 stages) {
    const uint32_t v = graph_.declareUse(pass_, ResourceKind::Image, t.resource, t.version, access, stages, false);
    return v == kInvalidId ? TextureHandle{} : TextureHandle{t.resource, v};
}

TextureHandle PassBuilder::write(TextureHandle t, Access access, VkPipelineStageFlags2 stages) {
    const uint32_t v = graph_.declareUse(pass_, ResourceKind::Image, t.resource, t.version, access, stages, true);
    return v == kInvalidId ? TextureHandle{} : TextureHandle{t.resource, v};
}

BufferHandle PassBuilder::read(BufferHandle b, Access access, VkPipelineStageFlags2 stages) {
    const uint32_t v = graph_.declareUse(pass_, ResourceKind::Buffer, b.resource, b.version, access, stages, false);
    return v == kInvalidId ? BufferHandle{} : BufferHandle{b.resource, v};
}

BufferHandle PassBuilder::write(BufferHandle b, Access access, VkPipelineStageFlags2 stages) {
    const uint32_t v = graph_.declareUse(pass_, ResourceKind::Buffer, b.resource, b.version, access, stages, true);
    return v == kInvalidId ? BufferHandle{} : BufferHandle{b.resource, v};
}

TextureHandle PassBuilder::history(std::string_view name) { return graph_.history(name); }
BufferHandle PassBuilder::historyBuffer(std::string_view name) { return graph_.historyBuffer(name); }
void PassBuilder::sideEffect() { graph_.passes_[pass_].sideEffect = true; }
void PassBuilder::after(std::string_view passName) { graph_.passes_[pass_].after.emplace_back(passName); }

// ---------------------------------------------------------------------------------------------------------
// PassContext

std::string_view PassContext::passName() const noexcept { return graph_.passes_[pass_].name; }
VkExtent2D PassContext::outputExtent() const noexcept { return graph_.passes_[pass_].extent; }

uint32_t PassContext::checkDeclared(uint32_t resource, ResourceKind kind) const {
    for (const PassUse& use : graph_.passes_[pass_].uses) {
        if (use.resource == resource && graph_.resources_[resource].kind == kind) return resource;
    }
    throw GraphError(strformat("render graph: pass '{}' looks up {} {} that it did not declare",
                                 graph_.passes_[pass_].name, kindWord(kind),
                                 resource < graph_.resources_.size() ? "'" + graph_.resources_[resource].name + "'"
                                                                     : strformat("#{}", resource)));
}

const PhysicalTexture& PassContext::texture(TextureHandle handle) const {
    return graph_.physicalTextures_[checkDeclared(handle.resource, ResourceKind::Image)];
}

const PhysicalBuffer& PassContext::buffer(BufferHandle handle) const {
    return graph_.physicalBuffers_[checkDeclared(handle.resource, ResourceKind::Buffer)];
}

bool PassContext::historyValid(TextureHandle handle) const {
    return graph_.historyValid(checkDeclared(handle.resource, ResourceKind::Image));
}

bool PassContext::historyValid(BufferHandle handle) const {
    return graph_.historyValid(checkDeclared(handle.resource, ResourceKind::Buffer));
}

// ---------------------------------------------------------------------------------------------------------
// Declaration

RenderGraph::RenderGraph(ResourcePool& pool, VkExtent2D outputExtent)
    : pool_(pool), outputExtent_(outputExtent), relativeExtent_(outputExtent) {}

void RenderGraph::setRelativeExtent(VkExtent2D extent) { relativeExtent_ = extent; }

void RenderGraph::error(std::string message) { errors_.push_back(std::move(message)); }

std::string RenderGraph::passLabel(uint32_t pass) const {
    return pass < passes_.size() ? strformat("pass '{}'", passes_[pass].name) : std::string("the graph");
}

void RenderGraph::addPass(std::string_view name, const std::function<void(PassBuilder&)>& setup,
                          std::function<void(PassContext&)> exec) {
    compiled_.reset();
    const auto index = static_cast<uint32_t>(passes_.size());
    PassNode node;
    node.name = std::string(name);
    node.exec = std::move(exec);
    node.extent = relativeExtent_;
    passes_.push_back(std::move(node));
    PassBuilder builder(*this, index);
    if (setup) setup(builder);
}

uint32_t RenderGraph::addResource(ResourceNode node, uint32_t pass) {
    compiled_.reset();
    for (const ResourceNode& existing : resources_) {
        if (existing.name == node.name) {
            error(strformat("render graph: {} declares resource '{}', but a resource of that name already exists",
                              passLabel(pass), node.name));
            break;
        }
    }
    resources_.push_back(std::move(node));
    return static_cast<uint32_t>(resources_.size() - 1);
}

TextureHandle RenderGraph::createTexture(std::string_view name, const TextureDesc& desc) {
    ResourceNode node;
    node.name = std::string(name);
    node.kind = ResourceKind::Image;
    node.origin = desc.persistent ? Origin::Persistent : Origin::Transient;
    node.textureDesc = desc;
    node.relativeTo = relativeExtent_;
    return {addResource(std::move(node), kInvalidId), 0};
}

BufferHandle RenderGraph::createBuffer(std::string_view name, const BufferDesc& desc) {
    ResourceNode node;
    node.name = std::string(name);
    node.kind = ResourceKind::Buffer;
    node.origin = desc.persistent ? Origin::Persistent : Origin::Transient;
    node.bufferDesc = desc;
    return {addResource(std::move(node), kInvalidId), 0};
}

TextureHandle RenderGraph::importTexture(std::string_view name, const PhysicalTexture& texture,
                                         const ResourceState& current, std::optional<FinalUse> finalUse) {
    ResourceNode node;
    node.name = std::string(name);
    node.kind = ResourceKind::Image;
    node.origin = Origin::Imported;
    node.importedTexture = texture;
    node.importedState = current;
    node.finalUse = finalUse;
    node.textureDesc.format = texture.format;
    if (finalUse && !accessInfo(finalUse->access, ResourceKind::Image).valid) {
        error(strformat("render graph: imported texture '{}' has final use {}, which is not valid for an image",
                          name, toString(finalUse->access)));
    }
    return {addResource(std::move(node), kInvalidId), 0};
}

BufferHandle RenderGraph::importBuffer(std::string_view name, const PhysicalBuffer& buffer,
                                       const ResourceState& current, std::optional<FinalUse> finalUse) {
    ResourceNode node;
    node.name = std::string(name);
    node.kind = ResourceKind::Buffer;
    node.origin = Origin::Imported;
    node.importedBuffer = buffer;
    node.importedState = current;
    node.finalUse = finalUse;
    node.bufferDesc.size = buffer.size;
    if (finalUse && !accessInfo(finalUse->access, ResourceKind::Buffer).valid) {
        error(strformat("render graph: imported buffer '{}' has final use {}, which is not valid for a buffer",
                          name, toString(finalUse->access)));
    }
    return {addResource(std::move(node), kInvalidId), 0};
}

uint32_t RenderGraph::historyResource(std::string_view persistentName, ResourceKind kind) {
    const std::string name = strformat("{}@history", persistentName);
    for (uint32_t i = 0; i < resources_.size(); ++i) {
        if (resources_[i].origin == Origin::History && resources_[i].name == name && resources_[i].kind == kind) {
            return i;   // history(name) twice in one frame: the same resource
        }
    }
    ResourceNode node;
    node.name = name;
    node.kind = kind;
    node.origin = Origin::History;
    node.persistentName = std::string(persistentName);
    return addResource(std::move(node), kInvalidId);
}

TextureHandle RenderGraph::history(std::string_view persistentName) {
    return {historyResource(persistentName, ResourceKind::Image), 0};
}

BufferHandle RenderGraph::historyBuffer(std::string_view persistentName) {
    return {historyResource(persistentName, ResourceKind::Buffer), 0};
}

uint32_t RenderGraph::declareUse(uint32_t pass, ResourceKind kind, uint32_t resource, uint32_t version,
                                 Access access, VkPipelineStageFlags2 stages, bool write) {
    compiled_.reset();
    const std::string who = passLabel(pass);
    if (resource >= resources_.size() || resources_[resource].kind != kind ||
        version >= resources_[resource].producers.size()) {
        error(strformat("render graph: {} uses an unknown {} handle (resource #{}, version {})", who,
                          kindWord(kind), static_cast<int64_t>(resource == kInvalidId ? -1 : resource), version));
        return kInvalidId;
    }
    ResourceNode& node = resources_[resource];
    const AccessInfo info = accessInfo(access, kind);
    const char* verb = write ? "writes" : "reads";
    if (!info.valid) {
        error(strformat("render graph: {} {} {} '{}' as {}, which is not valid for a {}", who, verb, kindWord(kind),
                          node.name, toString(access), toString(kind)));
        return kInvalidId;
    }
    if (access == Access::Present) {
        error(strformat("render graph: {} declares Present on '{}'; Present is only valid as the FinalUse of an "
                        "imported texture", who, node.name));
        return kInvalidId;
    }
    if (write != info.isWrite) {
        error(strformat("render graph: {} declares {} on '{}' with {}(); use {}()", who, toString(access),
                          node.name, write ? "write" : "read", info.isWrite ? "write" : "read"));
        return kInvalidId;
    }
    if (stages != VK_PIPELINE_STAGE_2_NONE && (stages & ~info.allowedStages) != 0) {
        error(strformat("render graph: {} names pipeline stages {} that {} cannot happen in (resource '{}')",
                          who, stageNames(stages & ~info.allowedStages), toString(access), node.name));
        return kInvalidId;
    }
    for (const PassUse& use : passes_[pass].uses) {
        if (use.resource == resource) {
            error(strformat("render graph: {} declares '{}' twice (one access per resource per pass; use a "
                              "combined access such as StorageReadWrite)", who, node.name));
            return kInvalidId;
        }
    }
    const auto latest = static_cast<uint32_t>(node.producers.size() - 1);
    if (!write) {
        if (version < latest) {
            error(strformat("render graph: {} reads '{}' version {}, but pass '{}' already overwrote it (version "
                              "{}): read the handle that write returned", who, node.name, version,
                              passes_[node.producers[version + 1]].name, version + 1));
            return kInvalidId;
        }
        if (version == 0 && (node.origin == Origin::Transient || node.origin == Origin::Persistent)) {
            error(strformat("render graph: {} reads '{}', but no pass writes it before (read of a never-written "
                              "resource)", who, node.name));
            return kInvalidId;
        }
    } else {
        if (version < latest) {
            error(strformat("render graph: {} writes '{}' version {}, but pass '{}' already wrote that version "
                              "(write conflict: two passes writing the same version)", who, node.name, version,
                              passes_[node.producers[version + 1]].name));
            return kInvalidId;
        }
        if (node.origin == Origin::History) {
            error(strformat("render graph: {} writes '{}', but history resources are read-only", who, node.name));
            return kInvalidId;
        }
    }
    passes_[pass].uses.push_back(PassUse{resource, version, access, stages, write});
    if (!write) return version;
    node.producers.push_back(pass);
    return version + 1;
}

void RenderGraph::markOutputVersion(ResourceKind kind, uint32_t resource, uint32_t version) {
    compiled_.reset();
    if (resource >= resources_.size() || resources_[resource].kind != kind ||
        version >= resources_[resource].producers.size()) {
        error(strformat("render graph: markOutput() got an unknown {} handle", kindWord(kind)));
        return;
    }
    resources_[resource].outputVersions.push_back(version);
}

void RenderGraph::markOutput(TextureHandle t) { markOutputVersion(ResourceKind::Image, t.resource, t.version); }
void RenderGraph::markOutput(BufferHandle b) { markOutputVersion(ResourceKind::Buffer, b.resource, b.version); }

// ---------------------------------------------------------------------------------------------------------
// Inspection

const detail::CompiledGraph& RenderGraph::compiled() const {
    if (!compiled_) throw GraphError("render graph: call compile() before inspecting the compiled graph");
    return *compiled_;
}

uint32_t RenderGraph::passIndex(std::string_view name) const {
    for (uint32_t i = 0; i < passes_.size(); ++i) {
        if (passes_[i].name == name) return i;
    }
    throw GraphError(strformat("render graph: no pass named '{}'", name));
}

uint32_t RenderGraph::checkedResource(uint32_t resource, ResourceKind kind, const char* what) const {
    if (resource >= resources_.size() || resources_[resource].kind != kind) {
        throw GraphError(strformat("render graph: {}() got an unknown {} handle", what, kindWord(kind)));
    }
    return resource;
}

std::vector<std::string> RenderGraph::executionOrder() const {
    std::vector<std::string> names;
    for (uint32_t pass : compiled().order) names.push_back(passes_[pass].name);
    return names;
}

bool RenderGraph::isCulled(std::string_view passName) const {
    return compiled().positionOf[passIndex(passName)] == kInvalidId;
}

std::span<const PlannedBarrier> RenderGraph::barriersBefore(std::string_view passName) const {
    const uint32_t position = compiled().positionOf[passIndex(passName)];
    if (position == kInvalidId) return {};
    return compiled().passes[position].barriers;
}

std::span<const PlannedBarrier> RenderGraph::prologueBarriers() const { return compiled().prologueBarriers; }
std::span<const PlannedBarrier> RenderGraph::finalBarriers() const { return compiled().finalBarriers; }
const AliasingPlan& RenderGraph::aliasingPlan() const { return compiled().aliasing; }

const AliasSlot* RenderGraph::aliasSlot(TextureHandle t) const {
    return compiled().aliasing.slotOf(checkedResource(t.resource, ResourceKind::Image, "aliasSlot"));
}
const AliasSlot* RenderGraph::aliasSlot(BufferHandle b) const {
    return compiled().aliasing.slotOf(checkedResource(b.resource, ResourceKind::Buffer, "aliasSlot"));
}
ResourceState RenderGraph::finalState(TextureHandle t) const {
    return compiled().resources[checkedResource(t.resource, ResourceKind::Image, "finalState")].final;
}
ResourceState RenderGraph::finalState(BufferHandle b) const {
    return compiled().resources[checkedResource(b.resource, ResourceKind::Buffer, "finalState")].final;
}
const TextureInfo& RenderGraph::textureInfo(TextureHandle t) const {
    return compiled().resources[checkedResource(t.resource, ResourceKind::Image, "textureInfo")].texture;
}
const BufferInfo& RenderGraph::bufferInfo(BufferHandle b) const {
    return compiled().resources[checkedResource(b.resource, ResourceKind::Buffer, "bufferInfo")].buffer;
}
bool RenderGraph::historyValid(uint32_t resource) const {
    return resource < resources_.size() && compiled().resources[resource].historyValid;
}
std::string_view RenderGraph::resourceName(uint32_t resource) const {
    return resource < resources_.size() ? std::string_view(resources_[resource].name) : std::string_view("?");
}

}  // namespace idk::graph
