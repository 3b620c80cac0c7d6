// passes.hpp: every pass is a free function in its own file that declares its resources to the render graph
// and records its work; this header lists them with their settings and outputs.
#pragma once
#include <glm/glm.hpp>

#include <array>

#include <string>
#include <string_view>
#include <vector>

#include "graph/render_graph.hpp"
#include "render/lambert_scene.hpp"
#include "shared/scene_types.h"
#include "shared/skinning_types.h"
#include "shared/volumetric_types.h"
#include "vk/resources.hpp"
#include "vk/shader_library.hpp"

namespace idk::render {
class PointShadowMaps;
struct PointShadowFrame;
class LightShadowMaps;
struct LightShadowFrame;
}

namespace idk::passes {

// lambert.cpp: the foundation's minimal rasterizer (Lambert diffuse + emission + point lights).
struct LambertSettings {
    glm::mat4 viewProjection{1.0f};
    glm::vec3 ambient{0.03f};
    glm::vec4 clearColor{0.0f, 0.0f, 0.0f, 1.0f};
    VkFormat colorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // the target's format (pipelines are built per format)
};
struct LambertOutputs {
    graph::TextureHandle color;  // the written version of the target
    graph::TextureHandle depth;  // transient D32
};
LambertOutputs addLambertPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                              const render::GpuLambertScene& scene, graph::TextureHandle target,
                              const LambertSettings& settings);

// ---- The deferred PBR frame: [scene_update] -> gbuffer -> deferred_lighting -> sky -> tonemap ----

// Counts the indirect draw calls passes record (tests assert one multi-draw-indirect per pass and its draw
// count; `idk render --stats` prints them). Filled while the graph executes.
struct IndirectDrawLog {
    struct Entry {
        std::string pass;
        uint32_t calls = 0;  // vkCmdDrawIndexedIndirect calls
        uint32_t draws = 0;  // sum of their drawCount
    };
    std::vector<Entry> entries;
    void record(std::string_view pass, uint32_t drawCount);
};

// The GPU scene's buffers as imported into this frame's graph (render::GpuScene); invalid handles for
// buffers the scene does not have.
struct SceneBuffers {
    graph::BufferHandle vertices, indices, meshes, instances, drawCommands, materials, lights;
    graph::BufferHandle colors, uv1;  // optional vertex streams
    uint32_t drawCount = 0;
    // The G-buffer adds its layers target: scene::SceneFeatures::hasLayerTextures, or an anisotropic material
    // (frame/frame_inputs.cpp).
    bool layerTexels = false;
    // ... and its spill target (RG32UI): scene::SceneFeatures::hasSpilledLayerTexels (implies layerTexels).
    bool layerSpill = false;
};

// scene_reads.cpp: what a draw over the scene's meshes reads (G-buffer, transparency, transmission, voxelization):
// the vertices and the optional colour and second-UV streams in the geometry stages (the vertex shader, or the task
// and mesh shaders of a mesh-shader draw), the indices, the instances there and in the fragment shader, the meshes
// and materials in the fragment shader (material textures, alpha test).
void readSceneMeshes(graph::PassBuilder& b, const SceneBuffers& s,
                     VkPipelineStageFlags2 geometryStages = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT);

// The same buffers' device addresses in a draw's push block (0 for an absent optional stream). `materials` false
// leaves the meshes and materials at 0: depth-only shadow draws of scenes without alpha-tested materials.
template <class Push>
void setSceneAddresses(Push& push, graph::PassContext& pc, const SceneBuffers& s, bool materials = true) {
    push.vertices = pc.buffer(s.vertices).address;
    push.instances = pc.buffer(s.instances).address;
    push.meshes = materials ? pc.buffer(s.meshes).address : 0;
    push.materials = materials ? pc.buffer(s.materials).address : 0;
    push.colors = s.colors.valid() ? pc.buffer(s.colors).address : 0;
    push.uv1 = s.uv1.valid() ? pc.buffer(s.uv1).address : 0;
}

