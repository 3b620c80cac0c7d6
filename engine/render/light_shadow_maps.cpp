// light_shadow_maps.cpp: caster selection, images and views of directional cascades and spot maps, and their
// per-frame projections and table records. See light_shadow_maps.hpp.
#include "render/light_shadow_maps.hpp"

#include <string>

#include "render/blend_draws.hpp"
#include "render/draw_bounds.hpp"
#include "render/point_shadow_maps.hpp"
#include "render/shadow_caster_draws.hpp"
#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::render {

std::vector<uint32_t> shadowMapCasters(const std::vector<gpu::GpuLight>& lights, uint32_t maxLights) {
    std::vector<uint32_t> casters;
    for (uint32_t i : shadowCasters(lights, maxLights))
        if (!castsIntoCube(lights[i])) casters.push_back(i);
    return casters;
}

LightShadowMaps::LightShadowMaps(vk::Context& ctx, const GpuSceneData& scene, std::vector<uint32_t> casters,
                                 std::vector<uint32_t> layers, uint32_t resolution)
    : ctx_(ctx), casters_(std::move(casters)), layers_(std::move(layers)), resolution_(resolution),
      alphaMask_(scene.features.hasMask || blendDrawCount(scene) > 0) {
    sceneBox_ = sceneBounds(scene, meshBounds(scene));
    vk::SamplerDesc sampler;
    sampler.filter = VK_FILTER_LINEAR;  // 2x2 comparison filtering
    sampler.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler.compare = true;
    sampler.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit where reference <= stored depth
    sampler_ = ctx.bindless().addSampler(sampler);
    try {
        createMaps(ctx);
        // BLEND and transmissive draws have no instance in the scene's buffer (the G-buffer skips them); these
        // commands give them one.
        if (!scene.draws.empty() && blendDrawCount(scene) + blendDrawCount(scene, ForwardDraws::Transmission) > 0)
            casterDraws_ = createShadowCasterDraws(ctx, scene, 1, "light shadow draw commands");
    } catch (...) {  // no destructor runs for a throwing constructor
        release();
        throw;
    }
}

void LightShadowMaps::createMaps(vk::Context& ctx) {
    for (size_t c = 0; c < casters_.size(); ++c) {
        Map& map = maps_.emplace_back();  // listed first, so release() frees what exists if a step throws
        map.layers = layers_[c];
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_D32_SFLOAT;
        desc.extent = {resolution_, resolution_, 1};
        desc.layers = map.layers;
        desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        desc.name = "light shadow map " + std::to_string(c);
        desc.category = "shadow maps";
        map.image = ctx.createImage(desc);
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = map.image.image;
        view.format = desc.format;
        // The shaders read every map as a texture2DArray; the image's own view is plain 2D when it has one layer.
        view.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
        view.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, map.layers};
        vk::check(vkCreateImageView(ctx.device(), &view, nullptr, &map.arrayView));
        map.sampled = ctx.bindless().addSampled(map.arrayView);
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        for (uint32_t l = 0; l < map.layers; ++l) {
            view.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, l, 1};
            vk::check(vkCreateImageView(ctx.device(), &view, nullptr, &map.layerViews.emplace_back()));
        }
    }
}

LightShadowMaps::~LightShadowMaps() { release(); }

void LightShadowMaps::release() {
    ctx_.bindless().release(sampler_);
    for (Map& m : maps_) {
        ctx_.bindless().release(m.sampled);
        std::vector<VkImageView> views = m.layerViews;
        views.push_back(m.arrayView);
        VkDevice device = ctx_.device();
        ctx_.destroyDeferred([device, views] {
            for (VkImageView v : views)
                if (v != VK_NULL_HANDLE) vkDestroyImageView(device, v, nullptr);
        });
        ctx_.destroyDeferred(m.image);
    }
    if (casterDraws_) ctx_.destroyDeferred(casterDraws_);
}

bool LightShadowMaps::matches(const std::vector<uint32_t>& casters, const std::vector<uint32_t>& layers,
                              uint32_t resolution) const {
    return casters == casters_ && layers == layers_ && resolution == resolution_;
}

