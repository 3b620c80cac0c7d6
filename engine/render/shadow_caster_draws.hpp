// shadow_caster_draws.hpp: the draw commands of the shadow-map passes (point cubes, cascades, spot maps): the
// scene's multi-draw-indirect commands with the BLEND draws given back their instance (the scene's own buffer has
// instanceCount 0 for them, so the G-buffer skips them), so that BLEND surfaces cast shadows by coverage
// (shaders_glsl/include/shadow_caster.glsl: a stochastic alpha test, as the ray-traced rung's BLEND rule).
#pragma once
#include <volk.h>

#include <vector>

#include "render/gpu_scene.hpp"
#include "vk/resources.hpp"

namespace idk::render {

// scene.draws with each command's instanceCount = instancesPerDraw (6 for layered cubes: instance = face) for
// opaque, MASK and BLEND draws alike; commands with no triangles stay empty.
std::vector<VkDrawIndexedIndirectCommand> shadowCasterDraws(const GpuSceneData& scene, uint32_t instancesPerDraw);

// An indirect buffer of shadowCasterDraws(scene, instancesPerDraw); `name` labels it in memory reports.
vk::Buffer createShadowCasterDraws(vk::Context& ctx, const GpuSceneData& scene, uint32_t instancesPerDraw,
                                   const char* name);

}  // namespace idk::render