// scene_update.cpp: copies patched materials (GpuScene::setTexture) into the material buffer; returns the
// buffer's new version. Added only on frames where something changed.
graph::BufferHandle addSceneUpdatePass(graph::RenderGraph& graph, graph::BufferHandle materials,
                                       std::vector<gpu::GpuMaterial> contents);

// skinning.cpp: animation on the GPU for one frame (render/gpu_animation.hpp fills this only when the pose
// changed): "pose_upload" copies the pose's instance transforms into scene.instances; "skinning" morphs and skins
// every deformed vertex copy in scene.vertices (shared/skinning_types.h). Both handles become the written versions.
struct AnimationFrame {
    static constexpr VkDeviceSize kAbsent = ~VkDeviceSize(0);
    const vk::Buffer* pose = nullptr;  // this frame slot's host-visible [instances | joint matrices | weights]
    VkDeviceSize instanceBytes = 0;    // pose_upload copies these bytes; 0: no pose_upload this frame
    VkDeviceSize jointsOffset = kAbsent, weightsOffset = kAbsent;  // in `pose`
    bool deform = false;                                           // run skinning this frame
    const vk::Buffer *jobs = nullptr, *influences = nullptr, *deltas = nullptr;  // static; empty ones unused
    uint32_t jobCount = 0, threadCount = 0;
};
void addAnimationPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                        const AnimationFrame& frame, SceneBuffers& scene);

// gbuffer.cpp: one vkCmdDrawIndexedIndirect over every (instance, primitive) of the scene.
// Read with imageLoad (storage), not sampled: see shared/deferred_types.h.
struct GBufferOutputs {
    graph::TextureHandle albedo;    // RGBA8, sRGB-encoded base colour + alpha
    graph::TextureHandle normal;    // R32UI, octahedral world normal (packSnorm2x16)
    graph::TextureHandle material;  // RGBA8 metallic, roughness, occlusion, lit
    graph::TextureHandle emissive;  // RGBA16F
    graph::TextureHandle depth;     // R32F copy of the depth, 0 near .. 1 far (cleared to 1)
    graph::TextureHandle depthAttachment;  // D32 (transient, not stored)
    graph::TextureHandle ids;  // RG32UI (draw, triangle) of each kept fragment, ~0u background (only when asked)
    // RGBA32UI texels of the KHR_materials_specular / _clearcoat / _sheen textures and the KHR_materials_anisotropy
    // direction (include/gbuffer_fragment.glsl packs them), only when SceneBuffers::layerTexels.
    graph::TextureHandle layers;
    // RG32UI texels the layers target has no bits for in materials that combine extensions (diffuse transmission,
    // anisotropy direction: include/gbuffer_layer_bits.glsl), only when SceneBuffers::layerSpill.
    graph::TextureHandle layerSpill;
};
// `culled` (passes/culling.hpp, optional): draw the culling pass's compacted commands with
// vkCmdDrawIndexedIndirectCount instead of every scene draw. `drawOver` (optional, with `culled`): load and keep
// drawing into these targets (the late phase of occlusion culling) instead of clearing new ones.
struct CulledDraws;
struct ShadowCulledDraws;  // passes/culling.hpp
GBufferOutputs addGBufferPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                              const SceneBuffers& scene, graph::BufferHandle frame, IndirectDrawLog* log,
                              const CulledDraws* culled = nullptr, const GBufferOutputs* drawOver = nullptr,
                              graph::TextureHandle ids = {});
// `ids` (optional, only without `culled`): also write the surface-ID buffer GBufferOutputs::ids into this RG32UI
// colour attachment (gbuffer_ids.frag; needs the geometryShader feature for gl_PrimitiveID).

