// depth_pyramid.cpp: CPU Hi-Z pyramid and occlusion test (see depth_pyramid.hpp). Written as a direct reduction
// over each texel's covered pixels of the depth image (not level by level as the GPU does), so that it checks the
// GPU's level-to-level chaining instead of repeating it.
#include "render/depth_pyramid.hpp"

#include <algorithm>

namespace idk::render {

std::vector<float> buildDepthPyramid(const std::vector<float>& depth, glm::uvec2 size, DepthReduction reduction) {
    const bool farthest = reduction == DepthReduction::Farthest;
    const uint32_t levels = gpu::hizLevelCount(size);
    std::vector<float> out(gpu::hizLevelOffset(size, levels));
    for (uint32_t k = 0; k < levels; ++k) {
        const glm::uvec2 s = gpu::hizLevelSize(size, k);
        const uint32_t span = 2u << k, offset = gpu::hizLevelOffset(size, k);
        for (uint32_t y = 0; y < s.y; ++y)
            for (uint32_t x = 0; x < s.x; ++x) {
                float m = farthest ? 0.0f : 1.0f;
                for (uint32_t py = y * span; py < std::min((y + 1) * span, size.y); ++py)
                    for (uint32_t px = x * span; px < std::min((x + 1) * span, size.x); ++px) {
                        const float d = depth[size_t(py) * size.x + px];
                        m = farthest ? std::max(m, d) : std::min(m, d);
                    }
                out[offset + y * s.x + x] = m;
            }
    }
    return out;
}

bool hizBoxVisible(const std::vector<float>& pyramid, const gpu::GpuCullView& view, glm::vec3 center, glm::vec3 extent) {
    glm::vec4 rect;
    float nearest = 0.0f;
    if (!gpu::hizFootprint(view.viewProjection, center, extent, glm::vec2(view.viewport), rect, nearest)) return true;
    glm::uvec4 t;
    const uint32_t level = gpu::hizTexels(rect, view.viewport, t);
    const uint32_t offset = gpu::hizLevelOffset(view.viewport, level);
    const uint32_t width = gpu::hizLevelSize(view.viewport, level).x;
    const float farthest = std::max(std::max(pyramid[offset + t.y * width + t.x], pyramid[offset + t.y * width + t.z]),
                                    std::max(pyramid[offset + t.w * width + t.x], pyramid[offset + t.w * width + t.z]));
    return nearest <= farthest;
}

}  // namespace idk::render
