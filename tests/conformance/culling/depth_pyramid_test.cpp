// depth_pyramid_test.cpp: the Hi-Z pyramid's layout (shared/depth_pyramid.h: level sizes halve with the ceiling
// down to one texel), and the screen footprint of a box is conservative on 100k random boxes: every point of the
// box projects inside the rectangle, no nearer than its nearest depth, and the chosen level's at most 2 x 2 texels
// cover every pixel of the rectangle. CPU only. The pyramid kernels on both rungs of "hiz-reduction" are the
// registered check "culling/hi-z pyramid" (engine/conformance/culling_checks.cpp).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <iostream>
#include <random>

#include "scene/camera.hpp"
#include "shared/depth_pyramid.h"

namespace idk::test {
namespace {

TEST(DepthPyramidLayout, LevelSizesHalveWithCeilingDownToOneTexel) {
    EXPECT_EQ(gpu::hizLevelCount({1, 1}), 1u);
    EXPECT_EQ(gpu::hizLevelCount({2, 2}), 1u);
    EXPECT_EQ(gpu::hizLevelCount({3, 1}), 2u);
    EXPECT_EQ(gpu::hizLevelCount({640, 360}), 10u);  // 320, 160, 80, 40, 20, 10, 5, 3, 2, 1 wide
    EXPECT_EQ(gpu::hizLevelSize({640, 360}, 0), glm::uvec2(320, 180));
    EXPECT_EQ(gpu::hizLevelSize({640, 360}, 7), glm::uvec2(3, 2));
    EXPECT_EQ(gpu::hizLevelSize({641, 361}, 0), glm::uvec2(321, 181));
}

// 100k random boxes, some straddling the near plane or behind the eye, seen by random perspective views.
TEST(HizFootprint, IsConservativeOnRandomBoxes) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(-30.0f, 30.0f), size(0.01f, 6.0f);
    const glm::uvec2 viewport(333, 187);
    uint32_t projected = 0, rejected = 0;
    for (int n = 0; n < 100000; ++n) {
        const glm::vec3 eye(pos(rng) * 0.2f, pos(rng) * 0.2f, pos(rng) * 0.2f);
        const glm::mat4 vp = scene::perspectiveVulkan(0.4f + 1.2f * (u(rng) * 0.5f + 0.5f), 16.0f / 9.0f, 0.1f,
                                                      n % 2 ? 0.0f : 200.0f) *
                             glm::lookAt(eye, eye + glm::vec3(u(rng), u(rng), u(rng) + 1e-3f), glm::vec3(0, 1, 0));
        const glm::vec3 center(pos(rng), pos(rng), pos(rng)), extent(size(rng), size(rng), size(rng));
        glm::vec4 rect;
        float nearest = 0.0f;
        if (!gpu::hizFootprint(vp, center, extent, glm::vec2(viewport), rect, nearest)) {
            ++rejected;
            continue;
        }
        ++projected;
        for (int k = 0; k < 16; ++k) {
            const glm::vec3 t = k < 8 ? glm::vec3((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1)
                                      : glm::vec3(u(rng), u(rng), u(rng));
            const glm::vec4 clip = vp * glm::vec4(center + t * extent, 1.0f);
            ASSERT_GT(clip.w, 0.0f) << "box " << n;
            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
            const glm::vec2 pixel = (glm::vec2(ndc) * 0.5f + 0.5f) * glm::vec2(viewport);
            // Interior points are convex combinations of the corners: inside up to float rounding.
            const float slack = 1e-4f * (1.0f + std::abs(pixel.x) + std::abs(pixel.y));
            ASSERT_GE(pixel.x, rect.x - slack) << "box " << n;
            ASSERT_GE(pixel.y, rect.y - slack) << "box " << n;
            ASSERT_LE(pixel.x, rect.z + slack) << "box " << n;
            ASSERT_LE(pixel.y, rect.w + slack) << "box " << n;
            ASSERT_GE(ndc.z, nearest - 1e-6f) << "box " << n;
        }
        // The texels cover every pixel of the (clamped) rectangle, at most 2 x 2 of them.
        glm::uvec4 texels;
        const uint32_t level = gpu::hizTexels(rect, viewport, texels);
        ASSERT_LT(level, gpu::hizLevelCount(viewport));
        const glm::uvec2 levelSize = gpu::hizLevelSize(viewport, level);
        ASSERT_LE(texels.z - texels.x, 1u);
        ASSERT_LE(texels.w - texels.y, 1u);
        ASSERT_LT(texels.z, levelSize.x);
        ASSERT_LT(texels.w, levelSize.y);
        const glm::vec2 hi = glm::vec2(viewport) - 1.0f;
        const glm::uvec2 p0(glm::clamp(glm::vec2(rect.x, rect.y), glm::vec2(0.0f), hi));
        const glm::uvec2 p1(glm::clamp(glm::vec2(rect.z, rect.w), glm::vec2(0.0f), hi));
        const uint32_t span = 2u << level;
        ASSERT_LE(texels.x * span, p0.x);
        ASSERT_LE(texels.y * span, p0.y);
        ASSERT_GE((texels.z + 1) * span, p1.x + 1);
        ASSERT_GE((texels.w + 1) * span, p1.y + 1);
    }
    std::cout << "[ footprint ] " << projected << " boxes projected, " << rejected << " cross the near plane\n";
    EXPECT_GT(projected, 20000u);
    EXPECT_GT(rejected, 5000u);
}

}  // namespace
}  // namespace idk::test
