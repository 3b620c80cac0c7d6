// depth_pyramid.hpp: the CPU reference of the Hi-Z depth pyramid (layout and convention in
// shared/depth_pyramid.h) and of the occlusion test that reads it; conformance tests and the culling oracle use it.
#pragma once
#include <vector>

#include "shared/culling_types.h"
#include "shared/depth_pyramid.h"

namespace idk::render {

// Which depth each texel keeps (depth 0 = near, 1 = far): the farthest (culling's Hi-Z) or the closest
// (SSR's pyramid) of the pixels it covers.
enum class DepthReduction { Farthest, Closest };

// Every level of the pyramid of a w x h depth image (row-major, top row first), as the GPU lays it out.
std::vector<float> buildDepthPyramid(const std::vector<float>& depth, glm::uvec2 size,
                                     DepthReduction reduction = DepthReduction::Farthest);

// The late phase's occlusion test of a world box against `pyramid` (of view.viewport's size).
bool hizBoxVisible(const std::vector<float>& pyramid, const gpu::GpuCullView& view, glm::vec3 center, glm::vec3 extent);

}  // namespace idk::render