// point_shadows.cpp: one depth cube per cube-casting light (render/point_shadow_maps.hpp), one instanced indirect
// draw per light (native rung) or six (fallback). light_shadow_maps.cpp: every cascade / spot-map layer, and the
// upload of the frame's shadow table (per-light GpuPointShadow entries, then the GpuShadowMap records).
struct PointShadowOutputs {
    graph::BufferHandle table;                // the shadow table; invalid: no shadows this frame
    std::vector<graph::TextureHandle> cubes;  // every written cube and map (readers declare SampledRead on each)
    graph::BufferHandle mask;                 // ray-traced shadows: the visibility mask the table points at
};
std::vector<graph::TextureHandle> addPointShadowPass(graph::RenderGraph& graph, vk::Context& ctx,
                                                     vk::ShaderLibrary& shaders, const SceneBuffers& scene,
                                                     const render::PointShadowMaps& maps,
                                                     const render::PointShadowFrame& frame, IndirectDrawLog* log,
                                                     const ShadowCulledDraws* culled = nullptr);
std::vector<graph::TextureHandle> addLightShadowMapPass(graph::RenderGraph& graph, vk::Context& ctx,
                                                        vk::ShaderLibrary& shaders, const SceneBuffers& scene,
                                                        const render::LightShadowMaps& maps,
                                                        const render::LightShadowFrame& frame, IndirectDrawLog* log);
graph::BufferHandle addShadowTablePass(graph::RenderGraph& graph, std::vector<uint8_t> bytes);

// rt_shadows.cpp: one shadow ray per pixel and light into a visibility mask (ray query or our BVH), and the table
// pointing the lighting at it.
struct RtShadowInputs {
    graph::BufferHandle frame, lights;
    graph::TextureHandle depth, normal;  // GBufferOutputs
    VkDeviceAddress sceneDesc = 0;       // GpuPtSceneDesc
    bool rayQuery = false, hasAlpha = false;
    uint32_t blasStack = 1, tlasStack = 1;
    std::vector<uint32_t> casters;       // light indices, at most kRtShadowMaxLights
    uint32_t lightCount = 0;
    float lightRadius = 0.0f;            // > 0: soft shadows of sphere lights, softRays rays per pixel and light
    uint32_t softRays = 1;
};
PointShadowOutputs addRtShadowPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                     const RtShadowInputs& inputs, uint32_t width, uint32_t height);

// volumetrics.cpp: in-scattering ray-marched at 1/scale resolution, composited into `hdr` (hdr * T + L) by a
// depth-aware upsample; returns the HDR image's new version.
struct VolumetricInputs {
    graph::BufferHandle frame, lights;
    graph::TextureHandle depth;  // GBufferOutputs::depth
    PointShadowOutputs shadows;  // the frame's shadow table and maps (may be empty)
    uint32_t width = 0, height = 0;
    gpu::VolumetricPush push{};  // the medium, steps, scale and maxDistance (addresses and indices filled in)
};
graph::TextureHandle addVolumetricPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const VolumetricInputs& inputs, graph::TextureHandle hdr);

// Traced indirect light per pixel (VXGI, passes/vxgi_passes.hpp): invalid handles when GI is off.
struct IndirectLightImages {
    graph::TextureHandle diffuse, specular;
};

// The deferred lighting pass's optional inputs, one per feature that feeds it (invalid handles: that feature is off).
struct LightingInputs {
    PointShadowOutputs shadows;             // point-light cube shadows (point_shadows.cpp)
    graph::BufferHandle materials;          // the BSDF extensions' factors (include/material_layers.glsl)
    graph::BufferHandle vrsRates;           // software VRS: shade cell anchors only (vrs_passes.hpp)
    graph::TextureHandle ambientOcclusion;  // SSAO visibility of the ambient light (ssao.hpp)
    IndirectLightImages indirect;           // VXGI cone-traced light (vxgi_passes.hpp)
    graph::TextureHandle reflections;       // SSR reflected radiance + hit weight (ssr.hpp)
};

// deferred_lighting.cpp: shades the G-buffer's geometry pixels into `target` (RGBA16F); returns its new version.
graph::TextureHandle addDeferredLightingPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                             const GBufferOutputs& gbuffer, graph::BufferHandle frame,
                                             graph::BufferHandle lights, graph::TextureHandle environment,
                                             graph::TextureHandle target, const LightingInputs& in = {});

