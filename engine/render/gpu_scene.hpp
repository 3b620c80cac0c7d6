// gpu_scene.hpp: the scene packed for GPU-driven drawing: merged vertices/indices, one GpuMesh per glTF primitive,
// one GpuInstance + VkDrawIndexedIndirectCommand per drawn (node instance, primitive) pair (ONE multi-draw-indirect,
// gl_DrawID selecting the instance), materials with bindless texture slots (placeholders until textures stream in),
// punctual lights, optional COLOR_0/TEXCOORD_1 streams. Ports IDKEngine's ModelManager buffers (reference 1.7,
// 2.7); nothing is allocated that the scene lacks.
#pragma once
#include <volk.h>

#include <memory>
#include <optional>
#include <vector>

#include "render/gpu_animation.hpp"
#include "scene/scene.hpp"
#include "shared/scene_types.h"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::vk {
class Context;
}

namespace idk::render {

// Bindless indices the packer writes into material slots that have no texture (or whose texture has not
// arrived yet), and the sampler index of each scene texture (defaultSampler for slots without a texture).
struct TextureBindings {
    uint32_t white = 0;                     // 1x1 (1, 1, 1, 1)
    uint32_t flatNormal = 0;                // 1x1 (0.5, 0.5, 1): tangent-space +Z exactly
    uint32_t defaultSampler = 0;            // linear, repeat, no anisotropy
    std::vector<uint32_t> textureSamplers;  // per Scene::textures entry
};

// One material slot that samples a scene texture.
struct TextureSlotRef {
    uint32_t material = 0;
    uint32_t slot = 0;  // gpu::kSlot*
};

// The packed arrays (pure CPU data; unit-testable without a device).
struct GpuSceneData {
    std::vector<gpu::GpuVertex> vertices;
    std::vector<glm::vec4> colors;                    // COLOR_0 per vertex, only if some primitive has it
    std::vector<glm::vec2> uv1;                       // TEXCOORD_1 per vertex, only if some primitive has it
    std::vector<uint32_t> indices;                    // relative to each mesh's baseVertex
    std::vector<gpu::GpuMesh> meshes;                 // Scene mesh m, primitive p -> firstMesh[m] + p
    std::vector<gpu::GpuInstance> instances;          // one per draw, in draw order
    std::vector<VkDrawIndexedIndirectCommand> draws;  // draws[i] draws instances[i]
    std::vector<gpu::GpuMaterial> materials;          // Scene::materials, then glTF's default material
    std::vector<gpu::GpuLight> lights;
    std::vector<std::vector<TextureSlotRef>> textureUses;  // per Scene::textures entry
    scene::SceneFeatures features;                         // Scene::features() of the packed scene
    std::vector<uint32_t> drawInstance;                    // per draw: its Scene::instances index (poses)
    DeformationData deformation;  // skinned/morphed vertex copies and their jobs (gpu_animation.hpp)
};

GpuSceneData packGpuScene(const scene::Scene& scene, const TextureBindings& bindings);
// Whether a material's draws leave the G-buffer for a forward pass: BLEND (the transparency pass) or a lit
// KHR_materials_transmission material (the screen-space transmission pass, frame/transmission_feature.hpp).
inline bool drawnForward(const gpu::GpuMaterial& m) {
    return m.alphaMode == gpu::kAlphaBlend || (m.flags & gpu::kMaterialTransmission) != 0u;
}
// Whether a material is drawn by the transmission pass (transmissive and not BLEND: BLEND keeps the blend pass).
inline bool drawnByTransmission(const gpu::GpuMaterial& m) {
    return m.alphaMode != gpu::kAlphaBlend && (m.flags & gpu::kMaterialTransmission) != 0u;
}
// One draw's GpuInstance: `world` with its normal matrix and mirror flag, drawing GpuMesh `mesh`.
gpu::GpuInstance packInstance(const glm::mat4& world, uint32_t mesh);

// Sampler state of a glTF sampler (filters and wrap as glTF enums; wrapS decides both axes, see the .cpp).
vk::SamplerDesc samplerDesc(const scene::Sampler& sampler);

// What a GpuScene uploads. The path tracer traces its own geometry (render/pt_geometry.hpp) and reads only the
// materials with their bindless textures and samplers: MaterialsOnly leaves the vertex, index, mesh, instance,
// draw, light and optional-stream buffers null and creates no animation state.
enum class GpuSceneContents : uint8_t { Everything, MaterialsOnly };

class GpuScene {
public:
    GpuScene(vk::Context& ctx, const scene::Scene& scene, GpuSceneContents contents = GpuSceneContents::Everything);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    // Points every material slot that samples Scene::textures[sceneTextureIndex] at `texture` (for the async
    // texture streamer). Base-colour and emissive slots expect a view that decodes sRGB (see textureIsColor),
    // the others a UNORM view. The caller keeps the image alive while the scene uses it. The change reaches the
    // GPU at the next frame: the renderer adds a "scene_update" pass that copies the patched materials
    // (ordered by the render graph against the frame's and earlier frames' reads), so no frame stalls.
    // `sampler` replaces the slots' sampler (TextureStreamer's ReadyCallback passes one); without it the scene's
    // own deduplicated sampler for that texture stays. Throws std::out_of_range past Scene::textures.
    void setTexture(uint32_t sceneTextureIndex, vk::SampledIndex texture,
                    std::optional<vk::SamplerIndex> sampler = std::nullopt);
    bool textureIsColor(uint32_t sceneTextureIndex) const;  // used as base colour or emissive
    bool textureIsData(uint32_t sceneTextureIndex) const;   // used as metallic-roughness, normal or occlusion

