// depth_pyramid_levels.hpp: the compute rung's pyramid build with a chosen number of levels per dispatch
// (passes/depth_pyramid.cpp): recordDepthPyramid uses kHizTileLevels; 1 is the one-dispatch-per-level build that
// the benchmark and the conformance check compare it with (the same pyramid, bit for bit).
#pragma once
#include "passes/culling.hpp"

namespace idk::passes {

// `levelsPerDispatch` (1 .. gpu::kHizTileLevels) applies to HizReduction::Farthest (culling/hiz_build.comp.glsl);
// the Closest reduction is always one dispatch per level.
void recordDepthPyramidLevels(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders,
                              uint32_t depthStorage, glm::uvec2 size, VkDeviceAddress pyramid, HizReduction reduction,
                              uint32_t levelsPerDispatch);

}  // namespace idk::passes