// sky.cpp: writes the environment into the background pixels of `target` (depth == 1); returns its new version.
graph::TextureHandle addSkyPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                graph::TextureHandle depth, graph::BufferHandle frame, graph::TextureHandle environment,
                                graph::TextureHandle target, graph::BufferHandle vrsRates = {});

// transparency.cpp: BLEND draws back to front (render/blend_draws.hpp), forward-shaded and "over"-blended into
// the HDR `target` after sky, depth-tested against the G-buffer depth; returns the target's new version.
// --gi vxgi in the forward pass: the cone parameters' buffer (one gpu::VxgiConeParams, written by
// frame/vxgi_feature.cpp) and the directional volumes its cones sample; `params` invalid: GI off (the SH ambient).
// VXGI's six directional volumes as the graph sees them: [0..5] their colour images (+x -x +y -y +z -z), [6..11]
// their opacity images (invalid handles on the RGBA16F rung of "vxgi-volume-format", where the colour image holds
// the coverage too: frame/voxel_volume.hpp). Passes declare the valid ones.
inline constexpr uint32_t kVxgiDirectionImages = 12;
using VxgiDirectionHandles = std::array<graph::TextureHandle, kVxgiDirectionImages>;
// Bindless indices of the same twelve (views of one level, or the sampled views): an opacity index equal to its
// colour index means one RGBA16F image holds both (include/voxel_images.glsl).
using VxgiDirectionIndices = std::array<uint32_t, kVxgiDirectionImages>;

struct ForwardVxgiInputs {
    graph::BufferHandle params;
    uint32_t paramsIndex = 0xFFFFFFFFu;  // its bindless storage-buffer index
    VxgiDirectionHandles volumes;
    // The grid itself: the cones do not sample it, but a draw that uses the bindless 3D array counts for the
    // synchronization validation layer as reading every 3D image in it, so its next write must wait for this pass.
    graph::TextureHandle grid;
};

struct TransparencyInputs {
    SceneBuffers scene;
    graph::BufferHandle sortedDraws;  // the frame's back-to-front commands (firstInstance = instance)
    uint32_t drawCount = 0;
    graph::BufferHandle frame;
    graph::TextureHandle depth;        // GBufferOutputs::depth
    graph::TextureHandle environment;
    PointShadowOutputs shadows;
    ForwardVxgiInputs vxgi;
};
graph::TextureHandle addTransparencyPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const TransparencyInputs& inputs, graph::TextureHandle target,
                                         IndirectDrawLog* log);
// oit_weighted.cpp: the weighted blended OIT rung (`--oit weighted`): the same draws in any order into additive
// targets, composited over `target`; returns its new version.
graph::TextureHandle addWeightedOitPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                          const TransparencyInputs& inputs, graph::TextureHandle target,
                                          IndirectDrawLog* log);
// oit_layers.cpp: the fixed-layer OIT rung (`--oit layers`): the 10 nearest fragments per pixel (atomic insertion),
// composited in order over `target`; returns its new version.
graph::TextureHandle addLayeredOitPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const TransparencyInputs& inputs, graph::TextureHandle target,
                                         IndirectDrawLog* log);

// transmission.cpp: the screen-space transmission pass: `inputs` holds the transmissive draws; with `screen`, the lit
// `target` (of `extent` pixels) is first copied into a chain of halved levels (transmission/downsample.comp) that the forward pass reads
// behind each surface; without it (`--transmission off`) the surfaces are drawn opaque. Returns target's new version.
graph::TextureHandle addTransmissionPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                           const TransparencyInputs& inputs, graph::TextureHandle target,
                                           VkExtent2D extent, bool screen, IndirectDrawLog* log);

// tonemap.cpp: AgX of exposure * hdr into the RGBA8 `target` (sRGB-encoded values); returns its new version.
graph::TextureHandle addTonemapPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    graph::TextureHandle hdr, graph::TextureHandle target, float exposure);

}  // namespace idk::passes