LightShadowMaps::Frame LightShadowMaps::beginFrame(graph::RenderGraph& graph, const std::vector<gpu::GpuLight>& lights,
                                                   const scene::CameraView& camera, float aspect,
                                                   const LightShadowSettings& settings,
                                                   std::vector<gpu::GpuPointShadow>& table,
                                                   std::vector<gpu::GpuShadowMap>& records) {
    Frame frame;
    if (casterDraws_) {
        graph::PhysicalBuffer b;
        b.buffer = casterDraws_.buffer;
        b.size = casterDraws_.size;
        b.address = casterDraws_.address;
        frame.casterDraws = graph.importBuffer("light shadow draw commands", b, graph::ResourceState{});
    }
    constexpr VkPipelineStageFlags2 kReaders =
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    const graph::FinalUse finalUse{graph::Access::SampledRead, kReaders};
    for (size_t c = 0; c < maps_.size(); ++c) {
        Map& map = maps_[c];
        graph::PhysicalTexture p;
        p.image = map.image.image;
        p.view = map.arrayView;
        p.format = map.image.format;
        p.extent = map.image.extent;
        p.layers = map.layers;
        p.sampledIndex = map.sampled.value;
        graph::ResourceState state;
        if (map.rendered)
            state = graph::stateAfterAccess(graph::Access::SampledRead, graph::ResourceKind::Image, kReaders);
        map.rendered = true;
        frame.images.push_back(graph.importTexture("light shadow map " + std::to_string(c), p, state, finalUse));

        const uint32_t index = casters_[c];
        std::vector<ShadowProjection>& proj = frame.projections.emplace_back();
        if (index >= lights.size()) {  // cannot happen while matches() held; keeps the layers' count
            proj.resize(map.layers);
            continue;
        }
        const gpu::GpuLight& light = lights[index];
        if (light.type == gpu::kLightDirectional)
            proj = directionalCascades(camera, aspect, sceneBox_, light.direction, map.layers, resolution_,
                                       settings.distance);
        else
            proj = {spotShadowProjection(light.position, light.direction,
                                         spotOuterAngle(light.spotScale, light.spotOffset),
                                         pointShadowPlanes(light, sceneBox_), resolution_)};
        gpu::GpuPointShadow& entry = table[index];
        entry.position = light.position;
        entry.cube = map.sampled.value;
        entry.samplerIndex = sampler_.value;
        entry.mapOffset = uint32_t(lights.size() * sizeof(gpu::GpuPointShadow) +
                                   records.size() * sizeof(gpu::GpuShadowMap));
        entry.mapCount = uint32_t(proj.size());
        for (uint32_t l = 0; l < proj.size(); ++l) {
            gpu::GpuShadowMap r{};
            r.viewProjection = proj[l].viewProjection;
            r.texelScale = proj[l].texelScale;
            r.invResolution = 1.0f / float(resolution_);
            r.layer = l;
            r.perspective = proj[l].perspective ? 1u : 0u;
            records.push_back(r);
        }
    }
    return frame;
}

bool updateLightShadowMaps(vk::Context& ctx, const GpuScene& scene, const std::vector<gpu::GpuLight>& lights,
                           uint32_t maxLights, const LightShadowSettings& settings,
                           std::unique_ptr<LightShadowMaps>& maps) {
    std::vector<uint32_t> casters = shadowMapCasters(lights, maxLights);
    if (casters.empty() || scene.drawCount() == 0 || settings.resolution == 0) {
        maps.reset();
        return false;
    }
    std::vector<uint32_t> layers;
    for (uint32_t i : casters)
        layers.push_back(lights[i].type == gpu::kLightDirectional ? std::clamp(settings.cascades, 1u, 4u) : 1u);
    if (!maps || !maps->matches(casters, layers, settings.resolution)) {
        maps.reset();
        maps = std::make_unique<LightShadowMaps>(ctx, scene.data(), std::move(casters), std::move(layers),
                                                 settings.resolution);
    }
    return true;
}

}  // namespace idk::render
