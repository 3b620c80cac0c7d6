// point_shadow_maps.hpp: the persistent resources of point-light cube shadows: one D32 cube per shadow-casting
// light (category "shadow maps"), the views each ladder rung renders through, a comparison sampler, and for the
// native rung the scene's draw commands with instanceCount * 6 (one instance per face). Nothing exists without a
// shadow-casting light. Ports IDKEngine's PointShadowManager / CpuPointShadow (reference 2.12).
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "graph/render_graph.hpp"
#include "render/gpu_scene.hpp"
#include "shared/shadow_types.h"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::render {

struct PointShadowSettings {
    uint32_t maxLights = 8;     // shadow-casting lights of any type at most (the first in light order); 0: none
    uint32_t resolution = 512;  // cube face size in texels
};

// The castsShadows rule: every light with nonzero intensity, in light order, at most maxLights.
std::vector<uint32_t> shadowCasters(const std::vector<gpu::GpuLight>& lights, uint32_t maxLights);
// Which of them render a cube: point lights, and spot lights too wide for one perspective map (the others render
// cascades or a spot map, render/light_shadow_maps.hpp).
bool castsIntoCube(const gpu::GpuLight& light);
std::vector<uint32_t> pointShadowCasters(const std::vector<gpu::GpuLight>& lights, uint32_t maxLights);

// Near and far planes of a light's cube faces: far = the largest major-axis distance from the light to a corner of
// the scene box (x 1.01), no farther than the light's range; near = far / 1000 (D32 keeps sub-millimetre depth
// steps at 1 m). Depth is stored as d = far / (far - near) * (1 - near / ma) of the major-axis distance ma.
glm::vec2 pointShadowPlanes(const gpu::GpuLight& light, const scene::Aabb& sceneBox);

struct PointShadowFrame {
    std::vector<graph::TextureHandle> cubes;    // imported, to be written by the point_shadows pass
    std::vector<gpu::GpuPointShadow> table;     // one per light
    std::vector<glm::vec2> planes;              // near/far per cube
    graph::BufferHandle casterDraws;            // imported own draw commands (native rung or BLEND casters;
                                                // invalid: the scene's draw buffer)
};

class PointShadowMaps {
public:
    // layered: the native rung of "point-shadow cube faces" (gl_Layer from the vertex shader, one instanced draw
    // per light); otherwise six draws per light, one per face view.
    PointShadowMaps(vk::Context& ctx, const GpuSceneData& scene, std::vector<uint32_t> casters, uint32_t resolution,
                    bool layered);
    ~PointShadowMaps();
    PointShadowMaps(const PointShadowMaps&) = delete;
    PointShadowMaps& operator=(const PointShadowMaps&) = delete;

    bool matches(const std::vector<uint32_t>& casters, uint32_t resolution, bool layered) const;
    bool layered() const noexcept { return layered_; }
    uint32_t resolution() const noexcept { return resolution_; }
    const std::vector<uint32_t>& casters() const noexcept { return casters_; }  // light index per cube
    const vk::Image& cube(uint32_t i) const { return cubes_.at(i).image; }
    VkImageView layeredView(uint32_t i) const { return cubes_.at(i).layeredView; }  // 2D array of the 6 faces
    VkImageView faceView(uint32_t i, uint32_t face) const { return cubes_.at(i).faceViews.at(face); }  // both rungs
    bool alphaMask() const noexcept { return alphaMask_; }  // MASK or BLEND: the pass needs its fragment shader
    // BLEND draws cast (by coverage): unculled cubes draw them from the maps' own commands (the scene's lack them).
    bool blendCasters() const noexcept { return blendCasters_; }

    // This frame: imports every cube into the graph (in the state the previous frame left it) and builds the
    // per-light table (kNoShadow for lights without a cube) from the lights' current positions.
    using Frame = PointShadowFrame;
    Frame beginFrame(graph::RenderGraph& graph, const std::vector<gpu::GpuLight>& lights);

private:
    void createCubes(vk::Context& ctx, const GpuSceneData& scene);  // the constructor's fallible part
    void release();
    struct Cube {
        vk::Image image;
        vk::SampledIndex sampled;
        VkImageView layeredView = VK_NULL_HANDLE;
        std::array<VkImageView, 6> faceViews{};
        bool rendered = false;  // a frame has written it: it is left in SHADER_READ_ONLY after its readers
    };
    vk::Context& ctx_;
    std::vector<uint32_t> casters_;
    uint32_t resolution_;
    bool layered_;
    bool alphaMask_;
    scene::Aabb sceneBox_;
    std::vector<Cube> cubes_;
    vk::SamplerIndex sampler_;
    bool blendCasters_ = false;
    vk::Buffer casterDraws_;  // render/shadow_caster_draws.hpp: x6 for the native rung; only these or BLEND
};

// Keeps `maps` in step with the frame's lights (the scene's plus any extra ones) and the settings: creates it,
// re-creates it when the casters, the resolution or the ladder's rung change, and releases it when no light casts.
// Returns whether shadows run.
bool updatePointShadowMaps(vk::Context& ctx, const GpuScene& scene, const std::vector<gpu::GpuLight>& lights,
                           const PointShadowSettings& settings, std::unique_ptr<PointShadowMaps>& maps);

}  // namespace idk::render
