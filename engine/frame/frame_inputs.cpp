// frame_inputs.cpp: frame constants, the frame's light list and the GPU scene's buffers for one PBR frame (see
// frame_inputs.hpp).
#include "frame/frame_inputs.hpp"

#include <algorithm>
#include <string>

#include "pathtrace/albedo_integrator.hpp"
#include "render/gpu_animation.hpp"
#include "shared/deferred_types.h"
#include "vk/transfer.hpp"

namespace idk::frame {

graph::BufferHandle importBuffer(graph::RenderGraph& graph, const char* name, const vk::Buffer& buffer,
                                 const graph::ResourceState& state) {
    if (!buffer) return {};
    graph::PhysicalBuffer p;
    p.buffer = buffer.buffer;
    p.size = buffer.size;
    p.address = buffer.address;
    return graph.importBuffer(name, p, state);
}

FrameInputs::~FrameInputs() {
    for (vk::Buffer& b : frameConstants_) ctx_.destroy(b);
    if (albedoTables_) ctx_.destroy(albedoTables_);
    for (vk::Buffer& b : lightBuffers_)
        if (b) ctx_.destroy(b);
}

// The scene's light buffer, or with extra lights (the viewer's shot lights) this slot's host-visible copy of the
// combined list. Sets f.lights.
const vk::Buffer& FrameInputs::lightBuffer(FrameContext& f, render::GpuScene& scene) {
    if (extraLights_.empty()) {
        f.lights = &scene.data().lights;
        return scene.lights();
    }
    combinedLights_ = scene.data().lights;
    combinedLights_.insert(combinedLights_.end(), extraLights_.begin(), extraLights_.end());
    f.lights = &combinedLights_;
    if (lightBuffers_.size() < f.framesInFlight) lightBuffers_.resize(f.framesInFlight);
    vk::Buffer& buffer = lightBuffers_[f.slot];
    const VkDeviceSize bytes = combinedLights_.size() * sizeof(gpu::GpuLight);
    if (!buffer || buffer.size < bytes) {
        if (buffer) ctx_.destroyDeferred(buffer);
        vk::BufferDesc desc;
        desc.size = std::max<VkDeviceSize>(bytes, 64 * sizeof(gpu::GpuLight));
        desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        desc.memory = vk::MemoryUsage::Upload;
        desc.name = "frame lights " + std::to_string(f.slot);
        desc.category = "frame constants";
        buffer = ctx_.createBuffer(desc);
    }
    vk::uploadBuffer(ctx_, buffer, combinedLights_.data(), bytes);
    return buffer;
}

void FrameInputs::addPasses(FrameContext& f, render::GpuScene& s, const render::GpuEnvironment& env) {
    if (frameConstants_.empty()) {
        for (uint32_t i = 0; i < f.framesInFlight; ++i) {
            vk::BufferDesc desc;
            desc.size = sizeof(gpu::GpuFrame);
            desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
            desc.memory = vk::MemoryUsage::Upload;
            desc.name = "frame constants " + std::to_string(i);
            desc.category = "frame constants";
            frameConstants_.push_back(ctx_.createBuffer(desc));
        }
    }
    if (!albedoTables_) {  // static: written once (the upload waits for its copy) and only read after
        const std::vector<float> tables = pathtrace::albedoTableData();
        vk::BufferDesc desc;
        desc.size = tables.size() * sizeof(float);
        desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        desc.name = "albedo tables";
        desc.category = "frame constants";
        albedoTables_ = ctx_.createBuffer(desc);
        vk::uploadBuffer(ctx_, albedoTables_, tables.data(), desc.size);
    }
    // This frame's slot: the frame ring has waited until the GPU finished the slot's previous frame.
    const vk::Buffer& frameBuffer = frameConstants_[f.slot];
    const vk::Buffer& lights = lightBuffer(f, s);

    gpu::GpuFrame g{};
    g.viewProjection = f.viewProjection;
    g.inverseViewProjection = glm::inverse(f.viewProjection);
    g.cameraPosition = f.camera.position;
    g.albedoTables = albedoTables_.address;
    g.lightCount = uint32_t(f.lights->size());
    g.lights = lights ? lights.address : 0;
    g.extent = glm::uvec2(f.width, f.height);
    for (uint32_t k = 0; k < gpu::kShCoefficients; ++k)
        g.irradianceSh[k] = env.irradianceSh[k] * f.settings.environmentIntensity;
    g.environmentTexture = env.texture.value;
    g.environmentSampler = env.sampler.value;
    g.environmentMaxLod = env.maxLod;
    g.environmentIntensity = f.settings.environmentIntensity;
    g.environmentWidth = env.width;
    g.environmentHeight = env.height;
    vk::uploadBuffer(ctx_, frameBuffer, &g, sizeof(g));  // host-visible: a memcpy, read by this frame's passes
    f.frameConstants = importBuffer(f.graph, "frame constants", frameBuffer);

    // Scene buffers: written once at load (their upload ends with a full barrier), except the materials, which
    // scene_update may overwrite: that write must wait for earlier frames' G-buffer reads (WAR).
    passes::SceneBuffers& sb = f.scene;
    const auto readByGBuffer = graph::stateAfterAccess(
        graph::Access::StorageRead, graph::ResourceKind::Buffer,
        VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    // Vertices and instances are rewritten by skinning / pose_upload in animated frames: WAR as for materials.
    sb.vertices = importBuffer(f.graph, "scene vertices", s.vertices(), readByGBuffer);
    sb.indices = importBuffer(f.graph, "scene indices", s.indices());
    sb.meshes = importBuffer(f.graph, "scene meshes", s.meshes());
    sb.instances = importBuffer(f.graph, "scene instances", s.instances(), readByGBuffer);
    sb.drawCommands = importBuffer(f.graph, "scene draw commands", s.drawCommands());
    // The deferred lighting pass (compute) reads the materials too: the factors of the BSDF extensions.
    const auto readByGBufferAndLighting = graph::stateAfterAccess(
        graph::Access::StorageRead, graph::ResourceKind::Buffer,
        VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    sb.materials = importBuffer(f.graph, "scene materials", s.materialBuffer(), readByGBufferAndLighting);
    sb.lights = importBuffer(f.graph, "scene lights", lights);
    sb.colors = importBuffer(f.graph, "scene vertex colors", s.colors());
    sb.uv1 = importBuffer(f.graph, "scene uv1", s.uv1());
    sb.drawCount = s.drawCount();
    // The G-buffer's layers target carries the extension textures' texels and the anisotropy direction
    // (include/gbuffer_anisotropy.glsl): allocated for scenes with either, no others.
    sb.layerTexels = s.features().hasLayerTextures ||
                     std::any_of(s.materials().begin(), s.materials().end(), [](const gpu::GpuMaterial& m) {
                         return (m.flags & gpu::kMaterialAnisotropy) != 0u;
                     });
    // Its spill target only for scenes with a material whose texels exceed the first target's bits.
    sb.layerSpill = sb.layerTexels && s.features().hasSpilledLayerTexels;
    if (s.materialsDirty() && sb.materials.valid()) {
        sb.materials = passes::addSceneUpdatePass(f.graph, sb.materials, s.materials());
        s.clearMaterialsDirty();
    }
    if (render::GpuAnimation* animation = s.animation())
        animation->addPasses(f.graph, f.shaders, f.slot, f.framesInFlight, sb);
}

}  // namespace idk::frame
