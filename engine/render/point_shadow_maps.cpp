// point_shadow_maps.cpp: caster selection, cube planes, and the cube images, views, sampler and native-rung draw
// commands of point shadows; the per-frame import of the cubes into the render graph with their last state.
// Ports IDKEngine's PointShadowManager (cube per light, comparison sampler) and CpuPointShadow (face planes).
#include "render/point_shadow_maps.hpp"

#include <algorithm>
#include <string>

#include "render/blend_draws.hpp"
#include "render/draw_bounds.hpp"
#include "render/shadow_cascades.hpp"
#include "render/shadow_caster_draws.hpp"
#include "vk/check.hpp"
#include "vk/context.hpp"
#include "vk/features.hpp"
#include "vk/transfer.hpp"

namespace idk::render {

std::vector<uint32_t> shadowCasters(const std::vector<gpu::GpuLight>& lights, uint32_t maxLights) {
    std::vector<uint32_t> casters;
    for (uint32_t i = 0; i < lights.size() && casters.size() < maxLights; ++i)
        if (glm::any(glm::greaterThan(lights[i].intensity, glm::vec3(0.0f)))) casters.push_back(i);
    return casters;
}

bool castsIntoCube(const gpu::GpuLight& l) {
    return l.type == gpu::kLightPoint ||
           (l.type == gpu::kLightSpot && spotOuterAngle(l.spotScale, l.spotOffset) > kMaxSpotMapHalfAngle);
}

std::vector<uint32_t> pointShadowCasters(const std::vector<gpu::GpuLight>& lights, uint32_t maxLights) {
    std::vector<uint32_t> casters;
    for (uint32_t i : shadowCasters(lights, maxLights))
        if (castsIntoCube(lights[i])) casters.push_back(i);
    return casters;
}

glm::vec2 pointShadowPlanes(const gpu::GpuLight& light, const scene::Aabb& box) {
    float far = 0.0f;
    if (!box.empty()) {
        glm::vec3 d = glm::max(glm::abs(box.min - light.position), glm::abs(box.max - light.position));
        far = std::max({d.x, d.y, d.z}) * 1.01f;
    }
    if (light.range > 0.0f) far = std::min(far, light.range);
    far = std::max(far, 1e-3f);
    return {far * 1e-3f, far};
}

PointShadowMaps::PointShadowMaps(vk::Context& ctx, const GpuSceneData& scene, std::vector<uint32_t> casters,
                                 uint32_t resolution, bool layered)
    : ctx_(ctx), casters_(std::move(casters)), resolution_(resolution), layered_(layered),
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
        createCubes(ctx, scene);
    } catch (...) {  // a failed upload (device lost, out of memory): no destructor runs, so release here
        release();
        throw;
    }
}

void PointShadowMaps::createCubes(vk::Context& ctx, const GpuSceneData& scene) {
    const uint32_t resolution = resolution_;
    for (size_t c = 0; c < casters_.size(); ++c) {
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_D32_SFLOAT;
        desc.extent = {resolution, resolution, 1};
        desc.layers = 6;
        desc.cube = true;
        desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        desc.name = "point shadow cube " + std::to_string(c);
        desc.category = "shadow maps";
        Cube& cube = cubes_.emplace_back();  // in the list first, so release() frees what exists if a step throws
        cube.image = ctx.createImage(desc);
        cube.sampled = ctx.bindless().addSampled(cube.image.view);
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = cube.image.image;
        view.format = desc.format;
        if (layered_) {
            view.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
            view.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 6};
            vk::check(vkCreateImageView(ctx.device(), &view, nullptr, &cube.layeredView));
        }
        // Single-face views on both rungs: GPU culling draws each face's own culled commands into its view.
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        for (uint32_t f = 0; f < 6; ++f) {
            view.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, f, 1};
            vk::check(vkCreateImageView(ctx.device(), &view, nullptr, &cube.faceViews[f]));
        }
    }

    // Own draw commands where the scene's buffer will not do: six instances per draw on the native rung
    // (instance = face), and BLEND and transmissive draws, which the scene's buffer leaves without an instance (the
    // forward passes draw them), so they cast.
    blendCasters_ = blendDrawCount(scene) + blendDrawCount(scene, ForwardDraws::Transmission) > 0;
    if (!scene.draws.empty() && (layered_ || blendCasters_))
        casterDraws_ = createShadowCasterDraws(ctx, scene, layered_ ? 6u : 1u, "point shadow draw commands");
}

