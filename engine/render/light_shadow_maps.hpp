// light_shadow_maps.hpp: the persistent resources of directional-light cascades and spot-light maps: one D32
// 2D-array image per such shadow-casting light (category "shadow maps"; a layer per cascade, one layer for a
// spot), a sampled 2D-array view, one render view per layer and a comparison sampler. Nothing exists without such
// a light. Per frame it fits the projections (render/shadow_cascades.hpp) to the camera and the lights.
#pragma once
#include <memory>
#include <vector>

#include "graph/render_graph.hpp"
#include "render/gpu_scene.hpp"
#include "render/shadow_cascades.hpp"
#include "shared/shadow_types.h"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::render {

struct LightShadowSettings {
    uint32_t cascades = 4;      // per directional light, 1..4
    uint32_t resolution = 1024; // cascade / spot map size in texels
    float distance = 0.0f;      // view distance the cascades cover (0: up to the far end of the scene)
    bool rayTraced = false;     // `--shadows raytraced`: every shadow ray traced (frame/rt_shadow_feature.hpp), no maps
    float lightRadius = 0.0f;   // raytraced: point and spot lights are spheres of this radius (m), soft shadows
    uint32_t softShadowRays = 16;  // raytraced with a radius: rays per pixel and light, sampled over the sphere
};

// Among the first maxLights shadow casters (render/point_shadow_maps.hpp shadowCasters): directional lights and
// spot lights narrow enough for one perspective map.
std::vector<uint32_t> shadowMapCasters(const std::vector<gpu::GpuLight>& lights, uint32_t maxLights);

struct LightShadowFrame {
    std::vector<graph::TextureHandle> images;                // to be written by the light_shadow_maps pass
    std::vector<std::vector<ShadowProjection>> projections;  // per image, per layer
    graph::BufferHandle casterDraws;  // imported draw commands with BLEND casters (invalid: the scene's buffer)
};

class LightShadowMaps {
public:
    // layers[i]: the cascade count of caster i (directional) or 1 (spot).
    LightShadowMaps(vk::Context& ctx, const GpuSceneData& scene, std::vector<uint32_t> casters,
                    std::vector<uint32_t> layers, uint32_t resolution);
    ~LightShadowMaps();
    LightShadowMaps(const LightShadowMaps&) = delete;
    LightShadowMaps& operator=(const LightShadowMaps&) = delete;

    bool matches(const std::vector<uint32_t>& casters, const std::vector<uint32_t>& layers, uint32_t resolution) const;
    uint32_t resolution() const noexcept { return resolution_; }
    const std::vector<uint32_t>& casters() const noexcept { return casters_; }  // light index per image
    uint32_t layers(uint32_t i) const { return maps_.at(i).layers; }
    const vk::Image& image(uint32_t i) const { return maps_.at(i).image; }
    VkImageView layerView(uint32_t i, uint32_t layer) const { return maps_.at(i).layerViews.at(layer); }
    bool alphaMask() const noexcept { return alphaMask_; }  // MASK or BLEND: the pass needs its fragment shader
    const scene::Aabb& sceneBox() const noexcept { return sceneBox_; }

    // This frame: imports the images (in the state the previous frame left them), fits every layer's projection,
    // points the lights' table entries at their records and appends the records.
    using Frame = LightShadowFrame;
    Frame beginFrame(graph::RenderGraph& graph, const std::vector<gpu::GpuLight>& lights,
                     const scene::CameraView& camera, float aspect, const LightShadowSettings& settings,
                     std::vector<gpu::GpuPointShadow>& table, std::vector<gpu::GpuShadowMap>& records);

private:
    void createMaps(vk::Context& ctx);
    void release();
    struct Map {
        vk::Image image;
        uint32_t layers = 1;
        VkImageView arrayView = VK_NULL_HANDLE;  // sampled as texture2DArray even with one layer
        vk::SampledIndex sampled;
        std::vector<VkImageView> layerViews;      // depth attachments
        bool rendered = false;
    };
    vk::Context& ctx_;
    std::vector<uint32_t> casters_, layers_;
    uint32_t resolution_;
    bool alphaMask_;
    scene::Aabb sceneBox_;
    std::vector<Map> maps_;
    vk::SamplerIndex sampler_;
    vk::Buffer casterDraws_;  // render/shadow_caster_draws.hpp, only for scenes with BLEND draws
};

// Keeps `maps` in step with the frame's lights and settings (created, re-created on a change of casters, cascade
// count or resolution, released when no light needs one). Returns whether the maps run this frame.
bool updateLightShadowMaps(vk::Context& ctx, const GpuScene& scene, const std::vector<gpu::GpuLight>& lights,
                           uint32_t maxLights, const LightShadowSettings& settings,
                           std::unique_ptr<LightShadowMaps>& maps);

}  // namespace idk::render