    const scene::SceneFeatures& features() const noexcept { return data_.features; }
    uint32_t drawCount() const noexcept { return uint32_t(data_.draws.size()); }  // (instance, primitive) pairs
    uint32_t lightCount() const noexcept { return uint32_t(data_.lights.size()); }
    const std::vector<gpu::GpuMaterial>& materials() const noexcept { return data_.materials; }
    const GpuSceneData& data() const noexcept { return data_; }
    // Skinning, morphs and animated transforms (nullptr when the scene has no skins, morphs or animations).
    GpuAnimation* animation() noexcept { return animation_.get(); }

    // Buffers (absent ones are null: e.g. no light buffer without lights, nothing at all for an empty scene).
    const vk::Buffer& vertices() const noexcept { return vertices_; }
    const vk::Buffer& indices() const noexcept { return indices_; }
    const vk::Buffer& meshes() const noexcept { return meshes_; }
    const vk::Buffer& instances() const noexcept { return instances_; }
    const vk::Buffer& drawCommands() const noexcept { return draws_; }
    const vk::Buffer& materialBuffer() const noexcept { return materials_; }
    const vk::Buffer& lights() const noexcept { return lights_; }
    const vk::Buffer& colors() const noexcept { return colors_; }  // optional streams
    const vk::Buffer& uv1() const noexcept { return uv1_; }

    // Material upload bookkeeping for the renderer's scene_update pass.
    bool materialsDirty() const noexcept { return materialsDirty_; }
    void clearMaterialsDirty() noexcept { materialsDirty_ = false; }

private:
    void create(const scene::Scene& scene, GpuSceneContents contents);
    void release();  // every resource created so far (the destructor, and a constructor that throws)
    vk::Context& ctx_;
    GpuSceneData data_;
    vk::Image white_, flatNormal_;
    vk::SampledIndex whiteIndex_, flatNormalIndex_;
    std::vector<vk::SamplerIndex> samplers_;  // deduplicated; released with the scene
    vk::Buffer vertices_, indices_, meshes_, instances_, draws_, materials_, lights_, colors_, uv1_;
    bool materialsDirty_ = false;
    std::unique_ptr<GpuAnimation> animation_;  // after data_: it keeps a reference to it
};

}  // namespace idk::render