PointShadowMaps::~PointShadowMaps() { release(); }

void PointShadowMaps::release() {
    ctx_.bindless().release(sampler_);
    for (Cube& c : cubes_) {
        ctx_.bindless().release(c.sampled);
        std::vector<VkImageView> views(c.faceViews.begin(), c.faceViews.end());
        views.push_back(c.layeredView);
        VkDevice device = ctx_.device();
        ctx_.destroyDeferred([device, views] {
            for (VkImageView v : views)
                if (v != VK_NULL_HANDLE) vkDestroyImageView(device, v, nullptr);
        });
        ctx_.destroyDeferred(c.image);
    }
    if (casterDraws_) ctx_.destroyDeferred(casterDraws_);
}

bool PointShadowMaps::matches(const std::vector<uint32_t>& casters, uint32_t resolution, bool layered) const {
    return casters == casters_ && resolution == resolution_ && layered == layered_;
}

PointShadowMaps::Frame PointShadowMaps::beginFrame(graph::RenderGraph& graph,
                                                   const std::vector<gpu::GpuLight>& lights) {
    Frame frame;
    gpu::GpuPointShadow none{};
    none.cube = gpu::kNoShadow;
    frame.table.assign(lights.size(), none);
    // Left by the previous frame's readers (deferred lighting, transparency) as the final use below says.
    constexpr VkPipelineStageFlags2 kReaders =
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    const graph::FinalUse finalUse{graph::Access::SampledRead, kReaders};
    for (size_t c = 0; c < cubes_.size(); ++c) {
        Cube& cube = cubes_[c];
        graph::PhysicalTexture p;
        p.image = cube.image.image;
        p.view = cube.image.view;
        p.format = cube.image.format;
        p.extent = cube.image.extent;
        p.layers = 6;
        p.sampledIndex = cube.sampled.value;
        graph::ResourceState state;
        if (cube.rendered)
            state = graph::stateAfterAccess(graph::Access::SampledRead, graph::ResourceKind::Image, kReaders);
        cube.rendered = true;
        frame.cubes.push_back(graph.importTexture("point shadow cube " + std::to_string(c), p, state, finalUse));

        const uint32_t light = casters_[c];
        glm::vec2 planes = light < lights.size() ? pointShadowPlanes(lights[light], sceneBox_) : glm::vec2(1.0f);
        frame.planes.push_back(planes);
        if (light >= lights.size()) continue;
        gpu::GpuPointShadow& s = frame.table[light];
        s.position = lights[light].position;
        s.nearPlane = planes.x;
        s.farPlane = planes.y;
        s.cube = cube.sampled.value;
        s.samplerIndex = sampler_.value;
        s.texelScale = 2.0f / float(resolution_);
    }
    if (casterDraws_) {
        graph::PhysicalBuffer b;
        b.buffer = casterDraws_.buffer;
        b.size = casterDraws_.size;
        b.address = casterDraws_.address;
        frame.casterDraws = graph.importBuffer("point shadow draw commands", b, graph::ResourceState{});
    }
    return frame;
}

bool updatePointShadowMaps(vk::Context& ctx, const GpuScene& scene, const std::vector<gpu::GpuLight>& lights,
                           const PointShadowSettings& settings, std::unique_ptr<PointShadowMaps>& maps) {
    std::vector<uint32_t> casters = pointShadowCasters(lights, settings.maxLights);
    if (casters.empty() || scene.drawCount() == 0 || settings.resolution == 0) {
        maps.reset();
        return false;
    }
    bool layered = ctx.ladder("point-shadow cube faces").chosen == vk::Rung::Native;
    if (!maps || !maps->matches(casters, settings.resolution, layered)) {
        maps.reset();
        maps = std::make_unique<PointShadowMaps>(ctx, scene.data(), std::move(casters), settings.resolution, layered);
    }
    return true;
}

}  // namespace idk::render
